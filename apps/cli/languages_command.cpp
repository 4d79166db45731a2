// `stochtex languages`: the languages of `export-shader --language`, from their table
// (src/gl/languages.hpp), for people and (--json) scripts.

#include <fmt/core.h>

#include <memory>

#include "commands.hpp"
#include "stochtex/error.hpp"
#ifdef STOCHTEX_WITH_GL
#include "gl/languages.hpp"
#endif

namespace stochtex::cli {

Command add_languages_command(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  auto* command =
      app.add_subcommand("languages", "list the shader languages of export-shader --language");
  command->add_flag("--json", *json, "print one JSON document");
  return {command, [json]() -> int {
#ifdef STOCHTEX_WITH_GL
            fmt::print("{}", *json ? gl::languages_json() + "\n" : gl::languages_text());
            return 0;
#else
            throw Error(ErrorCode::io,
                        "this stochtex was built without the OpenGL backend "
                        "(STOCHTEX_BUILD_GL=OFF), which export-shader needs");
#endif
          }};
}

}  // namespace stochtex::cli
