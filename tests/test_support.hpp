#pragma once
// Shared by the unit and GL tests: bitwise image comparison, the rejection of corrupt model
// records, and a fresh folder per test.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/model_record.hpp"
#include "stochtex/error.hpp"
#include "stochtex/image.hpp"
#include "stochtex/io.hpp"
#include "stochtex/stochtex.hpp"
#include "stochtex/surface.hpp"

namespace stochtex::test_support {

// The shipped rock material set (data/materials/rock_sandstone) and meshes (data/meshes).
inline const std::string kRock = std::string(STOCHTEX_MATERIAL_DIR) + "/rock_sandstone/";
inline const std::string kMeshes = std::string(STOCHTEX_SOURCE_DIR) + "/data/meshes/";

// The folder that CTest's fixture tests fill with what several tests share and is costly to make
// (tests/CMakeLists.txt sets STOCHTEX_TEST_CACHE for them: the statistical tests' default models,
// the GL tests' export case models), when the test runs under CTest. Run by hand, without it, a
// test makes what it needs itself, so a stale folder is never read.
inline std::optional<std::filesystem::path> shared_folder() {
  const char* folder = std::getenv("STOCHTEX_TEST_CACHE");
  if (folder == nullptr || *folder == '\0') return std::nullopt;
  return std::filesystem::path(folder);
}

// A fixture with an empty folder of its own, named after the test and the process, removed after.
class FolderTest : public testing::Test {
 protected:
  void SetUp() override {
    const auto* test = testing::UnitTest::GetInstance()->current_test_info();
    folder_ = std::filesystem::temp_directory_path() /
              ("stochtex_" + std::string(test->test_suite_name()) + "_" + test->name() + "_" +
               std::to_string(::getpid()));
    std::filesystem::remove_all(folder_);
    std::filesystem::create_directories(folder_);
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }

  std::filesystem::path file(const std::string& name) const { return folder_ / name; }
  std::vector<std::filesystem::path> folder_contents() const {
    return {std::filesystem::directory_iterator(folder_), std::filesystem::directory_iterator()};
  }

  std::filesystem::path folder_;
};

// The maps `names` of the shipped material set `set` (data/materials/<set>/<name>.png), their
// channels side by side in one image in the order given: an exemplar of many channels.
inline ImageF material_exemplar(const std::string& set, const std::vector<std::string>& names) {
  std::vector<ImageF> maps;
  int channels = 0;
  for (const auto& name : names) {
    maps.push_back(
        read_image(std::filesystem::path(STOCHTEX_MATERIAL_DIR) / set / (name + ".png")));
    channels += maps.back().channels();
  }
  ImageF stacked(maps.front().width(), maps.front().height(), channels);
  for (int y = 0; y < stacked.height(); ++y)
    for (int x = 0; x < stacked.width(); ++x) {
      int c = 0;
      for (const ImageF& map : maps)
        for (int k = 0; k < map.channels(); ++k) stacked.at(x, y, c++) = map.at(x, y, k);
    }
  return stacked;
}

// The bytes of the file at `path`.
inline std::vector<unsigned char> file_bytes(const std::filesystem::path& path) {
  std::ifstream stream(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

// The same size and the same bytes (determinism checks compare floats bit for bit).
inline bool same_bytes(const ImageF& a, const ImageF& b) {
  return a.pixels().size() == b.pixels().size() &&
         std::memcmp(a.pixels().data(), b.pixels().data(), a.pixels().size_bytes()) == 0;
}

// Method::from_record must refuse `record` with a format error that names the file ('bad.stx').
template <typename Method>
void expect_record_rejected(const ModelRecord& record, const std::string& what) {
  try {
    Method::from_record(record, "bad.stx");
    ADD_FAILURE() << what << ": accepted";
  } catch (const Error& error) {
    EXPECT_EQ(error.code(), ErrorCode::format) << what;
    EXPECT_NE(std::string(error.what()).find("'bad.stx'"), std::string::npos) << what;
  }
}

// The values of the array `name` of `record` (throws when there is none).
inline std::vector<float>& record_array(ModelRecord& record, const std::string& name) {
  for (NamedArray& array : record.arrays)
    if (array.name == name) return array.values;
  throw std::logic_error("no array " + name);
}

// Each (scalar, value) set alone in `good`, then each (array, (index, value)): every one must be
// refused.
template <typename Method>
void expect_corruptions_rejected(
    const ModelRecord& good, const std::vector<std::pair<std::string, double>>& scalars,
    const std::vector<std::pair<std::string, std::pair<std::size_t, float>>>& values) {
  for (const auto& [name, value] : scalars) {
    ModelRecord record = good;
    record.scalars[name] = value;
    expect_record_rejected<Method>(record, name + " = " + std::to_string(value));
  }
  for (const auto& [name, edit] : values) {
    ModelRecord record = good;
    record_array(record, name)[edit.first] = edit.second;
    expect_record_rejected<Method>(
        record, name + "[" + std::to_string(edit.first) + "] = " + std::to_string(edit.second));
  }
}

// A model of `method` (default parameters, seed 3) analysed from a 32 x 32 colour exemplar of
// Gaussian white noise (mean 0.5, sd 0.1): small and quick to make.
inline Model white_noise_model(std::string_view method) {
  std::mt19937 engine(8);
  std::normal_distribution<float> normal(0.5f, 0.1f);
  ImageF exemplar(32, 32, 3);
  for (float& value : exemplar.pixels()) value = normal(engine);
  return analyze(method, exemplar.view(), {}, 3);
}

// `count` points of a sphere of radius `radius` centred on the origin, normals drawn from
// std::mt19937(seed), each with a frame (tangent: the normal crossed with the axis it is least
// aligned with) and a footprint of `along` pixels along the tangent and `across` along n x t.
inline std::vector<SurfacePoint> sphere_points(int count, double radius, double along,
                                               double across, unsigned seed) {
  std::vector<SurfacePoint> points;
  std::mt19937 engine(seed);
  std::normal_distribution<double> normal;
  const auto unit = [](Vec3d v) {
    const double length = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    return Vec3d{v.x / length, v.y / length, v.z / length};
  };
  const auto cross = [](const Vec3d& a, const Vec3d& b) {
    return Vec3d{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
  };
  for (int i = 0; i < count; ++i) {
    // One draw per statement: the order of the draws must not depend on evaluation order.
    const double x = normal(engine);
    const double y = normal(engine);
    const double z = normal(engine);
    const Vec3d n = unit({x, y, z});
    const Vec3d t =
        unit(cross(n, std::abs(n.x) < 0.9 ? Vec3d{1.0, 0.0, 0.0} : Vec3d{0.0, 1.0, 0.0}));
    const Vec3d b = cross(n, t);
    points.push_back({{radius * n.x, radius * n.y, radius * n.z},
                      n,
                      t,
                      {along * t.x, along * t.y, along * t.z},
                      {across * b.x, across * b.y, across * b.z}});
  }
  return points;
}

}  // namespace stochtex::test_support
