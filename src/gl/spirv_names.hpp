#pragma once
// Names for what glslang leaves unnamed in a library's SPIR-V, given to SPIRV-Cross so that the
// exported GLSL ES, HLSL and Metal say `tiling_lod_of_width_result` and `width` where they said
// `_1030` and `param_5` (cross_compile.cpp).
//
// glslang names every variable, parameter, struct, member and function of the GLSL (OpName,
// OpMemberName) whether or not it writes debug information (which adds line numbers, not names),
// and SPIRV-Cross writes those names. What it writes as `_<id>` are values that no GLSL variable
// holds, and `param`, `param_1`, ... are glslang's copies of a call's arguments. Each gets:
//  - an argument's copy: the name of the callee's parameter it is passed as;
//  - a function call's result: `<function>_result`;
//  - a local temporary (a `?:`'s variable, an array or struct constructed, a short-circuit's
//    value) stored into a variable or struct member: `<that name>_value`;
//  - a constant array: the name of the top-level GLSL `const` array with its values, joined by
//    `_or_` where several have the same values (glslang makes them one constant).
// A name that a function, global variable or struct already has is not given; SPIRV-Cross appends
// _1, _2, ... where a name repeats within a function. Only names change: SPIRV-Cross writes the
// same code.

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace stochtex::gl {

struct SpirvName {
  unsigned id = 0;
  std::string name;
};

// The names to give (spvc_compiler_set_name) in `spirv`, glslang's module of `glsl` (GLSL 4.50),
// in a fixed order: the same module gets the same names.
std::vector<SpirvName> readable_names(std::span<const unsigned> spirv, std::string_view glsl);

}  // namespace stochtex::gl
