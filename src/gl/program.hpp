#pragma once
// Small RAII pieces of OpenGL 4.5: a compiled program (compute, or vertex + fragment) with typed
// uniform setters and a storage buffer. A GL context must be current (gl::Context).

#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

#include <cstddef>
#include <string>

namespace stochtex::gl {

// Throws stochtex::Error(numerical) naming `step` when the GL error flag is set.
void check_gl(const char* step);

class Program {
 public:
  // Compiles and links one compute shader; throws stochtex::Error with the compiler's log.
  explicit Program(const std::string& source);
  // Compiles and links a vertex and a fragment shader (drawing), likewise.
  Program(const std::string& vertex, const std::string& fragment);
  ~Program();
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;

  GLint location(const char* name) const { return glGetUniformLocation(id_, name); }
  void set(const char* name, int value) const { glProgramUniform1i(id_, location(name), value); }
  void set(const char* name, unsigned value) const {
    glProgramUniform1ui(id_, location(name), value);
  }
  void set(const char* name, float value) const { glProgramUniform1f(id_, location(name), value); }
  void set2(const char* name, int x, int y) const { glProgramUniform2i(id_, location(name), x, y); }
  void set2(const char* name, unsigned x, unsigned y) const {
    glProgramUniform2ui(id_, location(name), x, y);
  }
  void set2(const char* name, float x, float y) const {
    glProgramUniform2f(id_, location(name), x, y);
  }
  GLuint id() const { return id_; }

 private:
  GLuint id_ = 0;
};

// A shader storage buffer of `bytes` bytes: filled with `data` (model data), or left for results
// read back to the CPU when `data` is null.
class Buffer {
 public:
  explicit Buffer(std::size_t bytes, const void* data = nullptr);
  ~Buffer();
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  GLuint id() const { return id_; }

 private:
  GLuint id_ = 0;
};

}  // namespace stochtex::gl
