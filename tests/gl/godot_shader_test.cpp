// godot_from_essl (src/gl/godot_shader.hpp): each rewrite on the forms SPIRV-Cross writes, and
// the refusals of what it does not handle. The rewrites' result as a whole runs as GLSL ES in
// export_language_test.cpp (ExportLanguage.GodotText*) and in Godot itself in tests/godot.
#include "gl/godot_shader.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace stochtex::godot_shader_test {
namespace {

// A fragment shader as SPIRV-Cross writes it for cross_compile's Godot path: `globals` after the
// header, `body` as main()'s statements, which end by storing stochtex_result.
std::string essl(const std::string& globals, const std::string& body) {
  return "#version 300 es\nprecision highp float;\nprecision highp int;\n\n" + globals +
         "\nuniform highp sampler2D stochtex_data;\n\nlayout(location = 0) out vec4 "
         "stochtex_result;\nin vec2 p;\nin vec2 dpdx;\nin vec2 dpdy;\nflat in uint seed;\n\n"
         "void main()\n{\n" +
         body + "    stochtex_result = result;\n}\n\n";
}

std::string godot(const std::string& globals, const std::string& body) {
  return gl::godot_from_essl(essl(globals, body), "stochtex_test").functions;
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(GodotShader, WritesMainAsTheFunctionWithItsUniforms) {
  const gl::GodotLibrary library =
      gl::godot_from_essl(essl("", "    vec4 result = vec4(p, dpdx.x, float(seed));\n"), "f");
  ASSERT_EQ(library.uniforms.size(), 1u);
  EXPECT_EQ(library.uniforms[0], "uniform sampler2D stochtex_data;");
  EXPECT_EQ(library.functions,
            "vec4 f(vec2 p, vec2 dpdx, vec2 dpdy, uint seed)\n{\n"
            "    vec4 result = vec4(p, dpdx.x, float(seed));\n    return result;\n}\n");
}

TEST(GodotShader, WritesLiteralsGodotReadsBack) {
  const std::string text = godot("",
                                 "    uint a = 7u + 0x10u + 2891336453u + 2147483648u;\n"
                                 "    int b = 0x10 - 1;\n"
                                 "    float c = 0.5 + 0.57735025882720947265625 + 1.0e-10;\n"
                                 "    vec4 result = vec4(float(a), float(b), c, 0.0);\n");
  // uint(N) below 2^31, the int of the same bits above (Godot turns 2891336453 into 2^31).
  EXPECT_TRUE(has(text, "uint a = uint(7) + uint(16) + uint(-1403630843) + uint(-2147483647 - 1);"))
      << text;
  EXPECT_TRUE(has(text, "int b = 16 - 1;")) << text;
  // Godot writes a float constant with 6 significant digits: one they do not give back goes as
  // its bits (1058262330 is 0x3f13cd3a, the float nearest 0.57735025...).
  EXPECT_TRUE(has(text, "float c = 0.5 + uintBitsToFloat(uint(1058262330)) + 1.0e-10;")) << text;
}

TEST(GodotShader, MovesGlobalsIntoTheFunction) {
  const std::string text = godot("const float _10[2] = float[](1.0, 2.0);\nfloat _11;\n",
                                 "    vec4 result = vec4(_10[int(p.x)]);\n");
  EXPECT_TRUE(has(text, "{\n    float _10[2] = float[](1.0, 2.0);\n    float _11;\n")) << text;
}

TEST(GodotShader, WritesForLoopsAsWhileLoops) {
  const std::string text = godot("",
                                 "    float s = 0.0;\n"
                                 "    float t = 0.0;\n"
                                 "    for (int i = 0; i < 4; s = t, i++)\n"
                                 "    {\n"
                                 "        t = s + 1.0;\n"
                                 "        if (t > 2.0)\n"
                                 "        {\n"
                                 "            continue;\n"
                                 "        }\n"
                                 "        for (;;)\n"
                                 "        {\n"
                                 "            continue;\n"
                                 "        }\n"
                                 "        do\n"
                                 "        {\n"
                                 "            continue;\n"
                                 "        } while(false);\n"
                                 "    }\n"
                                 "    vec4 result = vec4(s);\n");
  EXPECT_FALSE(has(text, "for (")) << text;
  EXPECT_TRUE(has(text, "    int i = 0;\n    while (i < 4)\n    {\n")) << text;
  // The steps before this loop's continue and at the end of its body, one statement a line; not
  // before the continues of the loops inside it.
  EXPECT_TRUE(has(text, "            s = t;\n            i++;\n            continue;\n")) << text;
  EXPECT_TRUE(has(text, "        s = t;\n        i++;\n    }\n")) << text;
  EXPECT_TRUE(has(text, "        while (true)\n        {\n            continue;\n        }\n"))
      << text;
  EXPECT_TRUE(has(text, "        do\n        {\n            continue;\n        } while(false);\n"))
      << text;
}

TEST(GodotShader, WritesCompoundXorAndNegatedNegatives) {
  const std::string text = godot("",
                                 "    uint a = seed;\n"
                                 "    a ^= (a >> 16u);\n"
                                 "    float b = p.x - (-2.5) - (-1.5e-07);\n"
                                 "    float c = b - (-(p.y * 2.0)) - (-float(a));\n"
                                 "    vec4 result = vec4(float(a), b, c, 0.0);\n");
  EXPECT_TRUE(has(text, "    a = a ^ ((a >> uint(16)));\n")) << text;
  // Godot writes `(-2.5)` back as `-2.5`, and `x--2.5` is not GLSL.
  EXPECT_TRUE(has(text, "float b = p.x + 2.5 + 1.5e-07;")) << text;
  EXPECT_TRUE(has(text, "float c = b + (p.y * 2.0) + float(a);")) << text;
  // A negation of several terms would not be the same sum: refused (SPIRV-Cross writes none).
  EXPECT_THROW(godot("", "    vec4 result = vec4(p.x - (-p.y + 1.0));\n"), std::logic_error);
  EXPECT_THROW(godot("", "    vec4 result = vec4(-(-p.y));\n"), std::logic_error);
}

TEST(GodotShader, AssignsArraysElementByElement) {
  const std::string text = godot("",
                                 "    float a[2] = float[](p.x, p.y);\n"
                                 "    float b[2] = a;\n"
                                 "    a = float[](a[1], a[0]);\n"
                                 "    b = a;\n"
                                 "    vec4 result = vec4(a[0], a[1], b[0], b[1]);\n");
  EXPECT_TRUE(has(text, "float b[2] = float[](a[0], a[1]);")) << text;
  // Every element computed before the first is stored (a swap).
  EXPECT_TRUE(has(text,
                  "float stochtex_a[2] = float[](a[1], a[0]); a[0] = stochtex_a[0]; "
                  "a[1] = stochtex_a[1];"))
      << text;
  EXPECT_TRUE(has(text, "b[0] = stochtex_b[0]; b[1] = stochtex_b[1];")) << text;
}

TEST(GodotShader, ReadsAndWritesVectorComponentsAtAVariableIndex) {
  const std::string text = godot("",
                                 "    int i = int(p.x);\n"
                                 "    float c[3] = float[](1.0, 2.0, 3.0);\n"
                                 "    vec4 v = vec4(0.0);\n"
                                 "    v[i] = c[i] + v[2];\n"
                                 "    v[i] += texelFetch(stochtex_data, ivec2(0), 0)[i];\n"
                                 "    uvec2 u = uvec2(seed);\n"
                                 "    vec4 result = vec4(v.xyz[i], float(u[i]), 0.0, 0.0);\n");
  // An array's element and a constant component as they are; a vector's at a variable index
  // through the helpers, declared before the function.
  EXPECT_TRUE(has(text, "v = stochtex_vec4_with(v, int(i), c[i] + v[2]);")) << text;
  EXPECT_TRUE(has(text,
                  "v = stochtex_vec4_with(v, int(i), stochtex_vec4_at(v, int(i)) + "
                  "(stochtex_vec4_at(texelFetch(stochtex_data, ivec2(0), 0), int(i))));"))
      << text;
  EXPECT_TRUE(has(text,
                  "vec4(stochtex_vec3_at(v.xyz, int(i)), float(stochtex_uvec2_at(u, "
                  "int(i))), 0.0, 0.0)"))
      << text;
  for (const char* helper :
       {"float stochtex_vec4_at(vec4 v, int i)", "vec4 stochtex_vec4_with(vec4 v, int i, float x)",
        "float stochtex_vec3_at(vec3 v, int i)", "uint stochtex_uvec2_at"})
    EXPECT_LT(text.find(helper), text.find("vec4 stochtex_test(")) << helper;
}

TEST(GodotShader, RefusesWhatItDoesNotHandle) {
  // A struct left by spirv-opt, main() not last, an unknown indexed expression, no result.
  EXPECT_THROW(godot("struct S\n{\n    float a;\n};\n", "    vec4 result = vec4(0.0);\n"),
               std::logic_error);
  EXPECT_THROW(godot("", "    int i = int(p.x);\n    vec4 result = vec4((p + p)[i]);\n"),
               std::logic_error);
  EXPECT_THROW(gl::godot_from_essl("void main()\n{\n    int a = 0;\n}\n", "f"), std::logic_error);
  EXPECT_THROW(
      gl::godot_from_essl(essl("", "    vec4 result = vec4(0.0);\n") + "void g()\n{\n}\n", "f"),
      std::logic_error);
}

}  // namespace
}  // namespace stochtex::godot_shader_test
