// Deterministic mutation fuzzing of the OBJ reader (docs/meshes.md, docs/design.md §9): seeded
// edits of the small valid meshes of tests/fuzz/corpus/mesh (numbers swapped for edge values, NaN
// and huge indices, lines repeated, dropped, cut and spliced, bytes flipped) must each read as a
// mesh that keeps every promise of prepare_mesh and renders finite values, or be refused with
// stochtex::Error. Any other exception, or a crash, fails the test.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "stochtex/mesh_render.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex {
namespace {

namespace fs = std::filesystem;

constexpr int kMutatedFiles = 3000;
constexpr std::uint32_t kSeed = 20250301;

std::vector<std::string> seeds() {
  std::vector<std::string> texts;
  for (const auto& entry : fs::directory_iterator(fs::path(STOCHTEX_FUZZ_CORPUS) / "mesh")) {
    std::ifstream stream(entry.path(), std::ios::binary);
    texts.emplace_back(std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>());
  }
  std::sort(texts.begin(), texts.end());
  return texts;
}

// Tokens that sit on the edges an OBJ parser gets wrong: signs, zero and huge indices, values
// that are not finite, numbers beyond int and double, and lines of every kind.
constexpr std::array<const char*, 16> kTokens = {"0",
                                                 "-1",
                                                 "-99999",
                                                 "2147483647",
                                                 "99999999999999999999",
                                                 "nan",
                                                 "inf",
                                                 "-inf",
                                                 "1e308",
                                                 "1e-320",
                                                 "/",
                                                 "//",
                                                 " ",
                                                 "\nf 1 1 1\n",
                                                 "\nv 1e300 -1e300 0\n",
                                                 "\nmtllib /etc/passwd\n"};

void mutate(std::string& text, std::mt19937& random) {
  const auto position = [&] {
    return std::uniform_int_distribution<std::size_t>(0,
                                                      text.empty() ? 0 : text.size() - 1)(random);
  };
  const int edits = std::uniform_int_distribution<int>(1, 4)(random);
  for (int edit = 0; edit < edits && !text.empty(); ++edit) {
    switch (std::uniform_int_distribution<int>(0, 5)(random)) {
      case 0: {  // a number (or any run of digits) replaced by an edge token
        const std::size_t at = text.find_first_of("0123456789", position());
        if (at == std::string::npos) break;
        const std::size_t end = text.find_first_not_of("0123456789.e-", at);
        text.replace(at, (end == std::string::npos ? text.size() : end) - at,
                     kTokens[random() % kTokens.size()]);
        break;
      }
      case 1:  // a token inserted anywhere
        text.insert(position(), kTokens[random() % kTokens.size()]);
        break;
      case 2: {  // a line repeated
        const std::size_t start = text.rfind('\n', position());
        const std::size_t from = start == std::string::npos ? 0 : start + 1;
        const std::size_t end = text.find('\n', from);
        const std::string line = text.substr(from, end == std::string::npos ? end : end - from + 1);
        text.insert(from, line);
        break;
      }
      case 3: {  // a range dropped
        const std::size_t at = position();
        text.erase(at, std::uniform_int_distribution<std::size_t>(1, 24)(random));
        break;
      }
      case 4:  // truncation
        text.resize(position());
        break;
      case 5:  // a byte flipped
        text[position()] ^= static_cast<char>(1u << (random() % 8));
        break;
    }
  }
}

// A mesh that read keeps prepare_mesh's promises.
void expect_consistent(const Mesh& mesh, const std::string& context) {
  ASSERT_FALSE(mesh.triangles.empty()) << context;
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size()) << context;
  ASSERT_TRUE(mesh.uvs.empty() || mesh.uvs.size() == mesh.positions.size()) << context;
  for (const auto& triangle : mesh.triangles)
    for (const std::uint32_t index : triangle) ASSERT_LT(index, mesh.positions.size()) << context;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const Vec3d& p = mesh.positions[v];
    const Vec3d& n = mesh.normals[v];
    ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << context;
    ASSERT_NEAR(n.x * n.x + n.y * n.y + n.z * n.z, 1.0, 1e-9) << context;
  }
}

TEST(MeshFuzz, MutatedFilesReadOrThrowError) {
  const fs::path folder =
      fs::temp_directory_path() / ("stochtex_mesh_fuzz_" + std::to_string(::getpid()));
  fs::remove_all(folder);
  fs::create_directories(folder);
  const std::vector<std::string> texts = seeds();
  ASSERT_GE(texts.size(), 3u);
  ImageF exemplar(24, 24, 3);
  std::mt19937 random(kSeed);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (float& value : exemplar.pixels()) value = uniform(random);
  const Model model = analyze("tiling", exemplar.view(), {}, 0);

  int meshes_read = 0;
  int errors_thrown = 0;
  const fs::path path = folder / "mutated.obj";
  for (int iteration = 0; iteration < kMutatedFiles; ++iteration) {
    const std::size_t seed = static_cast<std::size_t>(iteration) % texts.size();
    std::string text = texts[seed];
    mutate(text, random);
    std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
    const std::string context = "iteration " + std::to_string(iteration) + " from seed " +
                                std::to_string(seed) + ":\n" + text;
    try {
      const Mesh mesh = read_mesh(path);
      expect_consistent(mesh, context);
      ImageF image(6, 5, 3);
      MeshRenderOptions options;
      options.threads = 1;
      options.texture_scale = 7.0;
      options.mapping = mesh.uvs.empty() || iteration % 2 == 0
                            ? std::optional(SurfaceMapping::triplanar_linear)
                            : std::nullopt;
      try {
        render_mesh(model, mesh, orbit_camera(mesh, 30.0, 20.0, 1.0, 6, 5), options, 1,
                    image.view());
        for (const float value : image.pixels()) ASSERT_TRUE(std::isfinite(value)) << context;
      } catch (const std::invalid_argument&) {
        // The texture scale puts a huge mesh beyond the precise range: refused before work.
      }
      ++meshes_read;
    } catch (const Error&) {
      ++errors_thrown;
    } catch (const std::exception& e) {
      FAIL() << context << "\nthrew something other than stochtex::Error: " << e.what();
    }
  }
  fs::remove_all(folder);
  EXPECT_GT(meshes_read, kMutatedFiles / 10);
  EXPECT_GT(errors_thrown, kMutatedFiles / 10);
  std::printf("%d mutated meshes: %d read and rendered, %d refused with stochtex::Error\n",
              kMutatedFiles, meshes_read, errors_thrown);
}

}  // namespace
}  // namespace stochtex
