#pragma once
// The prose of the shader exports' READMEs: the template files of src/gl/readme/, embedded with
// the GLSL (cmake/embed_files.cmake, shaders.hpp) and filled here by the exporter
// (export_shader.cpp, export_material.cpp), which computes only the values. A template's text is
// its file's without the file's last newline, so that a template can be a part of a line or of a
// paragraph as well as whole paragraphs. It holds
//   {{name}}                the value `name`;
//   {{#name}}...{{/name}}   the text between when the flag `name` is set, nothing otherwise;
//   {{^name}}...{{/name}}   the text between when the flag `name` is not set.
// Sections nest. Everything else is the README's text as it is written.

#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace stochtex::gl {

using TemplateValues = std::map<std::string, std::string, std::less<>>;
using TemplateFlags = std::map<std::string, bool, std::less<>>;

// `source`, a template's text, filled with `values` and `flags`. Throws std::logic_error (a bug),
// naming the template `label`, when its sections do not close or the names it holds (shown or
// not) and those of `values` and `flags` differ.
std::string fill_template(std::string_view label, std::string_view source,
                          const TemplateValues& values, const TemplateFlags& flags);

// `parts` one after another with `separator` between each two: the filled templates of a list,
// one per item.
std::string join(const std::vector<std::string>& parts, std::string_view separator = "\n");

// A README template with its values, set one by one:
//   ReadmeTemplate("glsl_usage").set("file", file).set("colour", colour).text()
class ReadmeTemplate {
 public:
  // The template src/gl/readme/<name>.md. Throws std::logic_error when it is not embedded.
  explicit ReadmeTemplate(std::string_view name);

  ReadmeTemplate& set(std::string_view name, std::string value);
  ReadmeTemplate& flag(std::string_view name, bool value);

  // The filled text (fill_template).
  std::string text() const;

 private:
  std::string path_;
  std::string_view source_;
  TemplateValues values_;
  TemplateFlags flags_;
};

}  // namespace stochtex::gl
