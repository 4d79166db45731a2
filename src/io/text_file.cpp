#include "io/text_file.hpp"

#include <fstream>
#include <string>
#include <system_error>

#include "stochtex/error.hpp"

namespace stochtex {

void write_text_file(const std::filesystem::path& path, std::string_view text) {
  std::filesystem::path temporary = path;
  temporary += ".tmp";
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    file << text;
    file.close();
    if (!file) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      throw Error(ErrorCode::io, "cannot write '" + path.string() + "'");
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw Error(ErrorCode::io, "cannot write '" + path.string() + "': " + error.message());
  }
}

}  // namespace stochtex
