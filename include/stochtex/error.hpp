#pragma once
// Analysis and I/O report failures with `stochtex::Error`; evaluation never throws (STYLE.md 5).

#include <stdexcept>
#include <string>

namespace stochtex {

enum class ErrorCode {
  io,             // a file cannot be opened, read or written
  format,         // a file is not in the expected format, is truncated or corrupt
  invalid_input,  // the data is readable but unusable (1x1 image, NaN pixels, constant image...)
  numerical,      // a computation failed
};

class Error : public std::runtime_error {
 public:
  Error(ErrorCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
  ErrorCode code() const { return code_; }

 private:
  ErrorCode code_;
};

}  // namespace stochtex
