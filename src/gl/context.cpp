#include "gl/context.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>

#include <array>
#include <string>

#include "stochtex/error.hpp"

namespace stochtex::gl {
namespace {

[[noreturn]] void fail(Api api, const std::string& problem) {
  if (api == Api::gles30)
    throw Error(ErrorCode::io, "cannot create an OpenGL ES 3.0 context: " + problem +
                                   "; install the Mesa or NVIDIA EGL drivers");
  throw Error(ErrorCode::io, "cannot create an OpenGL 4.5 context for --backend gl: " + problem +
                                 "; install the Mesa or NVIDIA EGL drivers, or use --backend cpu");
}

EGLDisplay open_display(Api api) {
  const auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  const auto query_devices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  if (get_platform_display && query_devices) {
    std::array<EGLDeviceEXT, 8> devices{};
    EGLint count = 0;
    if (query_devices(static_cast<EGLint>(devices.size()), devices.data(), &count))
      for (EGLint i = 0; i < count; ++i) {
        EGLDisplay display = get_platform_display(EGL_PLATFORM_DEVICE_EXT,
                                                  devices[static_cast<std::size_t>(i)], nullptr);
        if (display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr)) return display;
      }
  }
  if (get_platform_display) {
    EGLDisplay display =
        get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr)) return display;
  }
  EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr)) return display;
  fail(api, "no EGL display could be opened");
}

}  // namespace

struct Context::State {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
};

Context::Context(Api api) : state_(new State) {
  const bool es = api == Api::gles30;
  state_->display = open_display(api);
  if (!eglBindAPI(es ? EGL_OPENGL_ES_API : EGL_OPENGL_API)) {
    eglTerminate(state_->display);
    fail(api, es ? "EGL has no OpenGL ES API" : "EGL has no desktop OpenGL API");
  }
  const std::array<EGLint, 5> config_attributes = {
      EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
      es ? EGL_OPENGL_ES3_BIT : EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configs = 0;
  if (!eglChooseConfig(state_->display, config_attributes.data(), &config, 1, &configs))
    configs = 0;
  const std::array<EGLint, 7> context_attributes = {EGL_CONTEXT_MAJOR_VERSION,
                                                    4,
                                                    EGL_CONTEXT_MINOR_VERSION,
                                                    5,
                                                    EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                                    EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                                    EGL_NONE};
  const std::array<EGLint, 5> es_attributes = {EGL_CONTEXT_MAJOR_VERSION, 3,
                                               EGL_CONTEXT_MINOR_VERSION, 0, EGL_NONE};
  state_->context =
      eglCreateContext(state_->display, configs > 0 ? config : nullptr, EGL_NO_CONTEXT,
                       es ? es_attributes.data() : context_attributes.data());
  if (state_->context == EGL_NO_CONTEXT ||
      !eglMakeCurrent(state_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, state_->context)) {
    if (state_->context != EGL_NO_CONTEXT) eglDestroyContext(state_->display, state_->context);
    eglTerminate(state_->display);
    fail(api, es ? "the driver offers no OpenGL ES 3.0 context without a surface"
                 : "the driver offers no OpenGL 4.5 core context without a surface");
  }
}

Context::~Context() {
  eglMakeCurrent(state_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(state_->display, state_->context);
  eglTerminate(state_->display);
}

std::string Context::description() const {
  const auto text = [](GLenum name) {
    const auto* value = reinterpret_cast<const char*>(glGetString(name));
    return std::string(value ? value : "?");
  };
  return "OpenGL " + text(GL_VERSION) + " on " + text(GL_RENDERER);
}

}  // namespace stochtex::gl
