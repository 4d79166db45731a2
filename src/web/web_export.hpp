#pragma once
// The web export of a model (docs/studio.md, "Web export"): what the WebGL2 viewer
// (web/viewer/viewer.js) loads to draw a model with its exported GLSL ES 3.00 shader. The same
// files are written by `stochtex export-web` and served by `stochtex studio`.
//
//   manifest.json  the method, channels, variant, entry function, shader file, and per data
//                  texture its uniform, file, size, components, WebGL2 format and type, filter,
//                  wrap and mip levels: everything the viewer needs to create it;
//   shader.essl    export_shader(model, {variant, ShaderLanguage::essl})'s GLSL ES library;
//   <name>.bin     one raw little-endian texel array per data image, in the image's row order
//                  (row 0 = texel row 0, as texImage2D/3D take it).
//
// Formats (all WebGL2 core): float32 data read with texelFetch stays float32 (R32F .. RGBA32F);
// hardware-filtered data becomes half float (R16F, RG16F, RGBA16F: filterable without
// OES_texture_float_linear, where 16-bit PNGs would need EXT_texture_norm16), or 8-bit UNORM
// where the export is a PNG 8-bit; 3-channel filtered data is padded to RGBA (alpha 1) because
// generateMipmap needs a colour-renderable format. WebGL2 has no clamp to border: such textures
// are clamped to their edge (the texton texture's zero padding).

#include <cstdint>
#include <string>
#include <vector>

#include "stochtex/gpu.hpp"
#include "stochtex/model.hpp"

namespace stochtex::web {

// One file of a web export: its name in the export's folder and its bytes.
struct WebFile {
  std::string name;
  std::string bytes;
};

// The web export of `model` in `variant`: manifest.json first, then shader.essl, then the data.
// An exact shader the exporter refuses in GLSL ES (gabor's computes in double precision, which
// GLSL ES 3.00 lacks) is replaced by the model's fast shader, and the manifest says so
// ("shader_variant", and a "note" with the exporter's reason).
// Throws what export_shader throws (std::invalid_argument, stochtex::Error, one sentence), and
// Error(invalid_input) for a model of more than 4 channels (the viewer shows one vec4).
std::vector<WebFile> web_export(const Model& model, ShaderVariant variant);

// "exact" or "fast".
std::string_view variant_name(ShaderVariant variant);

}  // namespace stochtex::web
