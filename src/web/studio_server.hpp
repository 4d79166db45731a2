#pragma once
// `stochtex studio`'s HTTP server (docs/studio.md): the embedded pages of web/ and the JSON API
// over a StudioStore, on cpp-httplib.

#include <functional>
#include <string>

#include "web/studio_store.hpp"

namespace stochtex::web {

struct StudioOptions {
  std::string host = "127.0.0.1";
  int port = 8080;  // 0: a free port
  StudioLimits limits;
};

// Where the studio listens, once bound.
struct StudioAddress {
  // The page's address: "http://127.0.0.1:8080/", or beyond loopback with the token every request
  // needs, "http://0.0.0.0:8080/?token=<32 hexadecimal digits>".
  std::string url;
  bool loopback = true;  // bound to a loopback address (127.0.0.0/8, ::1)
};

// Binds to options.host:options.port, calls `listening` with the address served, then serves
// until SIGINT, SIGTERM or SIGHUP arrives. Throws Error when it cannot bind. Call it before other
// threads are started: it blocks those signals in this thread and every thread started after, and
// waits for them in a thread of its own.
void serve_studio(const StudioOptions& options,
                  const std::function<void(const StudioAddress& address)>& listening);

}  // namespace stochtex::web
