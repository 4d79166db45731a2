// The Godot files of `export-shader --language godot` (export_godot.hpp).

#include "gl/export_godot.hpp"

#include <array>
#include <bit>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "stochtex/colour.hpp"

namespace stochtex::gl {
namespace {

// Godot 3's largest image side (Image::MAX_WIDTH), which a float image's bytes must fit.
constexpr int kGodotMaxImageSide = 16384;

float channel_or_default(const ImageF& image, int x, int y, int c) {
  if (c < image.channels()) return image.at(x, y, c);
  return c == 3 ? 1.0f : 0.0f;
}

// The colour helpers a fragment() calls: the sRGB curve of core/srgb.hpp.
constexpr const char* kSrgbEncode =
    "float stochtex_srgb_encode(float l) {\n"
    "    if (l <= 0.0031308) {\n        return l * 12.92;\n    }\n"
    "    return 1.055 * pow(l, 1.0 / 2.4) - 0.055;\n}\n";
constexpr const char* kSrgbDecode =
    "float stochtex_srgb_decode(float v) {\n"
    "    if (v <= 0.04045) {\n        return v * (1.0 / 12.92);\n    }\n"
    "    return pow((v + 0.055) * (1.0 / 1.055), 2.4);\n}\n";

// The colour a fragment() shows of `value` (the function's result): each of R, G and B (a grey
// model's one channel three times) as `stochtex render`'s PNG holds it (encoded: sRGB-encoded
// values, for the canvas) or as linear light (for a spatial shader's ALBEDO). A channel in the
// srgb colour space is linear light already; a data channel holds the exemplar file's values,
// for a photo sRGB-encoded.
std::string shown_colour(int channels, const ModelColour& colour, bool encoded, bool& uses_encode,
                         bool& uses_decode) {
  std::string text = "vec3(";
  for (int k = 0; k < 3; ++k) {
    const int c = channels >= 3 ? k : 0;
    const std::string component = std::string("value.") + "xyzw"[c];
    const bool linear = colour.space(c) == ColourSpace::srgb;
    std::string shown = component;
    if (linear && encoded) {
      shown = "stochtex_srgb_encode(" + component + ")";
      uses_encode = true;
    } else if (!linear && !encoded) {
      shown = "stochtex_srgb_decode(" + component + ")";
      uses_decode = true;
    }
    text += (k == 0 ? "" : ", ") + shown;
  }
  return text + ")";
}

std::string helpers(bool uses_encode, bool uses_decode) {
  return std::string(uses_encode ? std::string("\n") + kSrgbEncode : "") +
         (uses_decode ? std::string("\n") + kSrgbDecode : "");
}

// A library's text split after its uniform declarations.
struct LibraryParts {
  std::string uniforms;
  std::string functions;
};
LibraryParts split_library(const std::string& library) {
  const std::size_t blank = library.find("\n\n");
  if (blank == std::string::npos) throw std::logic_error("godot_files: a library without uniforms");
  return {library.substr(0, blank + 1), library.substr(blank + 2)};
}

std::string spatial_shader(const std::string& function, const std::string& header,
                           const LibraryParts& library, int channels, const ModelColour& colour) {
  bool uses_encode = false;
  bool uses_decode = false;
  const std::string albedo = shown_colour(channels, colour, false, uses_encode, uses_decode);
  return header + "shader_type spatial;\n\n" + library.uniforms +
         "// Exemplar pixels per UV unit, and the noise's seed.\n"
         "uniform float stochtex_texture_scale = " +
         std::to_string(kGodotSceneSize) + ".0;\nuniform int stochtex_seed = 0;\n\n" +
         library.functions + helpers(uses_encode, uses_decode) +
         "\nvoid fragment() {\n    vec2 p = UV * stochtex_texture_scale;\n    vec4 value = " +
         function +
         "(p, dFdx(p), dFdy(p), uint(stochtex_seed));\n    // ALBEDO is linear light.\n"
         "    ALBEDO = " +
         albedo + ";\n}\n";
}

std::string canvas_shader(const std::string& function, const std::string& header,
                          const LibraryParts& library, int channels, const ModelColour& colour) {
  bool uses_encode = false;
  bool uses_decode = false;
  const std::string shown = shown_colour(channels, colour, true, uses_encode, uses_decode);
  const std::string size = std::to_string(kGodotSceneSize) + ".0";
  return header + "shader_type canvas_item;\n\n" + library.uniforms +
         "// The render this canvas item draws (its UV spanning `stochtex_size` pixels), as\n"
         "// `stochtex render --size <size> --origin <origin> --scale <scale> --seed <seed>`.\n"
         "uniform vec2 stochtex_size = vec2(" +
         size + ", " + size +
         ");\nuniform vec2 stochtex_origin = vec2(0.0, 0.0);\n"
         "uniform float stochtex_scale = 1.0;\nuniform int stochtex_seed = 0;\n\n" +
         library.functions + helpers(uses_encode, uses_decode) +
         "\nvoid fragment() {\n    vec2 pixel = floor(UV * stochtex_size);\n"
         "    vec2 p = stochtex_origin + stochtex_scale * (pixel + vec2(0.5, 0.5));\n"
         "    vec4 value = " +
         function +
         "(p, vec2(stochtex_scale, 0.0), vec2(0.0, stochtex_scale), uint(stochtex_seed));\n"
         "    // A 2-D canvas shows the values it is given: sRGB-encoded, as the render's PNG.\n"
         "    COLOR = vec4(" +
         shown + ", 1.0);\n}\n";
}

std::string scene(const std::string& method, const std::string& canvas_file,
                  const std::vector<ShaderTexture>& textures) {
  std::string resources = "[ext_resource path=\"" + canvas_file + "\" type=\"Shader\" id=1]\n";
  std::string parameters;
  for (std::size_t k = 0; k < textures.size(); ++k) {
    const std::string id = std::to_string(k + 2);
    resources += "[ext_resource path=\"" + textures[k].file_name() + "\" type=\"" +
                 (textures[k].depth == 1 ? "Texture" : "Texture3D") + "\" id=" + id + "]\n";
    parameters += "shader_param/stochtex_" + textures[k].name + " = ExtResource( " + id + " )\n";
  }
  const std::string size = std::to_string(kGodotSceneSize);
  return "[gd_scene load_steps=" + std::to_string(textures.size() + 3) + " format=2]\n\n" +
         resources + "\n[sub_resource type=\"ShaderMaterial\" id=1]\nshader = ExtResource( 1 )\n" +
         parameters + "shader_param/stochtex_size = Vector2( " + size + ", " + size +
         " )\nshader_param/stochtex_origin = Vector2( 0, 0 )\nshader_param/stochtex_scale = 1.0\n"
         "shader_param/stochtex_seed = 0\n\n[node name=\"stochtex_" +
         method + "\" type=\"ColorRect\"]\nmaterial = SubResource( 1 )\nmargin_right = " + size +
         ".0\nmargin_bottom = " + size + ".0\n";
}

// The import settings Godot 3.2.3's editor writes, with the values that keep the data as it is:
// lossless, sRGB off, no alpha-border fix or premultiplication, no "Detect 3D" (which turns on
// VRAM compression and sRGB when a 3-D material uses the texture), the table's filter, wrap and
// mip-maps, and no anisotropic filtering: with it, Godot 3.2.3 on llvmpipe read tiling's
// exemplar 0.13 away from the CPU at scale 1, the level chosen from the texture coordinates'
// screen derivatives instead of textureGrad's gradients (measured, tests/godot).
std::string import_settings(const ShaderTexture& t) {
  const bool filter = t.filter != TextureFilter::nearest;
  const bool mipmaps = t.mip_levels > 1;
  const std::string repeat = t.wrap == TextureWrap::repeat ? "1" : "0";
  const std::string yes_no[2] = {"false", "true"};
  // A 3-D texture uncompressed: the layered importer's Lossless mode stores PNG, which holds no
  // half floats (Godot 3.2.3 then fails to load it).
  if (t.depth > 1)
    return "[remap]\n\nimporter=\"texture_3d\"\ntype=\"Texture3D\"\n\n[params]\n\n"
           "compress/mode=2\ncompress/no_bptc_if_rgb=false\nflags/repeat=" +
           repeat + "\nflags/filter=" + yes_no[filter] + "\nflags/mipmaps=" + yes_no[mipmaps] +
           "\nflags/srgb=0\nslices/horizontal=1\nslices/vertical=" + std::to_string(t.depth) + "\n";
  return "[remap]\n\nimporter=\"texture\"\ntype=\"StreamTexture\"\n\n[params]\n\n"
         "compress/mode=0\ncompress/lossy_quality=0.7\ncompress/hdr_mode=0\ncompress/bptc_ldr=0\n"
         "compress/normal_map=0\nflags/repeat=" +
         repeat + "\nflags/filter=" + yes_no[filter] + "\nflags/mipmaps=" + yes_no[mipmaps] +
         "\nflags/anisotropic=false" +
         "\nflags/srgb=0\nprocess/fix_alpha_border=false\nprocess/premult_alpha=false\n"
         "process/HDR_as_SRGB=false\nprocess/invert_color=false\nstream=false\nsize_limit=0\n"
         "detect_3d=false\nsvg/scale=1.0\n";
}

}  // namespace

void godot_textures(std::vector<ShaderTexture>& textures, const std::string& method) {
  for (ShaderTexture& t : textures) {
    const int width = t.image.width();
    const int height = t.image.height();
    if (t.filter == TextureFilter::nearest) {
      if (t.encoding != TextureEncoding::exr_float32)
        throw std::logic_error("godot_textures: a texel-read image that is not float: " + t.name);
      if (8 * width > kGodotMaxImageSide)
        throw std::invalid_argument("the " + method + " data image " + t.file_name() + " is " +
                                    std::to_string(width) + " texels wide, and its floats' " +
                                    "bytes would exceed Godot 3's largest image side, " +
                                    std::to_string(kGodotMaxImageSide));
      ImageF bytes(8 * width, height, 2);
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
          for (int c = 0; c < 4; ++c) {
            const auto bits = std::bit_cast<std::uint32_t>(channel_or_default(t.image, x, y, c));
            for (int b = 0; b < 4; ++b)
              bytes.at(8 * x + 2 * c + b / 2, y, b % 2) =
                  static_cast<float>((bits >> (8 * b)) & 0xffU) / 255.0f;
          }
      t.image = std::move(bytes);
      t.encoding = TextureEncoding::png8;
      t.float_bytes = true;
      continue;
    }
    // A filtered image: OpenEXR of 3 or 4 channels (Godot's importer takes R, G, B and A).
    // Godot 3 has no clamp to border: texton's texture, padded with zeros, clamps to its edge.
    if (t.wrap == TextureWrap::clamp_to_border) t.wrap = TextureWrap::clamp_to_edge;
    const int channels = t.image.channels() == 4 ? 4 : 3;
    ImageF padded(width, height, channels);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        for (int c = 0; c < channels; ++c)
          padded.at(x, y, c) = channel_or_default(t.image, x, y, c);
    t.image = std::move(padded);
    t.encoding = TextureEncoding::exr_float32;
  }
}

std::string godot_canvas_file(const std::string& method) {
  return "stochtex_" + method + "_canvas.shader";
}

std::string godot_scene_file(const std::string& method) {
  return "stochtex_" + method + ".tscn";
}

std::string godot4_file(const std::string& method) {
  return "stochtex_" + method + ".gdshader";
}

std::string godot4_hint(const ShaderTexture& t) {
  constexpr std::array<const char*, 3> kFilters = {"filter_nearest", "filter_linear",
                                                   "filter_linear_mipmap"};
  return std::string(kFilters[static_cast<std::size_t>(t.filter)]) +
         (t.wrap == TextureWrap::repeat ? ", repeat_enable" : ", repeat_disable");
}

GodotFiles godot_files(const std::string& method, const std::string& function,
                       const std::string& header, const std::string& library,
                       const std::vector<ShaderTexture>& textures, int channels,
                       const ModelColour& colour) {
  const LibraryParts parts = split_library(library);
  GodotFiles files;
  files.spatial = {"stochtex_" + method + ".shader",
                   spatial_shader(function, header, parts, channels, colour)};
  files.others.push_back(
      {godot_canvas_file(method), canvas_shader(function, header, parts, channels, colour)});
  files.others.push_back(
      {godot_scene_file(method), scene(method, godot_canvas_file(method), textures)});
  for (const ShaderTexture& t : textures)
    files.others.push_back({t.file_name() + ".import", import_settings(t)});
  // Godot 4: the spatial shader with each texture's filter and repeat as uniform hints.
  std::string godot4 = files.spatial.text;
  for (const ShaderTexture& t : textures) {
    const std::string declaration = " stochtex_" + t.name + ";\n";
    const std::size_t at = godot4.find(declaration);
    if (at == std::string::npos) continue;  // a texture the function does not read
    godot4.replace(at, declaration.size(), " stochtex_" + t.name + " : " + godot4_hint(t) + ";\n");
  }
  files.others.push_back({godot4_file(method),
                          "// For Godot 4, not tested (no Godot 4 ran where it was made): see "
                          "README.md, \"Godot 4\".\n" +
                              godot4});
  return files;
}

}  // namespace stochtex::gl
