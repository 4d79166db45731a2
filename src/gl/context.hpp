#pragma once
// A headless OpenGL 4.5 core context through EGL (no window, no display server): the EGL device
// platform (NVIDIA and Mesa), then Mesa's surfaceless platform (llvmpipe on machines without a
// GPU), then the default display. One context per thread that uses it; made current on creation.
// An OpenGL ES 3.0 context the same way runs exported GLSL ES shaders (tests/gl).

#include <memory>
#include <string>

namespace stochtex::gl {

enum class Api { gl45, gles30 };

class Context {
 public:
  // Throws stochtex::Error(io) with one sentence saying why no such context could be made.
  explicit Context(Api api = Api::gl45);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  // "OpenGL <version> on <renderer>", e.g. "4.5 (Core Profile) Mesa 22.3.6 on llvmpipe (...)".
  std::string description() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace stochtex::gl
