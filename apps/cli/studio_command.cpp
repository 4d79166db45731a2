// `stochtex studio [--port N] [--host H]`: the studio, a local web application to analyse an
// exemplar and see, compare and download its models (docs/studio.md), served from this process.

#include <fmt/core.h>

#include <cstdio>
#include <memory>
#include <string>

#include "commands.hpp"
#include "stochtex/error.hpp"
#ifdef STOCHTEX_WITH_GL
#include "web/studio_server.hpp"
#endif

namespace stochtex::cli {
namespace {

// Serves until SIGINT or SIGTERM.
void serve([[maybe_unused]] const std::string& host, [[maybe_unused]] int port) {
#ifdef STOCHTEX_WITH_GL
  web::StudioOptions studio;
  studio.host = host;
  studio.port = port;
  web::serve_studio(studio, [&host](const web::StudioAddress& address) {
    if (!address.loopback)
      fmt::print(stderr,
                 "stochtex studio: warning: listening on {}, not loopback: anyone who can reach "
                 "this address and has the token of the address below can use the studio\n",
                 host);
    fmt::print("stochtex studio: serving {}\n", address.url);
    std::fflush(stdout);
  });
#else
  throw Error(ErrorCode::io,
              "this stochtex was built without the OpenGL backend "
              "(STOCHTEX_BUILD_GL=OFF), which studio needs");
#endif
}

}  // namespace

Command add_studio_command(CLI::App& app) {
  struct Options {
    std::string host = "127.0.0.1";
    int port = 8080;
  };
  auto options = std::make_shared<Options>();
  auto* command = app.add_subcommand(
      "studio", "serve the studio, a web page to analyse an exemplar and compare its models");
  command->add_option("--port", options->port, "TCP port to listen on; 0 picks a free one")
      ->capture_default_str()
      ->check(CLI::Range(0, 65535));
  command
      ->add_option("--host", options->host,
                   "address to listen on. The default, loopback, lets only this machine in; any "
                   "other address (0.0.0.0: every interface) lets in anyone who can reach it and "
                   "has the token of the printed address (?token=...)")
      ->capture_default_str();
  command->footer(
      "\nOpen the printed address in a browser. Ctrl-C (SIGINT) or SIGTERM stops the server.");
  return {command,
          [options] {
            serve(options->host, options->port);
            return 0;
          },
          false};
}

}  // namespace stochtex::cli
