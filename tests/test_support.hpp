#pragma once
// Shared by the unit and GL tests: bitwise image comparison, the rejection of corrupt model
// records, and a fresh folder per test.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/model_record.hpp"
#include "stochtex/error.hpp"
#include "stochtex/image.hpp"

namespace stochtex::test_support {

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

}  // namespace stochtex::test_support
