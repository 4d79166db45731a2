#include "web/web_export.hpp"

#include <half.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <utility>

#include "model/model_data.hpp"
#include "stochtex/error.hpp"

namespace stochtex::web {
namespace {

// How the viewer stores one data image: its WebGL2 internal format, upload format and type.
enum class Stored { float32, half, byte };

// texelFetch data stays float32 (every float format is readable by texelFetch in WebGL2 core);
// hardware-filtered data becomes half float (filterable in core, unlike float32 without
// OES_texture_float_linear), or 8-bit where the export itself is 8-bit.
Stored stored_type(const ShaderTexture& texture) {
  if (texture.filter == TextureFilter::nearest) return Stored::float32;
  return texture.encoding == TextureEncoding::png8 ? Stored::byte : Stored::half;
}

// The components the texture is uploaded with: filtered RGB becomes RGBA (alpha 1), since
// RGB16F and RGB8 are not colour-renderable and generateMipmap needs that.
int stored_components(const ShaderTexture& texture) {
  const int channels = texture.image.channels();
  return stored_type(texture) != Stored::float32 && channels == 3 ? 4 : channels;
}

constexpr std::array<const char*, 4> kUploadFormats = {"RED", "RG", "RGB", "RGBA"};

// Names indexed by the enums' values.
constexpr std::array<const char*, 3> kStoredSuffixes = {"32F", "16F", "8"};
constexpr std::array<const char*, 3> kStoredTypes = {"FLOAT", "HALF_FLOAT", "UNSIGNED_BYTE"};

template <typename Enum>
const char* name_of(const std::array<const char*, 3>& names, Enum value) {
  return names[static_cast<std::size_t>(value)];
}

std::string internal_format(Stored stored, int components) {
  constexpr std::array<const char*, 4> kPrefixes = {"R", "RG", "RGB", "RGBA"};
  return std::string(kPrefixes[static_cast<std::size_t>(components - 1)]) +
         name_of(kStoredSuffixes, stored);
}

template <typename Word>
void append_little_endian(std::string& bytes, Word word) {
  for (std::size_t i = 0; i < sizeof(Word); ++i)
    bytes.push_back(static_cast<char>((word >> (8 * i)) & 0xffu));
}

// The texels of `texture` as the viewer uploads them: row 0 first, `components` values a texel.
std::string texel_bytes(const ShaderTexture& texture) {
  const Stored stored = stored_type(texture);
  const int components = stored_components(texture);
  const int channels = texture.image.channels();
  const std::size_t value_bytes = stored == Stored::float32 ? 4 : (stored == Stored::half ? 2 : 1);
  std::string bytes;
  bytes.reserve(texture.image.pixel_count() * static_cast<std::size_t>(components) * value_bytes);
  const std::span<const float> values = texture.image.pixels();
  for (std::size_t pixel = 0; pixel < texture.image.pixel_count(); ++pixel)
    for (int c = 0; c < components; ++c) {
      const float value =
          c < channels ? values[pixel * static_cast<std::size_t>(channels) + c] : 1.0f;
      switch (stored) {
        case Stored::float32:
          append_little_endian(bytes, std::bit_cast<std::uint32_t>(value));
          break;
        case Stored::half:
          append_little_endian(bytes, Imath::half(value).bits());
          break;
        case Stored::byte:
          // A PNG 8-bit export's value is already sample / 255.
          bytes.push_back(static_cast<char>(std::lround(value * 255.0f)));
          break;
      }
    }
  return bytes;
}

nlohmann::ordered_json texture_entry(const ShaderTexture& texture) {
  const Stored stored = stored_type(texture);
  const int components = stored_components(texture);
  // WebGL2 has no clamp to border: the exports that ask for it (the texton texture) pad their
  // data with zeros, which clamping to the edge reads at level 0.
  const TextureWrap wrap =
      texture.wrap == TextureWrap::clamp_to_border ? TextureWrap::clamp_to_edge : texture.wrap;
  nlohmann::ordered_json entry = {
      {"uniform", "stochtex_" + texture.name},
      {"file", texture.name + ".bin"},
      {"target", texture.depth == 1 ? "TEXTURE_2D" : "TEXTURE_3D"},
      {"width", texture.image.width()},
      {"height", texture.image.height() / texture.depth},
      {"depth", texture.depth},
      {"components", components},
      {"internal_format", internal_format(stored, components)},
      {"format", kUploadFormats[static_cast<std::size_t>(components - 1)]},
      {"type", name_of(kStoredTypes, stored)},
      {"filter", filter_name(texture.filter)},
      {"wrap", wrap_name(wrap)},
      {"mip_levels", texture.mip_levels},
      {"anisotropy", texture.filter == TextureFilter::mipmap ? 16 : 1},
      {"exported_as",
       {{"file", texture.file_name()},
        {"encoding", encoding_name(texture.encoding)},
        {"components", texture.image.channels()},
        {"wrap", wrap_name(texture.wrap)}}},
  };
  return entry;
}

}  // namespace

std::string_view variant_name(ShaderVariant variant) {
  return variant == ShaderVariant::fast ? "fast" : "exact";
}

std::vector<WebFile> web_export(const Model& model, ShaderVariant variant) {
  if (model.empty()) throw std::invalid_argument("web_export: the model is empty");
  if (model.channels() > kMaxImageChannels)
    throw Error(ErrorCode::invalid_input,
                "the web viewer shows a model of up to 4 channels, and this " +
                    std::string(model.method()) + " model has " + std::to_string(model.channels()) +
                    "; export its shader with `stochtex export-shader` instead");
  // An exact shader that GLSL ES cannot run (gabor's needs double precision) is refused by the
  // exporter with its reason: the web export then holds the model's fast shader and says why.
  ShaderVariant shader_variant = variant;
  ShaderExport exported;
  std::string refusal;
  try {
    exported = export_shader(model, {variant, ShaderLanguage::essl});
  } catch (const std::invalid_argument& e) {
    if (variant != ShaderVariant::exact) throw;
    refusal = e.what();
    shader_variant = ShaderVariant::fast;
    exported = export_shader(model, {shader_variant, ShaderLanguage::essl});
  }
  const std::string entry = "stochtex_" + std::string(model.method());
  if (exported.shader.text.find("vec4 " + entry + "(") == std::string::npos)
    throw Error(ErrorCode::invalid_input, "the exported GLSL ES shader of this " +
                                              std::string(model.method()) + " model has no vec4 " +
                                              entry + " function for the web viewer to call");
  nlohmann::ordered_json manifest = {
      {"format", "stochtex-web-export"},
      {"version", 1},
      {"method", model.method()},
      {"channels", model.channels()},
      // What the shader returns: linear light (a srgb model: the viewer encodes it for the
      // canvas) or the model's values as they are (data: shown as they are).
      {"colour", model.data().colour.decodes() ? "linear" : "data"},
      {"variant", variant_name(variant)},
      {"shader_variant", variant_name(shader_variant)},
      {"entry", entry},
      {"shader", "shader.essl"},
      {"textures", nlohmann::ordered_json::array()},
  };
  if (shader_variant != variant)
    manifest["note"] = refusal + " (this web export holds its fast shader)";
  std::vector<WebFile> files;
  files.push_back({"manifest.json", ""});
  files.push_back({"shader.essl", exported.shader.text});
  for (const ShaderTexture& texture : exported.textures) {
    manifest["textures"].push_back(texture_entry(texture));
    files.push_back({texture.name + ".bin", texel_bytes(texture)});
  }
  files.front().bytes = manifest.dump(1) + "\n";
  return files;
}

}  // namespace stochtex::web
