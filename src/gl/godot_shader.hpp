#pragma once
// Godot 3's shading language from the GLSL ES 3.00 that SPIRV-Cross writes (cross_compile.hpp,
// `export-shader --language godot`). Godot 3.2 parses a subset of GLSL ES 3.00 (measured with
// Debian's Godot 3.2.3, docs/engines.md): no structs, no global variables nor global const arrays,
// no `7u` or hexadecimal literals, no `#define`, no `^=`, no for loop with an empty or a
// comma-separated part, no assignment of a whole array and no vector component chosen by a
// variable index; local arrays, `inout`, `texelFetch`, `textureGrad`, `sampler3D` and uint
// arithmetic it has. It also writes its GLSL back with float constants of 6 digits, integer
// literals clamped to 2^31 and negations without parentheses. cross_compile gives SPIRV-Cross a
// module whose functions are all inlined into main() and whose structs are split into their
// members (spirv-opt), so that what is left is written here in that subset, statement by
// statement, without changing what is computed.

#include <string>
#include <string_view>
#include <vector>

namespace stochtex::gl {

// The names of the exported function's arguments in Godot's text (the GLSL wrapper's inputs).
inline constexpr std::string_view kGodotArguments = "vec2 p, vec2 dpdx, vec2 dpdy, uint seed";

struct GodotLibrary {
  // "uniform sampler2D <name>;" (or sampler3D) per texture the function reads, in the GLSL's order.
  std::vector<std::string> uniforms;
  // The helper functions it calls, then `vec4 <function>(vec2 p, vec2 dpdx, vec2 dpdy, uint seed)`.
  std::string functions;
};

// `essl`: SPIRV-Cross's GLSL ES 3.00 of a fragment shader whose only function is main(), reading
// the inputs `p`, `dpdx`, `dpdy` and `seed` and storing `stochtex_result` once, as its last
// statement. Returns main() as `function`, written in Godot 3's subset:
//   - the global const arrays and variables become the function's first local variables (not
//     const: an initialiser may call uintBitsToFloat, below);
//   - `7u` becomes `uint(7)`, and from 2^31 on the conversion of the int of the same bits,
//     `uint(-1403630843)` (Godot 3.2 turns a larger literal into 2^31); a hexadecimal literal its
//     decimal value;
//   - a float literal that printf's %g (6 digits, how Godot writes constants back into GLSL) does
//     not give back becomes its bits, `uintBitsToFloat(uint(1058262330))`;
//   - `a - (-b)` becomes `a + b` (Godot writes `a--b`);
//   - `for (init; condition; steps) { body }` becomes `init; while (condition) { body steps }`,
//     the steps also written before each `continue;` of that loop;
//   - `a ^= b;` becomes `a = a ^ (b);`;
//   - an array assigned whole (`a = float[](x, y);`, `a = b;`, `float a[2] = b;`) is assigned
//     element by element;
//   - a vector's component at a variable index, `v[i]`, is read by a helper function,
//     `stochtex_vec4_at(v, int(i))`, and written by another,
//     `v = stochtex_vec4_with(v, int(i), x);`.
// Every rewrite computes the same floats (Godot's text run as GLSL ES matches the CPU as the ESSL
// export does, export_language_test.cpp). Throws std::logic_error, naming what it met, for a text
// outside what SPIRV-Cross writes for the methods (a bug to fix here, which the tests of every
// method and variant would show).
GodotLibrary godot_from_essl(std::string_view essl, std::string_view function);

}  // namespace stochtex::gl
