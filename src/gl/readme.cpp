// The README templates' filling (readme.hpp).

#include "gl/readme.hpp"

#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/embedded_file.hpp"
#include "gl/shaders.hpp"

namespace stochtex::gl {

std::string fill_template(std::string_view label, std::string_view source,
                          const TemplateValues& values, const TemplateFlags& flags) {
  const auto fail = [label](const std::string& what) {
    return std::logic_error("the README template " + std::string(label) + " " + what);
  };
  std::string text;
  // The open sections: their names and whether their text is shown (theirs and every outer one's).
  std::vector<std::pair<std::string, bool>> sections;
  std::set<std::string, std::less<>> named;
  std::size_t at = 0;
  while (true) {
    const bool shown = sections.empty() || sections.back().second;
    const std::size_t open = source.find("{{", at);
    if (shown) text += source.substr(at, open == std::string_view::npos ? open : open - at);
    if (open == std::string_view::npos) break;
    const std::size_t close = source.find("}}", open);
    if (close == std::string_view::npos) throw fail("has a {{ without }}");
    const std::string_view tag = source.substr(open + 2, close - open - 2);
    at = close + 2;
    const bool section = tag.starts_with('#') || tag.starts_with('^') || tag.starts_with('/');
    const std::string name(section ? tag.substr(1) : tag);
    named.insert(name);
    if (tag.starts_with('/')) {
      if (sections.empty() || sections.back().first != name)
        throw fail("closes '" + name + "', which is not the open section");
      sections.pop_back();
    } else if (section) {
      const auto flag = flags.find(name);
      if (flag == flags.end()) throw fail("needs the flag '" + name + "'");
      sections.emplace_back(name, shown && flag->second == tag.starts_with('#'));
    } else {
      const auto value = values.find(name);
      if (value == values.end()) throw fail("needs the value '" + name + "'");
      if (shown) text += value->second;
    }
  }
  if (!sections.empty()) throw fail("leaves '" + sections.back().first + "' open");
  for (const auto& [given, value] : values)
    if (!named.contains(given)) throw fail("has no value '" + given + "'");
  for (const auto& [given, value] : flags)
    if (!named.contains(given)) throw fail("has no flag '" + given + "'");
  return text;
}

std::string join(const std::vector<std::string>& parts, std::string_view separator) {
  std::string text;
  for (const std::string& part : parts) {
    if (&part != &parts.front()) text += separator;
    text += part;
  }
  return text;
}

ReadmeTemplate::ReadmeTemplate(std::string_view name)
    : path_("gl/readme/" + std::string(name) + ".md") {
  const EmbeddedFile* file = find_embedded(embedded_files(), path_);
  if (file == nullptr) throw std::logic_error("the README template " + path_ + " is not embedded");
  // The file's last newline ends the file, not the template's text (readme.hpp).
  source_ = file->text;
  if (source_.ends_with('\n')) source_.remove_suffix(1);
}

ReadmeTemplate& ReadmeTemplate::set(std::string_view name, std::string value) {
  values_.insert_or_assign(std::string(name), std::move(value));
  return *this;
}

ReadmeTemplate& ReadmeTemplate::flag(std::string_view name, bool value) {
  flags_.insert_or_assign(std::string(name), value);
  return *this;
}

std::string ReadmeTemplate::text() const {
  return fill_template(path_, source_, values_, flags_);
}

}  // namespace stochtex::gl
