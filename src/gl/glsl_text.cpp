// glsl_precision_variant (glsl_text.hpp): one GLSL source, compiled in double or float only.

#include "gl/glsl_text.hpp"

#include <cctype>
#include <stdexcept>
#include <string>
#include <string_view>

namespace stochtex::gl {
namespace {

bool identifier_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
}

// `code` (no comment) float-only: double -> float, dvecN -> vecN, 0.5lf -> 0.5.
std::string float_code(std::string_view code) {
  std::string out;
  std::size_t i = 0;
  while (i < code.size()) {
    const char c = code[i];
    if (std::isalpha(static_cast<unsigned char>(c)) != 0 || c == '_') {
      std::size_t end = i;
      while (end < code.size() && identifier_char(code[end])) ++end;
      const std::string_view word = code.substr(i, end - i);
      if (word == "double")
        out += "float";
      else if (word.size() == 5 && word.substr(0, 4) == "dvec")
        out += word.substr(1);
      else
        out += word;
      i = end;
    } else if (std::isdigit(static_cast<unsigned char>(c)) != 0) {
      // A number: digits and dots, an exponent, then a suffix (u, lf, or x... of a hex literal).
      std::size_t end = i;
      while (end < code.size() &&
             (std::isdigit(static_cast<unsigned char>(code[end])) != 0 || code[end] == '.'))
        ++end;
      if (end < code.size() && (code[end] == 'e' || code[end] == 'E')) {
        std::size_t exponent = end + 1;
        if (exponent < code.size() && (code[exponent] == '+' || code[exponent] == '-')) ++exponent;
        if (exponent < code.size() && std::isdigit(static_cast<unsigned char>(code[exponent]))) {
          end = exponent;
          while (end < code.size() && std::isdigit(static_cast<unsigned char>(code[end]))) ++end;
        }
      }
      std::size_t suffix = end;
      while (suffix < code.size() && identifier_char(code[suffix])) ++suffix;
      const std::string_view tail = code.substr(end, suffix - end);
      out += code.substr(i, end - i);
      if (tail != "lf" && tail != "LF") out += tail;
      i = suffix;
    } else {
      out += c;
      ++i;
    }
  }
  return out;
}

std::string_view trimmed(std::string_view line) {
  const std::size_t first = line.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const std::size_t last = line.find_last_not_of(" \t\r\n");
  return line.substr(first, last - first + 1);
}

}  // namespace

std::string glsl_precision_variant(std::string_view source, GlslPrecision precision) {
  const bool floats = precision == GlslPrecision::floats;
  enum class Block { none, float_lines, double_lines };
  Block block = Block::none;
  std::string out;
  std::size_t start = 0;
  while (start < source.size()) {
    std::size_t end = source.find('\n', start);
    end = end == std::string_view::npos ? source.size() : end + 1;
    const std::string_view line = source.substr(start, end - start);
    start = end;
    const std::string_view directive = trimmed(line);
    if (directive == "#ifdef STOCHTEX_FLOAT") {
      if (block != Block::none) throw std::logic_error("nested #ifdef STOCHTEX_FLOAT in GLSL");
      block = Block::float_lines;
      continue;
    }
    if (block != Block::none && directive == "#else") {
      if (block != Block::float_lines) throw std::logic_error("a second #else in GLSL");
      block = Block::double_lines;
      continue;
    }
    if (block != Block::none && directive == "#endif") {
      block = Block::none;
      continue;
    }
    if ((block == Block::float_lines && !floats) || (block == Block::double_lines && floats))
      continue;
    if (!floats) {
      out += line;
      continue;
    }
    const std::size_t comment = line.find("//");
    out += float_code(line.substr(0, comment));
    if (comment != std::string_view::npos) out += line.substr(comment);
  }
  if (block != Block::none) throw std::logic_error("#ifdef STOCHTEX_FLOAT without #endif in GLSL");
  return out;
}

}  // namespace stochtex::gl
