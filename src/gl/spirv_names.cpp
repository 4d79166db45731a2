// readable_names: one pass over glslang's SPIR-V collects names, types, calls and stores; the
// names are then given in the order of spirv_names.hpp.

#include "gl/spirv_names.hpp"

#include <spirv.h>

#include <bit>
#include <charconv>
#include <map>
#include <set>
#include <stdexcept>
#include <unordered_map>

namespace stochtex::gl {
namespace {

struct SpirvInstruction {
  SpvOp op;
  std::span<const unsigned> operands;  // the words after the opcode's
};

std::vector<SpirvInstruction> spirv_instructions(std::span<const unsigned> spirv) {
  std::vector<SpirvInstruction> code;
  for (std::size_t at = 5; at < spirv.size();) {  // after the header's 5 words
    const unsigned count = spirv[at] >> 16;
    if (count == 0 || at + count > spirv.size())
      throw std::logic_error("readable_names: the SPIR-V is malformed");
    code.push_back({static_cast<SpvOp>(spirv[at] & 0xffffu), spirv.subspan(at + 1, count - 1)});
    at += count;
  }
  return code;
}

// A literal string operand: UTF-8, four bytes a word, lowest first, ending with a zero byte.
std::string spirv_string(std::span<const unsigned> words) {
  std::string text;
  for (const unsigned word : words)
    for (int byte = 0; byte < 4; ++byte) {
      const auto c = static_cast<char>((word >> (8 * byte)) & 0xffu);
      if (c == '\0') return text;
      text.push_back(c);
    }
  return text;
}

// A top-level `const T NAME[N] = T[](a, b, ...);` of the GLSL, one declaration a line as the
// methods write them: its name and its elements' text.
struct GlslConstArray {
  std::string name;
  std::vector<std::string_view> elements;
};

std::vector<GlslConstArray> glsl_const_arrays(std::string_view glsl) {
  std::vector<GlslConstArray> arrays;
  for (std::size_t start = 0; start < glsl.size();) {
    std::size_t end = glsl.find('\n', start);
    if (end == std::string_view::npos) end = glsl.size();
    const std::string_view line = glsl.substr(start, end - start);
    start = end + 1;
    const std::size_t bracket = line.find('[');
    const std::size_t open = line.find("](");
    const std::size_t close = line.rfind(");");
    if (!line.starts_with("const ") || bracket == std::string_view::npos ||
        open == std::string_view::npos || close == std::string_view::npos || close < open)
      continue;
    const std::size_t space = line.rfind(' ', bracket);
    GlslConstArray array{std::string(line.substr(space + 1, bracket - space - 1)), {}};
    const std::string_view list = line.substr(open + 2, close - open - 2);
    for (std::size_t from = 0; from <= list.size();) {
      std::size_t comma = list.find(',', from);
      if (comma == std::string_view::npos) comma = list.size();
      std::string_view element = list.substr(from, comma - from);
      while (element.starts_with(' ')) element.remove_prefix(1);
      array.elements.push_back(element);
      from = comma + 1;
    }
    arrays.push_back(std::move(array));
  }
  return arrays;
}

// Whether the GLSL literal `text` is `word`, a 32-bit constant of a float (else integer) type:
// the float as glslang makes it, the literal's double rounded to float.
bool same_literal(std::string_view text, bool is_float, unsigned word) {
  while (!text.empty() &&
         (text.back() == 'u' || text.back() == 'U' || text.back() == 'f' || text.back() == 'F'))
    text.remove_suffix(1);
  const char* last = text.data() + text.size();
  if (is_float) {
    double value = 0.0;
    const auto [end, error] = std::from_chars(text.data(), last, value);
    return error == std::errc() && end == last &&
           std::bit_cast<unsigned>(static_cast<float>(value)) == word;
  }
  long long value = 0;
  const auto [end, error] = std::from_chars(text.data(), last, value);
  return error == std::errc() && end == last && static_cast<unsigned>(value) == word;
}

}  // namespace

std::vector<SpirvName> readable_names(std::span<const unsigned> spirv, std::string_view glsl) {
  // What the module says, in one pass.
  std::unordered_map<unsigned, std::string> names;  // OpName, non-empty
  std::map<std::pair<unsigned, unsigned>, std::string> member_names;
  std::set<unsigned> named_globally;  // functions, global variables, structs
  std::unordered_map<unsigned, std::vector<unsigned>> parameters;  // of each function
  std::unordered_map<unsigned, std::vector<unsigned>> members;     // struct -> member types
  std::unordered_map<unsigned, unsigned> element;  // array, vector, matrix -> element type
  std::set<unsigned> array_types;
  std::unordered_map<unsigned, bool> scalar_is_float;  // 32-bit int and float types
  std::unordered_map<unsigned, std::pair<unsigned, unsigned>> constants;  // -> type, value
  std::unordered_map<unsigned, unsigned> pointee;                         // pointer type -> type
  std::unordered_map<unsigned, unsigned> type_of;  // pointer's -> its pointer type
  std::unordered_map<unsigned, unsigned> loaded_from;
  std::unordered_map<unsigned, std::span<const unsigned>> chains;  // -> base, indices
  std::set<unsigned> temporaries;  // local variables, and values SPIRV-Cross may declare
  std::vector<std::span<const unsigned>> composites;
  std::vector<std::pair<unsigned, std::span<const unsigned>>> calls, stores;  // in a function
  std::vector<std::pair<unsigned, unsigned>> returns;                         // function, value
  std::unordered_map<unsigned, unsigned> owner;  // parameter or local variable -> its function
  unsigned function = 0;
  for (const SpirvInstruction& i : spirv_instructions(spirv)) {
    const std::span<const unsigned> o = i.operands;
    switch (i.op) {
      case SpvOpName:  // a function's without glslang's signature: `rng_next(struct-...;`
        if (std::string name = spirv_string(o.subspan(1)); !name.empty())
          names[o[0]] = name.substr(0, name.find('('));
        break;
      case SpvOpMemberName:
        member_names[{o[0], o[1]}] = spirv_string(o.subspan(2));
        break;
      case SpvOpTypeInt:
      case SpvOpTypeFloat:
        if (o[1] == 32) scalar_is_float[o[0]] = i.op == SpvOpTypeFloat;
        break;
      case SpvOpTypeArray:
        array_types.insert(o[0]);
        element[o[0]] = o[1];
        break;
      case SpvOpTypeVector:
      case SpvOpTypeMatrix:
        element[o[0]] = o[1];
        break;
      case SpvOpTypeStruct:
        members[o[0]].assign(o.begin() + 1, o.end());
        named_globally.insert(o[0]);
        break;
      case SpvOpTypePointer:
        pointee[o[0]] = o[2];
        break;
      case SpvOpConstant:
        constants[o[1]] = {o[0], o[2]};
        break;
      case SpvOpConstantComposite:
        composites.push_back(o);
        break;
      case SpvOpFunction:
        function = o[1];
        named_globally.insert(function);
        break;
      case SpvOpFunctionParameter:
        parameters[function].push_back(o[1]);
        owner[o[1]] = function;
        type_of[o[1]] = o[0];
        break;
      case SpvOpFunctionCall:
        calls.emplace_back(function, o);
        break;
      case SpvOpVariable:
        type_of[o[1]] = o[0];
        if (o[2] != SpvStorageClassFunction) {
          named_globally.insert(o[1]);
        } else {
          temporaries.insert(o[1]);
          owner[o[1]] = function;
        }
        break;
      case SpvOpLoad:
        loaded_from[o[1]] = o[2];
        break;
      case SpvOpStore:
        stores.emplace_back(function, o);
        break;
      case SpvOpReturnValue:
        returns.emplace_back(function, o[0]);
        break;
      case SpvOpAccessChain:
      case SpvOpInBoundsAccessChain:
        type_of[o[1]] = o[0];
        chains[o[1]] = o.subspan(2);
        break;
      case SpvOpCompositeConstruct:
      case SpvOpPhi:
        temporaries.insert(o[1]);
        break;
      default:
        break;
    }
  }
  // The names a given name must not be: the module's global ones, and the GLSL's in its function
  // (which SPIRV-Cross would rename `_1` if a name given here were declared before them).
  std::set<std::string> taken;
  for (const unsigned id : named_globally)
    if (names.contains(id)) taken.insert(names[id]);
  std::unordered_map<unsigned, std::set<std::string>> local_names;
  for (const auto& [id, in] : owner)
    if (names.contains(id) && names[id] != "param") local_names[in].insert(names[id]);
  const auto available = [&](unsigned in, const std::string& name) {
    return !taken.contains(name) && !local_names[in].contains(name);
  };

  std::vector<SpirvName> given;
  const auto give = [&](unsigned id, const std::string& name) {
    names[id] = name;
    given.push_back({id, name});
  };

  // Constant arrays, by their values.
  const std::vector<GlslConstArray> arrays = glsl_const_arrays(glsl);
  for (const std::span<const unsigned> composite : composites) {
    if (!array_types.contains(composite[0])) continue;
    const std::span<const unsigned> values = composite.subspan(2);
    std::string name;
    for (const GlslConstArray& array : arrays) {
      bool same = array.elements.size() == values.size();
      for (std::size_t k = 0; same && k < values.size(); ++k) {
        const auto constant = constants.find(values[k]);
        same = constant != constants.end() && scalar_is_float.contains(constant->second.first) &&
               same_literal(array.elements[k], scalar_is_float[constant->second.first],
                            constant->second.second);
      }
      if (same) name += (name.empty() ? "" : "_or_") + array.name;
    }
    if (!name.empty() && taken.insert(name).second) give(composite[1], name);
  }

  // Arguments' copies (`<parameter>_argument` where the caller has a name of the parameter's),
  // and results.
  for (const auto& [in, call] : calls) {
    const std::vector<unsigned>& callee = parameters[call[2]];
    for (std::size_t k = 0; k + 3 < call.size() && k < callee.size(); ++k) {
      const unsigned argument = call[k + 3];
      if (!names.contains(argument) || names[argument] != "param" || !names.contains(callee[k]))
        continue;
      const std::string& parameter = names[callee[k]];
      if (available(in, parameter))
        give(argument, parameter);
      else if (available(in, parameter + "_argument"))
        give(argument, parameter + "_argument");
    }
    if (names.contains(call[2]) && !names.contains(call[1]) &&
        available(in, names[call[2]] + "_result"))
      give(call[1], names[call[2]] + "_result");
  }

  // Temporaries: a returned one is the function's result; one stored is named after where: a
  // variable, the last struct member of an access chain, or the base name of a temporary named so
  // (a chain of stores keeps its first name).
  const auto stored = [&](unsigned object) {
    const auto load = loaded_from.find(object);
    const unsigned value = load != loaded_from.end() ? load->second : object;
    return temporaries.contains(value) && !names.contains(value) ? value : 0u;
  };
  for (const auto& [returning, object] : returns) {
    const unsigned value = stored(object);
    if (value != 0 && names.contains(returning) &&
        available(returning, names[returning] + "_result"))
      give(value, names[returning] + "_result");
  }
  std::unordered_map<unsigned, std::string> bases;
  const auto destination = [&](unsigned pointer) {
    unsigned base = pointer;
    std::string member;
    if (const auto chain = chains.find(pointer); chain != chains.end()) {
      base = chain->second[0];
      unsigned type = pointee[type_of[base]];
      for (const unsigned index : chain->second.subspan(1)) {
        if (members.contains(type) && constants.contains(index)) {
          const unsigned k = constants[index].second;
          member = member_names[{type, k}];
          type = members[type][k];
        } else {
          type = element[type];
        }
      }
    }
    if (!member.empty()) return member;
    if (bases.contains(base)) return bases[base];
    return names.contains(base) && names[base] != "param" ? names[base] : std::string();
  };
  for (bool named = true; named;) {
    named = false;
    for (const auto& [in, store] : stores) {
      const unsigned value = stored(store[1]);
      const std::string base = destination(store[0]);
      if (value == 0 || base.empty() || !available(in, base + "_value")) continue;
      bases[value] = base;
      give(value, base + "_value");
      named = true;
    }
  }
  return given;
}

}  // namespace stochtex::gl
