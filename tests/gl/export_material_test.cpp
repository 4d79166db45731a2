// `export-shader` of a material (issue 18): the struct StochtexMaterial and
// stochtex_<method>_material (src/gl/export_material.cpp) of texton, lrp and gabor models of
// rock_sandstone run in a compute shader on llvmpipe and match render_maps on the CPU map by map,
// derived normal maps included; every language's file goes through glslang's front end (Metal:
// its signature); a model of one image exports what it did; what cannot be exported is refused
// with a sentence.

#include "gl/export_material.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "gl/context.hpp"
#include "gl/cross_compile.hpp"
#include "gl/gl_support.hpp"
#include "model/model_data.hpp"
#include "stochtex/material.hpp"
#include "stochtex_gl_twins.hpp"

namespace stochtex::export_material_test {
namespace {

using namespace gl_test;

const std::vector<std::string> kRock = {"albedo", "normal", "roughness", "height", "ao"};

// rock_sandstone's maps `names` (their top-left side x side pixels) analysed by `method`, the
// albedo's values in colour space `albedo` (the other maps are data).
Model rock(const std::string& method, const std::vector<std::string>& names,
           const ParamValues& params, int side, const MaterialOptions& options = {},
           ColourSpace albedo = ColourSpace::data) {
  std::vector<ImageF> images;
  for (const std::string& name : names)
    images.push_back(read_image(std::filesystem::path(STOCHTEX_MATERIAL_DIR) / "rock_sandstone" /
                                (name + ".png")));
  std::vector<MaterialMap> maps;
  for (std::size_t m = 0; m < names.size(); ++m)
    maps.push_back({names[m],
                    {},
                    images[m].view().sub(0, 0, side, side),
                    names[m] + ".png",
                    names[m] == "albedo" ? albedo : ColourSpace::data});
  return analyze_material(method, maps, params, 0, options);
}

// A map's components in the struct: 3 for a normal map or a colour map of 3 channels, else 1.
int components(const MapInfo& map) {
  return map.kind == MapKind::normal || map.channels == 3 ? 3 : 1;
}

// The caller's GLSL: the material at p with footprint `footprint` (GLSL of dpdx and dpdy), each
// member's components one after the other into the pixel's values.
std::string store_material(const Model& model, const std::string& footprint) {
  std::string store = "  StochtexMaterial material = stochtex_" + std::string(model.method()) +
                      "_material(p, " + footprint + ", seed);\n";
  int value = 0;
  for (const MapInfo& map : model.maps())
    for (int c = 0; c < components(map); ++c)
      store += "  values[index].v[" + std::to_string(value++) + "] = material." + map.name +
               (components(map) == 3 ? std::string(".") + "xyz"[c] : "") + ";\n";
  return store;
}

// The largest difference per map between the exported function's maps (a normal map encoded
// 0.5 + 0.5 n, as render_maps writes it) and render_maps on the CPU, over size x size pixels at
// `scale` from the origin; `filter` false with the footprint zero.
std::vector<float> map_differences(const Model& model, const ShaderExport& files, int size,
                                   float scale, std::uint32_t seed, bool filter = true) {
  int floats = 0;
  for (const MapInfo& map : model.maps()) floats += components(map);
  std::vector<GLuint> textures;
  for (const ShaderTexture& t : files.textures) textures.push_back(gl::texture_of(t));
  const std::vector<float> values = run_export_program(
      files, store_material(model, filter ? "dpdx, dpdy" : "vec2(0.0), vec2(0.0)"), floats,
      textures, size, scale, seed);
  glDeleteTextures(static_cast<GLsizei>(textures.size()), textures.data());
  RenderOptions options;
  options.filter = filter;
  const std::vector<NamedImage> cpu = render_maps(
      model, Grid{{0.0, 0.0}, scale, size, size},
      [&](const Grid& part, ImageView<float> out) { render(model, part, seed, out, options); });
  std::vector<float> worst;
  int first = 0;
  for (std::size_t m = 0; m < cpu.size(); ++m) {
    const bool normal = model.maps()[m].kind == MapKind::normal;
    float difference = 0.0f;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x)
        for (int c = 0; c < cpu[m].image.channels(); ++c) {
          float gpu = values[(static_cast<std::size_t>(y) * size + x) * floats +
                             static_cast<std::size_t>(first + c)];
          if (normal) gpu = 0.5f + 0.5f * gpu;
          difference = std::max(difference, std::abs(gpu - cpu[m].image.at(x, y, c)));
        }
    worst.push_back(difference);
    first += components(model.maps()[m]);
  }
  return worst;
}

struct MaterialCase {
  const char* method;
  std::vector<std::string> maps;
  ParamValues params;
  int side;  // of the exemplar crop
  MaterialOptions options;
  int size;  // of the grid compared
  ColourSpace albedo = ColourSpace::data;
};

// The cases: every method that derives normal maps, with its normal map derived (6 channels:
// beyond a vec4), synthesised as two slopes (texton: 8 channels) and within a vec4 (lrp: albedo,
// derived normal and height, 4 channels).
std::vector<MaterialCase> material_cases() {
  return {
      {"texton", kRock, {{"support", 48}, {"iterations", 3}}, 256, {}, 32},
      {"texton", kRock, {{"support", 48}, {"iterations", 3}}, 256, {.derive_normals = false}, 32},
      {"lrp", kRock, {{"cosines", 10}}, 256, {}, 32},
      {"lrp", {"albedo", "normal", "height"}, {{"cosines", 10}}, 256, {}, 32},
      {"gabor", kRock, {{"impulses", 64}, {"iterations", 20}}, 256, {}, 24},
      // tiling keeps the normal map as two slopes: its groups' T^-1 in the shader (8 channels),
      // with the artist controls (the slopes' radial group turned with their patches, the
      // height-aware blend) and with 2 channels (within a vec4, still a material's function).
      {"tiling", kRock, {}, 256, {}, 32},
      {"tiling",
       kRock,
       {{"rotation", 180}, {"scale_jitter", 0.5}, {"height_blend", 0.1}},
       256,
       {},
       32},
      {"tiling", {"albedo", "height"}, {{"sharpness", 4}}, 256, {}, 32},
      // An sRGB albedo, decoded in the material function (gl/colour_material.glsl): beyond a
      // vec4 (texton's channels function; the albedo last, channels 3 to 5, whose removed
      // deviations straddle two rows of removed.exr) and within one (lrp).
      {"texton",
       {"height", "normal", "roughness", "ao", "albedo"},
       {{"support", 48}, {"iterations", 3}},
       256,
       {},
       32,
       ColourSpace::srgb},
      {"lrp", {"albedo", "normal", "height"}, {{"cosines", 10}}, 256, {}, 32, ColourSpace::srgb},
  };
}

TEST(ExportMaterial, MapsMatchTheCpu) {
  // The bound is the exact export's (ExportLanguage.GlslRunsInAFragmentShaderAndMatchesTheCpu),
  // the renderers' parity bound 1e-4. A derived normal map's slopes are slope_scale / (2 scale)
  // times a difference of two heights (35 / 2 on the full rock for texton), which multiplies the
  // heights' float error of ~1e-7 to the 1e-6 order, still far within it. A decoded map's, times
  // the decoding's largest slope (kDecodingSlope), as GlColour's.
  const gl::Context context;
  for (const MaterialCase& c : material_cases()) {
    const Model model = rock(c.method, c.maps, c.params, c.side, c.options, c.albedo);
    const bool derived = c.options.derive_normals && method_info(c.method).derives_normals;
    ASSERT_EQ(model.maps()[1].derived_from, derived ? "height" : "") << c.method;
    const ShaderExport files = export_shader(model);
    for (const auto& [seed, scale] : {std::pair{2u, 1.0f}, std::pair{9u, 3.0f}}) {
      const std::vector<float> worst = map_differences(model, files, c.size, scale, seed);
      for (std::size_t m = 0; m < worst.size(); ++m) {
        const bool decoded = model.maps()[m].colour_space == ColourSpace::srgb;
        std::cout << c.method << " (" << model.channels() << " channels"
                  << (decoded ? ", srgb albedo" : "") << "), seed " << seed << ", scale " << scale
                  << ", " << model.maps()[m].name << ": max |cpu - exported| = " << worst[m]
                  << "\n";
        EXPECT_LT(worst[m], 1e-4f * (decoded ? kDecodingSlope : 1.0f))
            << c.method << " " << model.maps()[m].name;
      }
    }
  }
}

TEST(ExportMaterial, DerivedNormalsWithoutAFootprintStepOnePixel) {
  // dpdx = dpdy = 0: no filtering, and the height's differences one exemplar pixel apart, which
  // is render_maps of an unfiltered grid of spacing 1.
  const gl::Context context;
  const Model model = rock("texton", kRock, {{"support", 48}, {"iterations", 3}}, 256);
  const std::vector<float> worst = map_differences(model, export_shader(model), 32, 1.0f, 4, false);
  for (std::size_t m = 0; m < worst.size(); ++m) EXPECT_LT(worst[m], 1e-4f) << model.maps()[m].name;
}

TEST(ExportMaterial, EveryLanguageCompiles) {
  // texton beyond a vec4 (a private chunk index, which Metal passes by reference) and within one,
  // lrp, with derived normal maps, and gabor's float-only variant (its exact one keeps doubles,
  // GLSL only) with the normal map's slopes of its own (on a crop whose wrapped edges break the
  // slopes' fit to the height's gradient), and tiling with every control (the per-patch arrays
  // flattened for ESSL 3.00, which has no arrays of arrays). The second texton material and lrp's
  // decode an sRGB albedo (gl/colour_material.glsl).
  const std::vector<Model> models = {
      rock("texton", kRock, {{"support", 16}, {"iterations", 3}}, 256),
      rock("texton", {"albedo", "normal", "height"}, {{"support", 16}, {"iterations", 3}}, 256, {},
           ColourSpace::srgb),
      rock("lrp", kRock, {{"cosines", 4}}, 256, {}, ColourSpace::srgb),
      rock("gabor", kRock, {{"impulses", 64}, {"iterations", 20}}, 32),
      rock("tiling", kRock, {{"rotation", 90}, {"scale_jitter", 0.3}, {"height_blend", 0.1}}, 64),
  };
  for (std::size_t k = 0; k < models.size(); ++k)
    ASSERT_EQ(models[k].maps()[1].derived_from, k < 3 ? "height" : "");
  for (const Model& model : models) {
    const std::string method(model.method());
    const std::string function = "stochtex_" + method + "_material";
    for (const gl::LanguageRow& row : gl::kLanguageRows) {
      const ShaderLanguage language = row.language;
      SCOPED_TRACE(method + " (" + std::to_string(model.channels()) + " channels) " +
                   std::string(row.name));
      const ShaderVariant variant = method == "gabor" && language != ShaderLanguage::glsl
                                        ? ShaderVariant::fast
                                        : ShaderVariant::exact;
      if (language == ShaderLanguage::godot) {
        // Godot 3's language has no structs: a material is refused, in one sentence.
        try {
          export_shader(model, {variant, language});
          ADD_FAILURE() << "the export did not refuse a material for Godot";
        } catch (const std::invalid_argument& e) {
          EXPECT_NE(std::string(e.what()).find("Godot 3's shading language"), std::string::npos)
              << e.what();
        }
        continue;
      }
      const ShaderExport files = export_shader(model, {variant, language});
      const std::string& text = files.shader.text;
      // The README declares the struct, a member per map, and names the function.
      EXPECT_NE(files.readme.find("struct StochtexMaterial {"), std::string::npos);
      for (const MapInfo& map : model.maps()) {
        const bool glsl = language == ShaderLanguage::glsl || language == ShaderLanguage::essl;
        const std::string member =
            std::string(components(map) == 3 ? (glsl ? "vec3 " : "float3 ") : "float ") + map.name +
            ";";
        EXPECT_NE(files.readme.find(member), std::string::npos) << member;
      }
      EXPECT_NE(files.readme.find("StochtexMaterial " + function + "("), std::string::npos);
      // A material that decodes its sRGB maps reads two more files, named in its README.
      const bool decodes = model.data().colour.expects_any();
      for (const char* table : {"decoded", "removed"}) {
        const bool shipped = std::any_of(files.textures.begin(), files.textures.end(),
                                         [&](const ShaderTexture& t) { return t.name == table; });
        EXPECT_EQ(shipped, decodes) << table;
        EXPECT_EQ(files.readme.find(std::string(table) + ".exr") != std::string::npos, decodes)
            << table;
      }
      // The manifest gives the function's outputs, one per map, and what each holds.
      const nlohmann::json manifest = nlohmann::json::parse(files.manifest);
      EXPECT_EQ(manifest["entry"], function);
      ASSERT_EQ(manifest["outputs"].size(), model.maps().size());
      for (std::size_t m = 0; m < model.maps().size(); ++m) {
        const nlohmann::json& output = manifest["outputs"][m];
        EXPECT_EQ(output["name"], model.maps()[m].name);
        EXPECT_EQ(output["components"], components(model.maps()[m]));
        EXPECT_EQ(output["colour"],
                  model.maps()[m].colour_space == ColourSpace::srgb ? "linear" : "data");
      }
      const std::string call = "StochtexMaterial material = " + function;
      switch (language) {
        case ShaderLanguage::glsl:
        case ShaderLanguage::essl: {
          const std::string version =
              language == ShaderLanguage::glsl ? "#version 450\n" : "#version 300 es\n";
          EXPECT_EQ(gl::front_end_errors(version + text +
                                             "out highp vec4 colour;\nvoid main() {\n  highp "
                                             "vec2 p = gl_FragCoord.xy;\n  " +
                                             call +
                                             "(p, dFdx(p), dFdy(p), 7u);\n  colour = "
                                             "vec4(material.normal, material.height);\n}\n",
                                         language),
                    "");
          break;
        }
        case ShaderLanguage::hlsl: {
          EXPECT_EQ(gl::front_end_errors(
                        text + "float4 main(float4 position : SV_Position) : SV_Target {\n  " +
                            "float2 p = position.xy;\n  " + call +
                            "(p, ddx(p), ddy(p), 7u);\n  return float4(material.normal, "
                            "material.height);\n}\n",
                        language),
                    "");
          // The Shader Graph function: an output per map.
          ASSERT_EQ(files.wrappers.size(), 1u);
          std::string outputs;
          std::string arguments;
          for (const MapInfo& map : model.maps()) {
            outputs +=
                std::string(components(map) == 3 ? "  float3 " : "  float ") + map.name + ";\n";
            arguments += ", " + map.name;
          }
          EXPECT_EQ(
              gl::front_end_errors(files.wrappers[0].text +
                                       "float4 main(float4 position : SV_Position) : "
                                       "SV_Target {\n  float2 p = position.xy;\n" +
                                       outputs + "  " + function + "_float(p, ddx(p), ddy(p), 7u" +
                                       arguments + ");\n  return float4(normal, height);\n}\n",
                                   language),
              "");
          break;
        }
        case ShaderLanguage::godot:
          break;  // refused above
        case ShaderLanguage::msl:
          // No Metal compiler on Linux: the struct and the signature.
          EXPECT_NE(text.find("struct StochtexMaterial\n{\n"), std::string::npos);
          EXPECT_NE(text.find("StochtexMaterial " + function +
                              "(thread const float2& p, thread const float2& dpdx, thread const "
                              "float2& dpdy, thread const uint& seed, "),
                    std::string::npos);
          break;
      }
    }
  }
}

TEST(ExportMaterial, ModelsOfOneImageExportTheirLibraryAlone) {
  // What export-shader wrote before materials: the header comment, then the method's library.
  for (const char* method : {"texton", "lrp", "gabor"}) {
    const Model model = test_support::white_noise_model(method);
    const ShaderExport files = export_shader(model);
    const std::string library = std::visit(
        [](const auto& m) {
          using Method = std::decay_t<decltype(m)>;
          return gl::Twin<Method>::shader(m, ShaderVariant::exact).library;
        },
        model.data().model);
    EXPECT_TRUE(files.shader.text.ends_with(library)) << method;
    EXPECT_EQ(files.shader.text.find("StochtexMaterial"), std::string::npos) << method;
    EXPECT_NE(files.readme.find("vec4 stochtex_" + std::string(method) + "("), std::string::npos);
  }
}

// The sentence export_shader throws for `model` with `options` (empty: none).
std::string refusal(const Model& model, const ShaderExportOptions& options = {}) {
  try {
    export_shader(model, options);
  } catch (const Error& error) {
    return error.what();
  }
  return {};
}

TEST(ExportMaterial, RefusesWhatItCannotExport) {
  const auto expect_sentence = [](const std::string& what, const std::string& part) {
    EXPECT_NE(what.find(part), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  };
  // tiling's fast variant reads an image's colour and alpha through its textures.
  expect_sentence(refusal(rock("tiling", {"albedo", "roughness"}, {}, 64),
                          {ShaderVariant::fast, ShaderLanguage::glsl}),
                  "export it with --variant exact");
  // texton's fast variant reads one texture of at most 4 channels.
  const Model texton = rock("texton", kRock, {{"support", 16}, {"iterations", 3}}, 64);
  expect_sentence(refusal(texton, {ShaderVariant::fast, ShaderLanguage::glsl}),
                  "export it with --variant exact");
  // lrp's section 5 beyond 4 channels.
  expect_sentence(refusal(rock("lrp", kRock, {{"cosines", 4}, {"ratio", 0.3}}, 64)),
                  "analyse it with ratio 0");
}

TEST(ExportMaterial, ReservedWordsAreNotMembers) {
  // GLSL reserves `sample`, HLSL `line`, and the Shader Graph function has an input `seed`: the
  // members become map_sample, map_line and map_seed.
  const auto scalar = [](const char* name) {
    MapInfo map;
    map.name = name;
    map.kind = MapKind::scalar;
    return map;
  };
  const std::vector<MapInfo> maps = {scalar("sample"), scalar("line"), scalar("seed"),
                                     scalar("albedo")};
  const gl::MaterialShader material = gl::material_shader(maps, 4, "lrp", "");
  ASSERT_EQ(material.members.size(), 4u);
  EXPECT_EQ(material.members[0].name, "map_sample");
  EXPECT_EQ(material.members[1].name, "map_line");
  EXPECT_EQ(material.members[2].name, "map_seed");
  EXPECT_EQ(material.members[3].name, "albedo");
  // The README declares each member, a name of 32 characters too.
  const std::string longest(32, 'a');
  const std::string readme = gl::material_readme(
      gl::material_shader(std::vector<MapInfo>{scalar(longest.c_str())}, 1, "lrp", ""),
      ShaderLanguage::hlsl);
  EXPECT_NE(readme.find("      float " + longest + "; // scalar map"), std::string::npos) << readme;
  try {
    gl::material_shader(std::vector<MapInfo>{scalar("sample"), scalar("map_sample")}, 2, "lrp", "");
    ADD_FAILURE() << "two maps made one member";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("the maps 'sample' and 'map_sample'"),
              std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace stochtex::export_material_test
