#pragma once
// `export-shader --language godot` (docs/engines.md, "Godot"): what the export holds beyond the
// cross-compiled function (cross_compile.hpp, godot_shader.hpp) and what it changes of the data,
// so that Godot 3.2's importer and shading language take it as they are:
//   stochtex_<m>.shader          a spatial shader: the function and a fragment() texturing a mesh;
//   stochtex_<m>_canvas.shader   a canvas_item shader drawing `stochtex render`'s pixels;
//   stochtex_<m>.tscn            a minimal scene: a ColorRect drawn by the canvas shader;
//   stochtex_<m>.gdshader        the spatial shader for Godot 4 (texture hints), not tested;
//   <data>.png|.exr and .import  each data image (godot_textures) and its import settings;
//   README.md                    export_shader.cpp, from readme/godot.md.

#include <string>
#include <vector>

#include "model/model_colour.hpp"
#include "stochtex/gpu.hpp"

namespace stochtex::gl {

// The side of the scene's ColorRect, in pixels (the render it draws: `stochtex render --size`).
inline constexpr int kGodotSceneSize = 512;

// `textures` as Godot 3.2 imports and samples them (measured with Debian's Godot 3.2.3 on Mesa,
// docs/engines.md): a float image read texel by texel as its floats' bytes in a grey + alpha PNG
// (float_bytes), which Godot imports exactly as LA8, a format with no sRGB form (Godot samples an
// RGBA8 or RGB8 PNG as sRGB-decoded on Mesa, whatever its import settings); a filtered image
// (tiling's fast exemplar and table, texton's fast texture) as OpenEXR of its values, 1 or 2
// channels padded to RGB as a GL texture reads them, which Godot imports as half floats (RGBH or
// RGBAH: 11 significant bits, more than the 8 Godot 3.2 keeps of a 16-bit PNG), clamped to its
// edge where it was clamped to a transparent border (Godot 3 has no border). Throws
// std::invalid_argument, one sentence naming `method`, for a float image whose bytes would be
// wider than Godot's largest image.
void godot_textures(std::vector<ShaderTexture>& textures, const std::string& method);

// The files `stochtex_<m>.shader` (spatial) and `stochtex_<m>_canvas.shader` (canvas_item) of a
// library `library` (cross_compile's Godot text: uniforms, then functions) exposing `function`,
// for a model of `channels` channels in `colour`, the scene drawing the canvas shader, each
// texture's `.import` file and the Godot 4 shader. `header` opens each shader (the export's
// comment).
struct GodotFiles {
  TextFile spatial;
  std::vector<TextFile> others;
};
GodotFiles godot_files(const std::string& method, const std::string& function,
                       const std::string& header, const std::string& library,
                       const std::vector<ShaderTexture>& textures, int channels,
                       const ModelColour& colour);

// The file names of the canvas shader, the scene and the Godot 4 shader.
std::string godot_canvas_file(const std::string& method);
std::string godot_scene_file(const std::string& method);
std::string godot4_file(const std::string& method);

// Godot 4's uniform hints for `t`'s filter and repeat (Godot 4 sets them in the shader, Godot 3
// at import): "filter_nearest, repeat_disable", ...
std::string godot4_hint(const ShaderTexture& t);

}  // namespace stochtex::gl
