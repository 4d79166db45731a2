// The look-ups and listings of the language table (languages.hpp).

#include "gl/languages.hpp"

#include <nlohmann/json.hpp>

namespace stochtex::gl {
namespace {

bool is_default(const LanguageRow& row) {
  return row.language == ShaderExportOptions{}.language;
}

}  // namespace

const LanguageRow* find_language(std::string_view name) {
  for (const LanguageRow& row : kLanguageRows)
    if (row.name == name) return &row;
  return nullptr;
}

std::string language_names() {
  std::string text;
  for (std::size_t i = 0; i < kLanguageRows.size(); ++i)
    text += std::string(i == 0 ? "" : (i + 1 == kLanguageRows.size() ? " or " : ", ")) +
            std::string(kLanguageRows[i].name);
  return text;
}

std::string languages_text() {
  std::string text;
  for (const LanguageRow& row : kLanguageRows)
    text += std::string(row.name) + ": " + std::string(row.title) + " for " +
            std::string(row.targets) + " (stochtex_<method>" + std::string(row.extension) + ")" +
            (is_default(row) ? "; the default\n" : "\n");
  return text;
}

std::string languages_json() {
  auto list = nlohmann::ordered_json::array();
  for (const LanguageRow& row : kLanguageRows)
    list.push_back({{"name", row.name},
                    {"title", row.title},
                    {"targets", row.targets},
                    {"extension", row.extension},
                    {"default", is_default(row)}});
  return list.dump(2);
}

}  // namespace stochtex::gl
