#include "gl/program.hpp"

#include <algorithm>

#include "stochtex/error.hpp"

namespace stochtex::gl {
namespace {

[[noreturn]] void gl_failure(const std::string& what) {
  throw Error(ErrorCode::numerical, "the OpenGL backend failed: " + what +
                                        "; use --backend cpu, and report this with `stochtex "
                                        "render --backend gl` and your driver");
}

}  // namespace

void check_gl(const char* step) {
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
    gl_failure(std::string(step) + " (GL error " + std::to_string(error) + ")");
}

Program::Program(const std::string& source) {
  const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    std::string log(4096, '\0');
    glGetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
    glDeleteShader(shader);
    gl_failure("the compute shader does not compile: " + std::string(log.c_str()));
  }
  id_ = glCreateProgram();
  glAttachShader(id_, shader);
  glLinkProgram(id_);
  glDeleteShader(shader);
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (!ok) {
    glDeleteProgram(id_);
    gl_failure("the compute shader does not link");
  }
}

Program::~Program() {
  glDeleteProgram(id_);
}

Buffer::Buffer(std::size_t bytes, const void* data) {
  glCreateBuffers(1, &id_);
  glNamedBufferData(id_, static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, 4)), data,
                    data ? GL_STATIC_DRAW : GL_DYNAMIC_READ);
}

Buffer::~Buffer() {
  glDeleteBuffers(1, &id_);
}

}  // namespace stochtex::gl
