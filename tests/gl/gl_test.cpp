// The OpenGL backend against the CPU reference (docs/design.md §4: the scalar C++ evaluator is
// the reference). Runs on Mesa llvmpipe in CI and on NVIDIA drivers where a GPU exists.

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "core/float_math.hpp"
#include "core/hash.hpp"
#include "gl/context.hpp"
#include "gl/gl_support.hpp"
#include "gl/program.hpp"
#include "gl/shaders.hpp"
#include "io/image_io.hpp"
#include "stochtex/gpu.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::gl_test {
namespace {

using namespace gl_test;

const Model& model_of(const std::string& name, int order, int points) {
  static std::map<std::string, Model> models;
  const std::string key = name + std::to_string(order) + "/" + std::to_string(points);
  if (!models.contains(key)) {
    const ImageF exemplar = read_image(kTextureDir + "/" + name);
    models[key] = analyze("texton", exemplar.view(),
                          {{"support", 48}, {"order", order}, {"points", points}}, 0);
  }
  return models[key];
}

TEST(Gl, ContextIsOpenGl45) {
  const std::string description = gl_device_description();
  std::cout << description << "\n";
  EXPECT_NE(description.find("OpenGL 4."), std::string::npos) << description;
}

TEST(Gl, RandomGlslMatchesTheCppSpec) {
  // random.glsl run by a one-off compute shader, bit for bit against core/hash.hpp.
  const gl::Context context;
  const std::string source = "#version 450\n" + gl::random_source() + R"glsl(
layout(local_size_x = 64) in;
layout(std430, binding = 0) writeonly buffer Out { uint values[]; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  uint key = cell_key(i * 7919u, 0u - i, i ^ 0x5bd1e995u, STREAM_POINTS);
  CounterRng rng = CounterRng(key, 0u);
  values[i * 4u + 0u] = pcg_hash(i * 2654435761u);
  values[i * 4u + 1u] = key;
  values[i * 4u + 2u] = rng_next(rng);
  values[i * 4u + 3u] = floatBitsToUint(rng_uniform(rng));
}
)glsl";
  const gl::Program program(source);
  constexpr std::uint32_t kCount = 1024;
  const gl::Buffer buffer(kCount * 4 * sizeof(std::uint32_t));
  glUseProgram(program.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer.id());
  glDispatchCompute(kCount / 64, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<std::uint32_t> values(kCount * 4);
  glGetNamedBufferSubData(buffer.id(), 0,
                          static_cast<GLsizeiptr>(values.size() * sizeof(std::uint32_t)),
                          values.data());
  ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  for (std::uint32_t i = 0; i < kCount; ++i) {
    const std::uint32_t key =
        cell_key(static_cast<std::int64_t>(i * 7919u), -static_cast<std::int64_t>(i),
                 i ^ 0x5bd1e995u, Stream::points);
    CounterRng rng(key);
    const std::uint32_t first = rng.next();
    const float uniform = rng.uniform();
    std::uint32_t uniform_bits = 0;
    std::memcpy(&uniform_bits, &uniform, sizeof(uniform_bits));
    ASSERT_EQ(values[i * 4 + 0], pcg_hash(i * 2654435761u)) << i;
    ASSERT_EQ(values[i * 4 + 1], key) << i;
    ASSERT_EQ(values[i * 4 + 2], first) << i;
    ASSERT_EQ(values[i * 4 + 3], uniform_bits) << i;
  }
}

TEST(Gl, FloatMathGlslMatchesTheCpp) {
  // float_math.glsl's cos_turns and exp_float, bit for bit against core/float_math.hpp, on
  // arguments across their range: turns up to +-1000 (gabor's and lrp's phases) with the fold
  // points 1/4, 1/2 and the integers, and exponents across [-100, 100] with the clamp's ends.
  std::vector<float> arguments;
  for (int i = -6400; i <= 6400; ++i)
    arguments.push_back(static_cast<float>(i) * 0.015625f + 1e-3f);
  for (int i = -4000; i <= 4000; ++i) arguments.push_back(static_cast<float>(i) * 0.25f);
  for (int i = 0; i < 4096; ++i) arguments.push_back(std::ldexp(static_cast<float>(i) + 0.3f, -12));
  for (float x : {-87.5f, kExpFloor, -86.999f, 88.0f, 88.001f, kExpCeiling, 1e-30f, -1e-30f})
    arguments.push_back(x);
  while (arguments.size() % 64 != 0) arguments.push_back(0.5f);
  const gl::Context context;
  const std::string source = "#version 450\n" + gl::float_math_source() + R"glsl(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer In { float arguments[]; };
layout(std430, binding = 1) writeonly buffer Out { uint values[]; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  float x = arguments[i];
  values[2u * i] = floatBitsToUint(cos_turns(x));
  values[2u * i + 1u] = floatBitsToUint(exp_float(x));
}
)glsl";
  const gl::Program program(source);
  const auto count = static_cast<GLsizeiptr>(arguments.size());
  const gl::Buffer input(count * static_cast<GLsizeiptr>(sizeof(float)));
  glNamedBufferSubData(input.id(), 0, count * static_cast<GLsizeiptr>(sizeof(float)),
                       arguments.data());
  const gl::Buffer output(2 * count * static_cast<GLsizeiptr>(sizeof(std::uint32_t)));
  glUseProgram(program.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, input.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, output.id());
  glDispatchCompute(static_cast<GLuint>(arguments.size() / 64), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<std::uint32_t> values(2 * arguments.size());
  glGetNamedBufferSubData(
      output.id(), 0, 2 * count * static_cast<GLsizeiptr>(sizeof(std::uint32_t)), values.data());
  ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  for (std::size_t i = 0; i < arguments.size(); ++i) {
    const float x = arguments[i];
    ASSERT_EQ(values[2 * i], std::bit_cast<std::uint32_t>(cos_turns(x)))
        << "cos_turns(" << x << ")";
    ASSERT_EQ(values[2 * i + 1], std::bit_cast<std::uint32_t>(exp_float(x)))
        << "exp_float(" << x << ")";
  }
}

struct ParityCase {
  const char* exemplar;
  int order;
  Grid grid;
  bool filter;
  int points = 1;  // texton params.hpp: 1 balanced (the default), 0 the paper's Poisson process
};

TEST(Gl, TextonMatchesTheCpuReference) {
  // Tolerance: the GPU computes sample positions in float relative to the origin's cell, the CPU
  // in double; with |p| < 2^10 exemplar pixels inside a render the position error is below
  // 2^-14 px, and the summed texton values move by less than 1e-5 (measured maximum: 4e-6 over
  // every case below). 1e-4 keeps a 25x margin and is 40x below one 8-bit step: 8-bit PNGs from
  // the two backends differ at most by one level, in the rare pixels that sit on a rounding tie.
  const std::vector<ParityCase> cases = {
      {"grass_lawn_128.png", 1, {{0.0, 0.0}, 1.0, 96, 80}, true},
      {"grass_lawn_128.png", 3, {{-300.25, 17.5}, 0.5, 64, 64}, true},
      {"metal_grey_256.png", 1, {{1e7, -3e6}, 4.0, 70, 50}, true},
      {"metal_grey_256.png", 5, {{5.0, 5.0}, 8.0, 40, 40}, true},
      {"grass_lawn_128.png", 0, {{12.0, -4.0}, 3.0, 50, 50}, false},
      {"grass_lawn_128.png", 1, {{0.0, 0.0}, 1.0, 96, 80}, true, 0},
      {"metal_grey_256.png", 1, {{1e7, -3e6}, 4.0, 70, 50}, true, 0},
  };
  for (const auto& c : cases) {
    const Model& model = model_of(c.exemplar, c.order, c.points);
    const ImageF cpu = render_cpu(model, c.grid, 9, c.filter);
    const ImageF gpu = render_gpu(model, c.grid, 9, 512, c.filter);
    float worst = 0.0f;
    for (std::size_t i = 0; i < cpu.pixels().size(); ++i)
      worst = std::max(worst, std::abs(cpu.pixels()[i] - gpu.pixels()[i]));
    std::cout << c.exemplar << " order " << c.order << " points " << c.points << " scale "
              << c.grid.scale << ": max |cpu - gl| = " << worst << "\n";
    EXPECT_LT(worst, 1e-4f) << c.exemplar << " order " << c.order << " scale " << c.grid.scale;
  }
}

TEST(Gl, TextonMaterialMatchesTheCpuReference) {
  // A whole material (issue 18): rock_sandstone's 5 maps, 9 channels, render in chunks of 4
  // channels (texton gl_pass.cpp) that draw the same impulses. Tolerance and grids as
  // TextonMatchesTheCpuReference: every channel of every chunk must match the CPU's.
  const ImageF exemplar = test_support::material_exemplar(
      "rock_sandstone", {"albedo", "normal", "roughness", "height", "ao"});
  ASSERT_EQ(exemplar.channels(), 9);
  for (const int order : {1, 3}) {
    const Model model =
        analyze("texton", exemplar.view(), {{"support", 48}, {"order", order}}, 0, "rock");
    for (const ParityCase& c :
         std::vector<ParityCase>{{"rock", order, {{0.0, 0.0}, 1.0, 96, 80}, true},
                                 {"rock", order, {{1e7, -3e6}, 4.0, 70, 50}, true},
                                 {"rock", order, {{12.0, -4.0}, 3.0, 50, 50}, false}}) {
      const ImageF cpu = render_cpu(model, c.grid, 9, c.filter);
      const ImageF gpu = render_gpu(model, c.grid, 9, 64, c.filter);
      std::vector<float> worst(9, 0.0f);
      for (std::size_t i = 0; i < cpu.pixels().size(); ++i)
        worst[i % 9] = std::max(worst[i % 9], std::abs(cpu.pixels()[i] - gpu.pixels()[i]));
      std::cout << "rock, 9 channels, order " << order << " scale " << c.grid.scale
                << ": max |cpu - gl| = " << *std::max_element(worst.begin(), worst.end()) << "\n";
      for (int channel = 0; channel < 9; ++channel)
        EXPECT_LT(worst[channel], 1e-4f)
            << "order " << order << " scale " << c.grid.scale << " channel " << channel;
    }
  }
}

TEST(Gl, TextonHardwareFilterRefusesMoreThanFourChannels) {
  const ImageF exemplar =
      test_support::material_exemplar("sand_pebbles", {"albedo", "normal", "roughness"});
  const Model model = analyze("texton", exemplar.view(), {{"support", 16}}, 0, "sand");
  ImageF out(8, 8, model.channels());
  GpuRenderOptions options;
  options.texture_filter = GlFilter::hardware;
  try {
    render_gl(model, Grid{{0.0, 0.0}, 2.0, 8, 8}, 1, out.view(), options);
    ADD_FAILURE() << "the hardware filter took 7 channels";
  } catch (const Error& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("--gl-filter hardware takes 1 to 4 channels and this model has 7"),
              std::string::npos)
        << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

struct MethodCase {
  const char* method;
  const char* exemplar;
  ParamValues params;
  Grid grid;
  bool filter = true;
};

// Tolerance as for texton (TextonMatchesTheCpuReference). tiling: GLSL's erf is Abramowitz-Stegun
// 7.1.26 (error 1.5e-7; the C++ a rational one) before the table look-up; lrp: the same polynomial
// cosine and window in both. Measured maxima 1e-5 and 2e-6 over these cases.
TEST(Gl, TilingAndLrpMatchTheCpuReference) {
  const std::vector<MethodCase> cases = {
      {"tiling", "grass_lawn_128.png", {}, {{0.0, 0.0}, 1.0, 80, 70}},
      {"tiling", "grass_lawn_128.png", {{"transport", 1}}, {{1e7, -3e6}, 3.0, 60, 50}},
      {"tiling", "metal_grey_256.png", {}, {{-77.5, 12.0}, 0.5, 64, 64}},
      {"tiling", "metal_grey_256.png", {}, {{5.0, 5.0}, 8.0, 40, 40}},
      {"tiling", "grass_lawn_128.png", {{"blend", 1}}, {{3.0, 4.0}, 2.0, 50, 50}},
      // The artist controls: rotated and scaled patches (their footprints and levels), sharpened
      // weights, far from the origin too.
      {"tiling",
       "grass_lawn_128.png",
       {{"rotation", 180}, {"scale_jitter", 0.5}},
       {{1e7, -3e6}, 1.0, 60, 50}},
      {"tiling",
       "metal_grey_256.png",
       {{"sharpness", 4}, {"rotation", 90}},
       {{5.0, 5.0}, 3.0, 40, 40}},
      {"tiling",
       "grass_lawn_128.png",
       {{"scale_jitter", 0.5}, {"transport", 1}},
       {{-7.0, 2.0}, 2.0, 50, 50}},
      {"lrp", "grass_lawn_128.png", {{"cosines", 20}}, {{0.0, 0.0}, 1.0, 48, 40}},
      {"lrp", "metal_grey_256.png", {{"cosines", 10}}, {{1e7, -3e6}, 4.0, 40, 40}},
      {"lrp", "metal_grey_256.png", {{"cosines", 10}}, {{-9.5, 2.0}, 2.0, 40, 40}, false},
      // Section 5: fixed phases with turbulence and placement, far from the origin too, and
      // r = 1 (subdivided blocks) without them.
      {"lrp",
       "grass_lawn_128.png",
       {{"cosines", 20}, {"ratio", 0.3}, {"turbulence", 2}},
       {{-30.0, 17.0}, 1.0, 72, 64}},
      {"lrp",
       "metal_grey_256.png",
       {{"cosines", 10}, {"ratio", 0.2}, {"turbulence", 1}},
       {{1e7, -3e6}, 4.0, 40, 40}},
      {"lrp",
       "metal_grey_256.png",
       {{"cosines", 20}, {"ratio", 1}, {"placement", 0}},
       {{5.0, -3.0}, 1.0, 48, 48},
       false},
  };
  for (const auto& c : cases) {
    const ImageF exemplar = read_image(kTextureDir + "/" + c.exemplar);
    const Model model = analyze(c.method, exemplar.view(), c.params, 0);
    const ImageF cpu = render_cpu(model, c.grid, 9, c.filter);
    const ImageF gpu = render_gpu(model, c.grid, 9, 4096, c.filter);
    float worst = 0.0f;
    for (std::size_t i = 0; i < cpu.pixels().size(); ++i)
      worst = std::max(worst, std::abs(cpu.pixels()[i] - gpu.pixels()[i]));
    std::cout << c.method << " " << c.exemplar << " scale " << c.grid.scale
              << ": max |cpu - gl| = " << worst << "\n";
    EXPECT_LT(worst, 1e-4f) << c.method << " " << c.exemplar << " scale " << c.grid.scale;
    // Dispatch tiles change nothing on this backend either.
    EXPECT_TRUE(same_bytes(gpu, render_gpu(model, c.grid, 9, 16, c.filter)));
  }
}

TEST(Gl, BitIdenticalWhateverTheDispatchTilesAndRegions) {
  const Model& model = model_of("grass_lawn_128.png", 1, 1);
  const Grid grid{{-40.0, 9.5}, 2.0, 75, 61};
  const ImageF reference = render_gpu(model, grid, 4, 512);
  EXPECT_TRUE(same_bytes(reference, render_gpu(model, grid, 4, 512)));
  EXPECT_TRUE(same_bytes(reference, render_gpu(model, grid, 4, 17)));
  EXPECT_TRUE(same_bytes(reference, render_gpu(model, grid, 4, 8)));
  // The right half rendered as a region of its own.
  Grid right = grid;
  right.width = 30;
  right.first_pixel_x = 45;
  const ImageF part = render_gpu(model, right, 4, 16);
  for (int y = 0; y < grid.height; ++y)
    for (int x = 0; x < right.width; ++x)
      for (int c = 0; c < model.channels(); ++c)
        ASSERT_EQ(part.at(x, y, c), reference.at(45 + x, y, c));
  const ImageF other_seed = render_gpu(model, grid, 5, 512);
  EXPECT_FALSE(same_bytes(reference, other_seed));
}

TEST(Gl, ExportedShadersCompileAndMatchTheCpu) {
  // What an engine gets from `stochtex export-shader`: the GLSL file and the data images, read
  // back from disk, each bound to `stochtex_<name>`, driven by a minimal compute shader through
  // the public entry point stochtex_<method>(p, dpdx, dpdy, seed), which computes the filter from
  // the footprint in GLSL (texton_filter, the tiling level of detail, the lrp clamping axes, the
  // Gabor kernel filter).
  const std::vector<ExportCase> cases = export_cases();
  const gl::Context context;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const ExportCase& c = cases[k];
    const Model& model = case_models()[k][0];
    const ShaderExport files = export_shader(model);
    ASSERT_EQ(files.shader.name, "stochtex_" + std::string(c.method) + ".glsl");
    EXPECT_NE(files.readme.find("stochtex_" + std::string(c.method) + "(vec2 p"),
              std::string::npos);
    const auto folder = std::filesystem::temp_directory_path() / "stochtex_export_test";
    std::filesystem::create_directories(folder);
    std::vector<GLuint> textures;
    for (const ShaderTexture& t : files.textures) {
      write_image(folder / t.file_name(), t.image.view());
      const ImageF texels = read_image(folder / t.file_name());
      ASSERT_EQ(texels.channels(), 4);
      GLuint texture = 0;
      glCreateTextures(GL_TEXTURE_2D, 1, &texture);
      glTextureStorage2D(texture, 1, GL_RGBA32F, texels.width(), texels.height());
      glTextureSubImage2D(texture, 0, 0, 0, texels.width(), texels.height(), GL_RGBA, GL_FLOAT,
                          texels.pixels().data());
      textures.push_back(texture);
    }
    std::filesystem::remove_all(folder);

    const int size = c.size;
    for (const double scale : {1.0, 3.0}) {
      const ImageF gl = run_export(files, c.method, textures, model.channels(), size,
                                   static_cast<float>(scale), 11);
      const float worst =
          max_difference(render_cpu(model, Grid{{0.0, 0.0}, scale, size, size}, 11), gl);
      std::cout << "exported " << c.method << " shader (" << c.exemplar << "), scale " << scale
                << ": max |cpu - gl| = " << worst << "\n";
      // The renderers' parity tolerance (TextonMatchesTheCpuReference); the exported tiling and
      // lrp shaders form the lattice coordinates from a float p instead of the CPU's double,
      // which at |p| < 150 moves them by less than 1e-5 pixel.
      EXPECT_LT(worst, 1e-4f) << c.method << " scale " << scale;
    }
    glDeleteTextures(static_cast<GLsizei>(textures.size()), textures.data());
  }
}

TEST(Gl, RefusesGridsBeyondThePreciseRange) {
  // The same check as render() (render.hpp): before any dispatch, for a NaN scale or an origin
  // beyond +-kPositionLimit.
  const Model& model = model_of("grass_lawn_128.png", 1, 1);
  GlRenderer renderer(model);
  ImageF out(4, 4, model.channels());
  for (const Grid& grid : {Grid{{0.0, 0.0}, std::nan(""), 4, 4}, Grid{{1e19, 0.0}, 1.0, 4, 4},
                           Grid{{kPositionLimit, 0.0}, 1.0, 4, 4}})
    EXPECT_THROW(renderer.render(grid, 1, out.view()), std::invalid_argument);
  EXPECT_NO_THROW(renderer.render(Grid{{kPositionLimit - 8.0, 0.0}, 1.0, 4, 4}, 1, out.view()));
}

}  // namespace
}  // namespace stochtex::gl_test
