// The methods' GPU twins as a whole (src/gl/twin.hpp): the constants C++ and GLSL share read back
// in GLSL as the C++ values, and every method of the registry renders on the GL backend.

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "gl/context.hpp"
#include "gl/gl_support.hpp"
#include "gl/program.hpp"
#include "gl/shaders.hpp"
#include "io/image_io.hpp"
#include "model/model_data.hpp"
#include "stochtex_gl_twins.hpp"

namespace stochtex::twin_test {
namespace {

using namespace gl_test;

// Every table of shared constants: random.glsl's streams, float_math.glsl's constants and the
// Twin::kConstants of each method that has a twin and constants of its own (a CPU-only model has
// none; texton_mix shares texton noise's and random.glsl's).
std::vector<std::span<const gl::GlslConstant>> shared_constant_tables() {
  std::vector<std::span<const gl::GlslConstant>> tables = {gl::random_constants(),
                                                           gl::float_math_constants()};
  [&]<typename... MethodModels>(std::type_identity<std::variant<MethodModels...>>) {
    (
        [&] {
          if constexpr (gl::HasTwin<MethodModels>)
            if (!gl::Twin<MethodModels>::kConstants.empty())
              tables.push_back(gl::Twin<MethodModels>::kConstants);
        }(),
        ...);
  }(std::type_identity<MethodModel>{});
  return tables;
}

// The two 32-bit words of a constant's value as C++ holds it (the second 0 unless a double).
std::array<std::uint32_t, 2> cpp_words(const gl::GlslConstant& constant) {
  std::array<std::uint32_t, 2> words{};
  std::visit(
      [&](auto value) {
        if constexpr (std::is_same_v<decltype(value), int>)
          words[0] = static_cast<std::uint32_t>(value);
        else
          std::memcpy(words.data(), &value, sizeof(value));
      },
      constant.value);
  return words;
}

// GLSL writing the same two words of the GLSL constant.
std::string glsl_words(const gl::GlslConstant& constant, std::size_t index) {
  const std::string at = "values[" + std::to_string(2 * index);
  const std::string name = constant.name;
  return std::visit(
      [&](auto value) -> std::string {
        using T = decltype(value);
        if constexpr (std::is_same_v<T, double>)
          return "  { uvec2 w = unpackDouble2x32(" + name + "); " + at + "u] = w.x; " + at +
                 "u + 1u] = w.y; }\n";
        const std::string word =
            std::is_same_v<T, float> ? "floatBitsToUint(" + name + ")" : "uint(" + name + ")";
        return "  " + at + "u] = " + word + ";\n  " + at + "u + 1u] = 0u;\n";
      },
      constant.value);
}

TEST(GlTwin, SharedConstantsReadBackInGlslAsTheCppValues) {
  // The GLSL declarations glsl_constants() writes from the C++ constexprs, compiled and read back
  // bit for bit: a literal that rounds (a float written with too few digits, a double without
  // `lf`) fails here.
  const gl::Context context;
  std::size_t checked = 0;
  for (const std::span<const gl::GlslConstant> table : shared_constant_tables()) {
    ASSERT_FALSE(table.empty());
    std::string body;
    for (std::size_t i = 0; i < table.size(); ++i) body += glsl_words(table[i], i);
    const gl::Program program("#version 450\n" + gl::glsl_constants(table) + R"glsl(
layout(local_size_x = 1) in;
layout(std430, binding = 0) writeonly buffer Out { uint values[]; };
void main() {
)glsl" + body + "}\n");
    const gl::Buffer buffer(table.size() * 2 * sizeof(std::uint32_t));
    glUseProgram(program.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer.id());
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<std::uint32_t> values(table.size() * 2);
    glGetNamedBufferSubData(buffer.id(), 0,
                            static_cast<GLsizeiptr>(values.size() * sizeof(std::uint32_t)),
                            values.data());
    ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    for (std::size_t i = 0; i < table.size(); ++i) {
      const std::array<std::uint32_t, 2> expected = cpp_words(table[i]);
      EXPECT_EQ(values[2 * i], expected[0]) << table[i].name;
      EXPECT_EQ(values[2 * i + 1], expected[1]) << table[i].name;
      ++checked;
    }
  }
  EXPECT_GT(checked, 20u);
}

TEST(GlTwin, PrecisionVariantsOfOneSource) {
  // Shared lines: unchanged for doubles, float-only code (comments untouched) for floats; the
  // STOCHTEX_FLOAT blocks give each precision its own lines, without the directives.
  const std::string source =
      "precise double x = 0.5lf * y + 1e-3lf; // a double\n"
      "dvec2 p = dvec2(x, 2.0lf); uint k = 0x0000ffu; float half_x = 3.0;\n"
      "  #ifdef STOCHTEX_FLOAT\n"
      "float only;\n"
      "#else\n"
      "double only;\n"
      "#endif\n"
      "#ifdef STOCHTEX_FLOAT\n"
      "float extra;\n"
      "#endif\n";
  EXPECT_EQ(gl::glsl_precision_variant(source, gl::GlslPrecision::doubles),
            "precise double x = 0.5lf * y + 1e-3lf; // a double\n"
            "dvec2 p = dvec2(x, 2.0lf); uint k = 0x0000ffu; float half_x = 3.0;\n"
            "double only;\n");
  EXPECT_EQ(gl::glsl_precision_variant(source, gl::GlslPrecision::floats),
            "precise float x = 0.5 * y + 1e-3; // a double\n"
            "vec2 p = vec2(x, 2.0); uint k = 0x0000ffu; float half_x = 3.0;\n"
            "float only;\n"
            "float extra;\n");
  EXPECT_THROW(
      gl::glsl_precision_variant("#ifdef STOCHTEX_FLOAT\nfloat x;\n", gl::GlslPrecision::floats),
      std::logic_error);
}

TEST(GlTwin, EveryRegisteredMethodRendersOnTheGlBackend) {
  // The methods of the registry, not a list of our own: each has a GPU twin (gl_supports) whose
  // render of a default model matches the CPU reference (tolerance of the parity tests).
  EXPECT_FALSE(gl_supports("no-such-method"));
  const ImageF exemplar = read_image(kTextureDir + "/grass_lawn_128.png");
  const Grid grid{{-20.0, 7.5}, 2.0, 24, 16};
  for (const MethodInfo& method : methods()) {
    ASSERT_TRUE(gl_supports(method.name)) << method.name;
    const Model model = analyze(method.name, exemplar.view(), {}, 0);
    const ImageF cpu = render_cpu(model, grid, 5);
    const ImageF gpu = render_gpu(model, grid, 5);
    std::cout << method.name << ": max |cpu - gl| = " << max_difference(cpu, gpu) << "\n";
    EXPECT_LT(max_difference(cpu, gpu), 1e-4f) << method.name;
    EXPECT_EQ(export_shader(model).shader.name, "stochtex_" + std::string(method.name) + ".glsl");
  }
}

TEST(GlTwin, TextonMixMatchesTheCpuReference) {
  // Texton noise mixing is made by `stochtex mix`, not by the registry's analysis: its twin on
  // ramp and mask fields, grey and colour, point-sampled and filtered (scale 3: pyramid levels and
  // probes), far from the origin (the field at the origin cell's corner formed in double), within
  // texton noise's parity bound (Gl.TextonMatchesTheCpuReference); dispatch tiles change nothing.
  const ParamValues ramp = {{"support", 16},     {"iterations", 5}, {"steps", 5},
                            {"ramp_start", -30}, {"ramp_end", 90},  {"direction_y", 0.5}};
  const ParamValues mask = {{"support", 16}, {"iterations", 5}, {"steps", 4}, {"mask_scale", 0.5}};
  const std::vector<ExportCase> cases = {
      {"texton_mix", "grass_lawn_128.png", ramp, 0, "wood_planks_256.png"},
      {"texton_mix", "metal_grey_256.png", ramp, 0, "nuts_grey_256.png"},
      {"texton_mix", "grass_lawn_128.png", mask, 0, "wood_planks_256.png", "metal_grey_256.png"},
      {"texton_mix", "metal_grey_256.png", mask, 0, "nuts_grey_256.png", "metal_grey_256.png"},
  };
  const std::vector<std::pair<Grid, bool>> grids = {
      {{{-20.0, 7.5}, 1.0, 48, 40}, true},
      {{{-20.0, 7.5}, 3.0, 40, 32}, true},
      {{{-20.0, 7.5}, 3.0, 40, 32}, false},
      {{{1e7, -3e6}, 4.0, 24, 24}, true},
  };
  for (const ExportCase& c : cases) {
    const Model model = case_model(c);
    for (const auto& [grid, filter] : grids) {
      const ImageF cpu = render_cpu(model, grid, 9, filter);
      const ImageF gpu = render_gpu(model, grid, 9, 4096, filter);
      std::cout << "texton_mix (" << c.exemplar << ", " << (c.mask ? "mask" : "ramp") << ", "
                << model.channels() << " channels) scale " << grid.scale
                << (filter ? "" : " unfiltered")
                << ": max |cpu - gl| = " << max_difference(cpu, gpu) << "\n";
      EXPECT_LT(max_difference(cpu, gpu), 1e-4f) << c.exemplar << " scale " << grid.scale;
      EXPECT_TRUE(same_bytes(gpu, render_gpu(model, grid, 9, 16, filter)));
    }
  }
}

}  // namespace
}  // namespace stochtex::twin_test
