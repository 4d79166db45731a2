// The exports' README templates (src/gl/readme.hpp): values, shown and hidden sections, and the
// mistakes a template or its caller can make, each refused with a sentence naming the template.
// (export_language_test.cpp and export_material_test.cpp read the READMEs the templates make.)

#include "gl/readme.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <string_view>

#include "core/embedded_file.hpp"
#include "gl/languages.hpp"
#include "gl/shaders.hpp"

namespace stochtex::readme_test {
namespace {

using gl::fill_template;

std::string refusal(std::string_view source, const gl::TemplateValues& values,
                    const gl::TemplateFlags& flags) {
  try {
    fill_template("test.md", source, values, flags);
  } catch (const std::logic_error& error) {
    return error.what();
  }
  return "accepted";
}

TEST(ReadmeTemplate, FillsValuesAndSections) {
  EXPECT_EQ(fill_template("test.md", "a {{x}} b {{x}}", {{"x", "1"}}, {}), "a 1 b 1");
  const std::string_view source =
      "<{{#on}}shown {{v}}{{^off}} inner{{/off}}{{/on}}{{^on}}not{{/on}}>";
  EXPECT_EQ(fill_template("test.md", source, {{"v", "V"}}, {{"on", true}, {"off", false}}),
            "<shown V inner>");
  EXPECT_EQ(fill_template("test.md", source, {{"v", "V"}}, {{"on", true}, {"off", true}}),
            "<shown V>");
  // A hidden section hides what it holds, an inner section that would show included.
  EXPECT_EQ(fill_template("test.md", source, {{"v", "V"}}, {{"on", false}, {"off", false}}),
            "<not>");
  EXPECT_EQ(fill_template("test.md", "no tags }} here", {}, {}), "no tags }} here");
}

TEST(ReadmeTemplate, RefusesMistakes) {
  EXPECT_EQ(refusal("{{x}}", {}, {}), "the README template test.md needs the value 'x'");
  EXPECT_EQ(refusal("{{#f}}a{{/f}}", {}, {}), "the README template test.md needs the flag 'f'");
  EXPECT_EQ(refusal("a", {{"x", "1"}}, {}), "the README template test.md has no value 'x'");
  EXPECT_EQ(refusal("a", {}, {{"f", true}}), "the README template test.md has no flag 'f'");
  // A value in a hidden section is still the template's, so its caller gives it.
  EXPECT_EQ(refusal("{{#f}}{{x}}{{/f}}", {}, {{"f", false}}),
            "the README template test.md needs the value 'x'");
  EXPECT_EQ(refusal("{{#f}}a", {}, {{"f", true}}), "the README template test.md leaves 'f' open");
  EXPECT_EQ(refusal("{{#f}}{{#g}}a{{/f}}{{/g}}", {}, {{"f", true}, {"g", true}}),
            "the README template test.md closes 'f', which is not the open section");
  EXPECT_EQ(refusal("a {{x", {{"x", "1"}}, {}), "the README template test.md has a {{ without }}");
}

TEST(ReadmeTemplate, ReadsTheEmbeddedFileWithoutItsLastNewline) {
  const EmbeddedFile* file = find_embedded(gl::embedded_files(), "gl/readme/glsl_signature.md");
  ASSERT_NE(file, nullptr);
  EXPECT_TRUE(file->text.ends_with(")\n"));
  EXPECT_EQ(
      gl::ReadmeTemplate("glsl_signature").flag("material", false).set("function", "f").text(),
      "vec4 f(vec2 p, vec2 dpdx, vec2 dpdy, uint seed)");
  EXPECT_THROW(gl::ReadmeTemplate("no_such_template"), std::logic_error);
}

TEST(ReadmeTemplate, EveryCrossCompiledLanguageHasItsBindingSection) {
  for (const gl::LanguageRow& row : gl::kLanguageRows) {
    // GLSL and Godot have READMEs of their own.
    if (row.language == ShaderLanguage::glsl || row.language == ShaderLanguage::godot) continue;
    EXPECT_NE(
        find_embedded(gl::embedded_files(), "gl/readme/binding_" + std::string(row.name) + ".md"),
        nullptr)
        << row.name;
  }
}

}  // namespace
}  // namespace stochtex::readme_test
