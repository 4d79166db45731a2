#include "gl/program.hpp"

#include <algorithm>
#include <initializer_list>

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

namespace {

GLuint compile(GLenum stage, const char* name, const std::string& source) {
  const GLuint shader = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    std::string log(4096, '\0');
    glGetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
    glDeleteShader(shader);
    gl_failure("the " + std::string(name) + " shader does not compile: " + log.c_str());
  }
  return shader;
}

// Links the compiled `shaders` into a program and deletes them.
GLuint link(std::initializer_list<GLuint> shaders, const char* name) {
  const GLuint id = glCreateProgram();
  for (const GLuint shader : shaders) glAttachShader(id, shader);
  glLinkProgram(id);
  for (const GLuint shader : shaders) glDeleteShader(shader);
  GLint ok = GL_FALSE;
  glGetProgramiv(id, GL_LINK_STATUS, &ok);
  if (!ok) {
    glDeleteProgram(id);
    gl_failure("the " + std::string(name) + " shader does not link");
  }
  return id;
}

}  // namespace

Program::Program(const std::string& source)
    : id_(link({compile(GL_COMPUTE_SHADER, "compute", source)}, "compute")) {}

Program::Program(const std::string& vertex, const std::string& fragment) {
  const GLuint vertex_shader = compile(GL_VERTEX_SHADER, "vertex", vertex);
  GLuint fragment_shader = 0;
  try {
    fragment_shader = compile(GL_FRAGMENT_SHADER, "fragment", fragment);
  } catch (...) {
    glDeleteShader(vertex_shader);
    throw;
  }
  id_ = link({vertex_shader, fragment_shader}, "vertex and fragment");
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
