// SPIRV-Cross's GLSL ES 3.00 (one inlined main()) -> Godot 3's shading language (godot_shader.hpp).
//
// SPIRV-Cross writes one statement per line, `{` and `}` on lines of their own and no comments,
// so the rewrites work line by line, with a small scanner for the expressions whose parts they
// move (array elements, vector components).

#include "gl/godot_shader.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace stochtex::gl {
namespace {

[[noreturn]] void fail(const std::string& what) {
  throw std::logic_error("godot_from_essl: " + what);
}

bool is_identifier_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
}

std::string_view trim(std::string_view text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front())) != 0)
    text.remove_prefix(1);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back())) != 0)
    text.remove_suffix(1);
  return text;
}

std::string indentation(std::string_view line) {
  return std::string(line.substr(0, line.find_first_not_of(' ')));
}

// `text` split at its top-level occurrences of `separator` (outside parentheses and brackets).
std::vector<std::string> split_top_level(std::string_view text, char separator) {
  std::vector<std::string> parts;
  int depth = 0;
  std::size_t start = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '(' || text[i] == '[') ++depth;
    if (text[i] == ')' || text[i] == ']') --depth;
    if (depth == 0 && text[i] == separator) {
      parts.emplace_back(trim(text.substr(start, i - start)));
      start = i + 1;
    }
  }
  parts.emplace_back(trim(text.substr(start)));
  return parts;
}

// The position of the bracket closing the one opened at `open` ('(' or '[').
std::size_t closing(std::string_view text, std::size_t open) {
  int depth = 0;
  for (std::size_t i = open; i < text.size(); ++i) {
    if (text[i] == '(' || text[i] == '[') ++depth;
    if (text[i] == ')' || text[i] == ']') --depth;
    if (depth == 0) return i;
  }
  fail("unbalanced brackets in `" + std::string(text) + "`");
}

// The position of the bracket opening the one closed at `close`.
std::size_t opening(std::string_view text, std::size_t close) {
  int depth = 0;
  for (std::size_t i = close + 1; i-- > 0;) {
    if (text[i] == ')' || text[i] == ']') ++depth;
    if (text[i] == '(' || text[i] == '[') --depth;
    if (depth == 0) return i;
  }
  fail("unbalanced brackets in `" + std::string(text) + "`");
}

// An int as Godot 3.2 reads it: it parses an integer literal into an int, which keeps at most
// 2^31 - 1 (2147483648 becomes -2^31), so -2^31 is written as a sum; a negative value in
// parentheses, so that no `-` precedes it directly.
std::string godot_int(std::int32_t value) {
  if (value == INT32_MIN) return "(-2147483647 - 1)";
  return value < 0 ? "(" + std::to_string(value) + ")" : std::to_string(value);
}

// A uint as Godot 3.2 reads it: `uint(7)` (it has no `7u`), and from 2^31 on the conversion of the
// int of the same bits, `uint(-1403630843)` for 2891336453 (GLSL's int-to-uint conversion keeps
// the bits; Godot turns a literal beyond 2^31 - 1 into 2^31).
std::string godot_uint(std::uint32_t value) {
  if (value < 0x80000000U) return "uint(" + std::to_string(value) + ")";
  return "uint" + godot_int(static_cast<std::int32_t>(value));
}

// A float literal as Godot 3.2 reads it: it writes a float constant back into GLSL with printf's
// %g, 6 significant digits (0.57735025882720947265625 becomes 0.57735), so a float that 6 digits
// do not give back is written as its bits, `uintBitsToFloat(uint(1058262330))`.
std::string godot_float(const std::string& literal) {
  const float value = std::strtof(literal.c_str(), nullptr);
  std::array<char, 32> shown{};
  std::snprintf(shown.data(), shown.size(), "%g", static_cast<double>(value));
  if (std::strtof(shown.data(), nullptr) == value) return literal;
  return "uintBitsToFloat(" + godot_uint(std::bit_cast<std::uint32_t>(value)) + ")";
}

// Literals: `7u` and `0xffu` -> godot_uint, `0x10` -> godot_int, floats -> godot_float.
std::string rewrite_literals(std::string_view line) {
  std::string out;
  std::size_t i = 0;
  while (i < line.size()) {
    const bool starts_number = std::isdigit(static_cast<unsigned char>(line[i])) != 0 &&
                               (i == 0 || (!is_identifier_char(line[i - 1]) && line[i - 1] != '.'));
    if (!starts_number) {
      out += line[i++];
      continue;
    }
    std::size_t end = i;
    const bool hex = line.substr(i, 2) == "0x" || line.substr(i, 2) == "0X";
    if (hex) end += 2;
    while (end < line.size() &&
           (hex ? std::isxdigit(static_cast<unsigned char>(line[end])) != 0
                : std::isdigit(static_cast<unsigned char>(line[end])) != 0 || line[end] == '.' ||
                      line[end] == 'e' || line[end] == 'E' ||
                      ((line[end] == '+' || line[end] == '-') &&
                       (line[end - 1] == 'e' || line[end - 1] == 'E'))))
      ++end;
    const std::string digits(line.substr(i, end - i));
    const bool is_unsigned = end < line.size() && (line[end] == 'u' || line[end] == 'U');
    if (is_unsigned) ++end;
    if (end < line.size() && is_identifier_char(line[end]))
      fail("unexpected literal in `" + std::string(line) + "`");
    if (hex || is_unsigned) {
      const std::uint64_t value =
          std::stoull(hex ? digits.substr(2) : digits, nullptr, hex ? 16 : 10);
      if (value > 0xffffffffULL) fail("literal beyond 32 bits: " + digits);
      out += is_unsigned ? godot_uint(static_cast<std::uint32_t>(value))
                         : godot_int(static_cast<std::int32_t>(static_cast<std::uint32_t>(value)));
    } else if (digits.find_first_of(".eE") == std::string::npos) {
      out += digits;
    } else {
      out += godot_float(digits);
    }
    i = end;
  }
  return out;
}

// `a - (-b)` as `a + b` (the same float: IEEE subtraction adds the negation). Godot 3.2 writes a
// negation without parentheses, `(-2.0)` folded into a constant as `-2.0`, and `a--2.0` is not
// GLSL. SPIRV-Cross negates one term (a literal, a name, a call or a parenthesised expression):
// anything else is refused, as is a negated negation, `-(-b)`, which Godot would write `--b`.
std::string rewrite_negated_negatives(std::string_view line) {
  std::string out;
  std::size_t i = 0;
  for (std::size_t at = line.find(" - (-"); at != std::string_view::npos;
       at = line.find(" - (-", i)) {
    const std::size_t close = closing(line, at + 3);
    const std::string_view term = line.substr(at + 5, close - at - 5);
    int depth = 0;
    for (std::size_t k = 0; k < term.size(); ++k) {
      const char c = term[k];
      if (c == '(' || c == '[') ++depth;
      if (c == ')' || c == ']') --depth;
      const bool exponent_sign = (c == '+' || c == '-') && k >= 2 &&
                                 (term[k - 1] == 'e' || term[k - 1] == 'E') &&
                                 std::isdigit(static_cast<unsigned char>(term[k - 2])) != 0;
      if (depth == 0 && !exponent_sign &&
          std::string_view("+-*/%<>=!&|^?:, ").find(c) != std::string_view::npos)
        fail("a negated expression of several terms in `" + std::string(line) + "`");
    }
    out += std::string(line.substr(i, at - i)) + " + " + std::string(term);
    i = close + 1;
  }
  out += line.substr(i);
  if (out.find("-(-") != std::string::npos) fail("a negated negation in `" + out + "`");
  return out;
}

// GLSL's types as SPIRV-Cross declares them: scalars, vectors and square matrices.
bool is_type(std::string_view word) {
  static const std::set<std::string_view> kTypes = {
      "float", "int",   "uint",  "bool",  "vec2",  "vec3",  "vec4", "ivec2", "ivec3", "ivec4",
      "uvec2", "uvec3", "uvec4", "bvec2", "bvec3", "bvec4", "mat2", "mat3",  "mat4"};
  return kTypes.contains(word);
}

// A vector type's component count (0: not a vector) and component type.
int vector_size(std::string_view type) {
  if (type.size() < 4 ||
      (!type.ends_with("vec2") && !type.ends_with("vec3") && !type.ends_with("vec4")))
    return 0;
  return type.back() - '0';
}

std::string component_type(std::string_view vector) {
  constexpr std::array<std::pair<char, const char*>, 4> kPrefixes = {
      {{'v', "float"}, {'i', "int"}, {'u', "uint"}, {'b', "bool"}}};
  for (const auto& [prefix, type] : kPrefixes)
    if (vector.front() == prefix) return type;
  fail("not a vector type: " + std::string(vector));
}

// What a name was declared as: its type and, for an array, its length (0: not an array).
struct Declared {
  std::string type;
  int length = 0;
};
using Names = std::map<std::string, Declared, std::less<>>;

// The declarations of `statement` ("[const] type name[N] = ..., name2 = ...;", a for loop's
// initialiser), recorded in `names`.
void record_declarations(std::string_view statement, Names& names) {
  statement = trim(statement);
  if (statement.starts_with("const ")) statement.remove_prefix(6);
  const std::size_t space = statement.find(' ');
  if (space == std::string_view::npos || !is_type(statement.substr(0, space))) return;
  const std::string type(statement.substr(0, space));
  std::string_view rest = statement.substr(space + 1);
  if (rest.ends_with(";")) rest.remove_suffix(1);
  for (const std::string& part : split_top_level(rest, ',')) {
    std::size_t end = 0;
    while (end < part.size() && is_identifier_char(part[end])) ++end;
    if (end == 0) fail("unexpected declaration `" + std::string(statement) + "`");
    Declared declared{type, 0};
    if (end < part.size() && part[end] == '[')
      declared.length = std::stoi(part.substr(end + 1, closing(part, end) - end - 1));
    names[part.substr(0, end)] = declared;
  }
}

// The loops: `for (init; condition; steps)` followed by a block becomes `init;` and
// `while (condition)`, its steps written at the end of the block and before each `continue;` of
// this loop (not of a loop inside it).
std::vector<std::string> rewrite_for_loops(const std::vector<std::string>& lines) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string_view line = trim(lines[i]);
    if (!line.starts_with("for (")) {
      out.push_back(lines[i]);
      continue;
    }
    const std::string indent = indentation(lines[i]);
    const std::size_t open = line.find('(');
    const std::vector<std::string> parts =
        split_top_level(line.substr(open + 1, closing(line, open) - open - 1), ';');
    if (parts.size() != 3 || i + 1 >= lines.size() || trim(lines[i + 1]) != "{")
      fail("unexpected loop `" + std::string(line) + "`");
    std::vector<std::string> steps;
    for (const std::string& step : split_top_level(parts[2], ','))
      if (!step.empty()) steps.push_back(step + ";");
    if (!parts[0].empty()) out.push_back(indent + parts[0] + ";");
    out.push_back(indent + "while (" + (parts[1].empty() ? "true" : parts[1]) + ")");
    // The body: the block from lines[i + 1] to its closing line; loops inside it are rewritten
    // when the outer loop has been (out is scanned again by the caller's loop below).
    int depth = 0;
    int inner_loops = 0;
    std::vector<int> loop_depths;  // the depth at which each enclosing inner loop's block opens
    bool next_block_is_loop = false;
    std::size_t j = i + 1;
    for (; j < lines.size(); ++j) {
      const std::string_view body_line = trim(lines[j]);
      const std::string body_indent = indentation(lines[j]);
      if (body_line.starts_with("}")) {
        --depth;
        if (!loop_depths.empty() && loop_depths.back() == depth) {
          loop_depths.pop_back();
          --inner_loops;
        }
        if (depth == 0) {
          for (const std::string& step : steps) out.push_back(indent + "    " + step);
          out.push_back(lines[j]);
          break;
        }
      }
      if (body_line == "continue;" && inner_loops == 0)
        for (const std::string& step : steps) out.push_back(body_indent + step);
      out.push_back(lines[j]);
      if (body_line.ends_with("{")) {
        if (next_block_is_loop) {
          loop_depths.push_back(depth);
          ++inner_loops;
          next_block_is_loop = false;
        }
        ++depth;
      }
      if (body_line.starts_with("for (") || body_line.starts_with("while (") || body_line == "do")
        next_block_is_loop = true;
    }
    if (j == lines.size()) fail("unclosed loop `" + std::string(line) + "`");
    i = j;
  }
  // Inner loops were copied as they were: rewrite them too.
  const bool more = std::any_of(out.begin(), out.end(), [](const std::string& line) {
    return trim(line).starts_with("for (");
  });
  return more ? rewrite_for_loops(out) : out;
}

// The type of the expression ending just before `end` in `text` (an identifier, a call, an
// indexed or swizzled expression), and where it starts; "" when not known.
struct Operand {
  std::size_t start;
  std::string type;
  int length = 0;  // an array's
};

Operand operand_before(std::string_view text, std::size_t end, const Names& names) {
  if (end == 0) fail("nothing indexed in `" + std::string(text) + "`");
  const char last = text[end - 1];
  if (last == ']' || last == ')') {
    const std::size_t open = opening(text, end - 1);
    if (last == ']') {
      Operand base = operand_before(text, open, names);
      if (base.length > 0) return {base.start, base.type, 0};
      const int size = vector_size(base.type);
      return {base.start, size > 0 ? component_type(base.type) : "", 0};
    }
    std::size_t start = open;
    while (start > 0 && is_identifier_char(text[start - 1])) --start;
    const std::string_view callee = text.substr(start, open - start);
    if (is_type(callee)) return {start, std::string(callee), 0};
    if (callee == "texelFetch" || callee == "texture" || callee == "textureLod" ||
        callee == "textureGrad")
      return {start, "vec4", 0};
    return {start, "", 0};
  }
  std::size_t start = end;
  while (start > 0 && is_identifier_char(text[start - 1])) --start;
  const std::string_view word = text.substr(start, end - start);
  if (start > 0 && text[start - 1] == '.') {  // a swizzle
    const Operand base = operand_before(text, start - 1, names);
    const int size = vector_size(base.type);
    if (size == 0) return {base.start, "", 0};
    const std::string component = component_type(base.type);
    if (word.size() == 1) return {base.start, component, 0};
    const std::string prefix = component == "float" ? "" : component.substr(0, 1);
    return {base.start, prefix + "vec" + std::to_string(word.size()), 0};
  }
  const auto found = names.find(word);
  if (found == names.end()) return {start, "", 0};
  return {start, found->second.type, found->second.length};
}

bool is_integer_literal(std::string_view text) {
  return !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
    return std::isdigit(static_cast<unsigned char>(c)) != 0;
  });
}

// The helpers that read and write a vector's component at a variable index.
std::string at_function(const std::string& vector) {
  return "stochtex_" + vector + "_at";
}
std::string with_function(const std::string& vector) {
  return "stochtex_" + vector + "_with";
}

std::string helper_functions(const std::set<std::string>& vectors) {
  constexpr std::string_view kComponents = "xyzw";
  std::string text;
  for (const std::string& vector : vectors) {
    const int size = vector_size(vector);
    const std::string component = component_type(vector);
    text += component + " " + at_function(vector) + "(" + vector + " v, int i) {\n";
    for (int c = 0; c + 1 < size; ++c)
      text += "    if (i == " + std::to_string(c) + ") {\n        return v." + kComponents[c] +
              ";\n    }\n";
    text += "    return v." + std::string(1, kComponents[size - 1]) + ";\n}\n\n";
    text += vector + " " + with_function(vector) + "(" + vector + " v, int i, " + component +
            " x) {\n    " + vector + " r = v;\n";
    for (int c = 0; c < size; ++c)
      text += "    if (i == " + std::to_string(c) + ") {\n        r." + kComponents[c] +
              " = x;\n    }\n";
    text += "    return r;\n}\n\n";
  }
  return text;
}

// A vector's component at a variable index, `v[i]`, read through stochtex_<vec>_at; the statement
// `v[i] = x;` (or `+=`, ...) as `v = stochtex_<vec>_with(v, int(i), ...);`.
std::string rewrite_indexing(const std::string& statement, const Names& names,
                             std::set<std::string>& vectors) {
  std::string text = statement;
  std::size_t from = 0;
  for (;;) {
    const std::size_t open = text.find('[', from);
    if (open == std::string::npos) return text;
    const std::size_t close = closing(text, open);
    const std::string index(trim(std::string_view(text).substr(open + 1, close - open - 1)));
    if (index.empty() || is_integer_literal(index)) {  // `float[](...)`, `a[2]`
      from = open + 1;
      continue;
    }
    const Operand base = operand_before(text, open, names);
    if (base.length > 0) {
      from = open + 1;
      continue;
    }
    if (vector_size(base.type) == 0)
      fail("a variable index into `" + text.substr(base.start, open - base.start) +
           "` of unknown or unsupported type in `" + statement + "`");
    vectors.insert(base.type);
    const std::string operand = text.substr(base.start, open - base.start);
    const std::string at = at_function(base.type) + "(" + operand + ", int(" + index + "))";
    const std::string_view after = trim(std::string_view(text).substr(close + 1));
    constexpr std::array<std::string_view, 5> kAssignments = {"= ", "+= ", "-= ", "*= ", "/= "};
    const auto assignment =
        std::find_if(kAssignments.begin(), kAssignments.end(),
                     [&](std::string_view op) { return after.starts_with(op); });
    if (trim(std::string_view(text).substr(0, base.start)).empty() &&
        assignment != kAssignments.end()) {
      std::string value = rewrite_indexing(
          std::string(after.substr(assignment->size(), after.size() - assignment->size() - 1)),
          names, vectors);
      if (*assignment != "= ")
        value = at + " " + std::string(assignment->substr(0, 1)) + " (" + value + ")";
      return text.substr(0, base.start) + operand + " = " + with_function(base.type) + "(" +
             operand + ", int(" + index + "), " + value + ");";
    }
    text = text.substr(0, base.start) + at + text.substr(close + 1);
    from = base.start;
  }
}

// A whole array assigned (`a = T[](x, y);`, `a = b;`) or initialised from another
// (`T a[2] = b;`): element by element.
std::string rewrite_array_assignment(const std::string& statement, const Names& names) {
  const std::string_view line = trim(statement);
  const std::string indent = indentation(statement);
  const std::size_t equals = line.find(" = ");
  if (equals == std::string_view::npos || !line.ends_with(";")) return statement;
  const std::string_view target = line.substr(0, equals);
  std::string_view value = line.substr(equals + 3);
  value.remove_suffix(1);
  // `T a[N] = b;`: the initialiser as a constructor of b's elements.
  const std::size_t bracket = target.find('[');
  if (bracket != std::string_view::npos && target.find(' ') != std::string_view::npos) {
    const auto source = names.find(value);
    if (source == names.end() || source->second.length == 0) return statement;
    std::string elements;
    for (int k = 0; k < source->second.length; ++k)
      elements += (k == 0 ? "" : ", ") + std::string(value) + "[" + std::to_string(k) + "]";
    return indent + std::string(target) + " = " + source->second.type + "[](" + elements + ");";
  }
  const auto array = names.find(target);
  if (array == names.end() || array->second.length == 0) return statement;
  std::vector<std::string> elements;
  const auto source = names.find(value);
  if (source != names.end() && source->second.length == array->second.length) {
    for (int k = 0; k < array->second.length; ++k)
      elements.push_back(std::string(value) + "[" + std::to_string(k) + "]");
  } else {
    const std::size_t open = value.find('(');
    if (open == std::string_view::npos || !value.substr(0, open).ends_with("[]"))
      fail("an array assigned from `" + std::string(value) + "`");
    elements = split_top_level(value.substr(open + 1, closing(value, open) - open - 1), ',');
  }
  if (static_cast<int>(elements.size()) != array->second.length)
    fail("an array assigned the wrong length in `" + std::string(line) + "`");
  // The elements are computed before any is stored (one of them may read the array).
  const std::string copy = "stochtex_" + std::string(target);
  std::string text = indent + array->second.type + " " + copy + "[" +
                     std::to_string(elements.size()) + "] = " + array->second.type + "[](";
  for (std::size_t k = 0; k < elements.size(); ++k) text += (k == 0 ? "" : ", ") + elements[k];
  text += ");";
  for (std::size_t k = 0; k < elements.size(); ++k)
    text += " " + std::string(target) + "[" + std::to_string(k) + "] = " + copy + "[" +
            std::to_string(k) + "];";
  return text;
}

}  // namespace

GodotLibrary godot_from_essl(std::string_view essl, std::string_view function) {
  std::vector<std::string> lines;
  for (std::size_t start = 0; start < essl.size();) {
    std::size_t end = essl.find('\n', start);
    if (end == std::string_view::npos) end = essl.size();
    lines.emplace_back(essl.substr(start, end - start));
    start = end + 1;
  }
  GodotLibrary library;
  std::vector<std::string> hoisted;
  std::size_t i = 0;
  for (; i < lines.size(); ++i) {
    const std::string_view line = trim(lines[i]);
    if (line == "void main()") break;
    if (line.empty() || line.starts_with("#version ") || line.starts_with("precision ") ||
        line.starts_with("in ") || line.starts_with("flat in ") || line.starts_with("layout("))
      continue;
    if (line.starts_with("uniform highp sampler")) {
      library.uniforms.push_back("uniform " + std::string(line.substr(14)));
      continue;
    }
    // A global (const array or variable) becomes a local variable: Godot 3.2 takes neither, and
    // a const's initialiser must be constant, which godot_float's uintBitsToFloat() is not.
    std::string_view declaration = line;
    if (declaration.starts_with("const ")) declaration.remove_prefix(6);
    if (!is_type(declaration.substr(0, declaration.find(' '))) || !line.ends_with(";"))
      fail("unexpected global `" + std::string(line) + "`");
    hoisted.push_back("    " + std::string(declaration));
  }
  if (i + 1 >= lines.size() || lines[i + 1] != "{") fail("no main() in the GLSL ES");
  std::size_t last = lines.size();
  while (last > i && trim(lines[last - 1]).empty()) --last;
  if (last <= i + 2 || lines[last - 1] != "}") fail("main() is not the GLSL ES's last function");
  std::vector<std::string> body = hoisted;
  body.insert(body.end(), lines.begin() + static_cast<std::ptrdiff_t>(i) + 2,
              lines.begin() + static_cast<std::ptrdiff_t>(last) - 1);
  if (body.empty() || !trim(body.back()).starts_with("stochtex_result = "))
    fail("main() does not end by storing stochtex_result");
  body.back() = "    return " + std::string(trim(body.back()).substr(18));
  for (std::size_t k = 0; k + 1 < body.size(); ++k)
    if (body[k].find("stochtex_result") != std::string::npos)
      fail("stochtex_result stored before main()'s end");

  Names names;
  for (std::string& line : body) {
    line = rewrite_negated_negatives(rewrite_literals(line));
    // A local const's initialiser may now call uintBitsToFloat(), which Godot's const refuses.
    const std::size_t first = line.find_first_not_of(' ');
    if (first != std::string::npos && line.compare(first, 6, "const ") == 0) line.erase(first, 6);
    std::string_view statement = trim(line);
    if (statement.starts_with("for (")) {
      statement.remove_prefix(5);
      statement = statement.substr(0, statement.find(';'));
    }
    record_declarations(statement, names);
  }
  std::set<std::string> vectors;
  std::string text;
  for (const std::string& line : rewrite_for_loops(body)) {
    std::string statement = line;
    const std::size_t xor_assign = statement.find(" ^= ");
    if (xor_assign != std::string::npos) {
      const std::string target(trim(std::string_view(statement).substr(0, xor_assign)));
      statement = indentation(statement) + target + " = " + target + " ^ (" +
                  statement.substr(xor_assign + 4, statement.size() - xor_assign - 5) + ");";
    }
    statement = rewrite_array_assignment(statement, names);
    text += rewrite_indexing(statement, names, vectors) + "\n";
  }
  library.functions = helper_functions(vectors) + "vec4 " + std::string(function) + "(" +
                      std::string(kGodotArguments) + ")\n{\n" + text + "}\n";
  return library;
}

}  // namespace stochtex::gl
