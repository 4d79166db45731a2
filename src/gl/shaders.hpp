#pragma once
// GLSL sources compiled into the library (generated from the .glsl files by CMake, so the files
// stay the single source and editors see them as GLSL).

namespace stochtex::gl {

extern const char* const kRandomGlsl;        // src/gl/random.glsl
extern const char* const kTextonGlsl;        // src/methods/texton/evaluate.glsl
extern const char* const kTextonRenderGlsl;  // src/gl/texton_render.glsl
extern const char* const kTilingGlsl;        // src/methods/tiling/evaluate.glsl
extern const char* const kTilingRenderGlsl;  // src/gl/tiling_render.glsl
extern const char* const kTilingHardwareGlsl;  // src/gl/tiling_hardware.glsl
extern const char* const kTextonHardwareGlsl;  // src/gl/texton_hardware.glsl
extern const char* const kLrpGlsl;           // src/methods/lrp/evaluate.glsl
extern const char* const kLrpRenderGlsl;     // src/gl/lrp_render.glsl
extern const char* const kGaborGlsl;         // src/methods/gabor/evaluate.glsl
extern const char* const kGaborRenderGlsl;   // src/gl/gabor_render.glsl

}  // namespace stochtex::gl
