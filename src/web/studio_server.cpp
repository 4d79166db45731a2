#include "web/studio_server.hpp"

#include <fmt/core.h>
#include <httplib.h>
#include <malloc.h>
#include <pthread.h>
#include <signal.h>
#include <sys/socket.h>

#include <atomic>
#include <charconv>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <regex>
#include <thread>

#include "gl/languages.hpp"
#include "stochtex/error.hpp"
#include "stochtex/stochtex.hpp"
#include "web/assets.hpp"

namespace stochtex::web {

namespace {

constexpr const char* kJson = "application/json";
constexpr std::string_view kClientCookie = "stochtex_client=";
const std::regex kClientId("[0-9a-f]{16}");
const std::string kId = "([0-9a-f]{16})";  // the ids the store makes
constexpr std::size_t kMaxJsonBody = 64 * 1024;

void send_json(httplib::Response& res, const nlohmann::ordered_json& doc, int status = 200) {
  res.status = status;
  res.set_content(doc.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace),
                  kJson);
}

void send_error(httplib::Response& res, int status, const std::string& message) {
  send_json(res, {{"error", message}}, status);
}

// Runs `work`, answering a StudioError or any other failure as a JSON error.
template <typename Work>
void answer(httplib::Response& res, Work&& work) {
  try {
    work();
  } catch (const StudioError& e) {
    send_error(res, e.status(), e.what());
  } catch (const std::bad_alloc&) {
    send_error(res, 503, "the server ran out of memory for this request; try a smaller one");
  } catch (const std::exception& e) {
    send_error(res, 500, fmt::format("the server failed: {}", e.what()));
  }
}

httplib::Server::Handler guarded(
    std::function<void(const httplib::Request&, httplib::Response&)> handler) {
  return [handler = std::move(handler)](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] { handler(req, res); });
  };
}

std::string too_large(std::size_t limit) {
  return fmt::format("the request body is larger than the limit of {} bytes; send a smaller one",
                     limit);
}

// A handler of the request's body, read here up to `limit` bytes: httplib's own limit
// (set_payload_max_length) holds only for bodies with a Content-Length, not for chunked ones.
httplib::Server::HandlerWithContentReader with_body(
    std::size_t limit,
    std::function<void(const httplib::Request&, httplib::Response&, const std::string&)> handler) {
  return [limit, handler = std::move(handler)](const httplib::Request& req, httplib::Response& res,
                                               const httplib::ContentReader& reader) {
    answer(res, [&] {
      std::string body;
      bool over = false;
      const bool read = reader([&](const char* data, std::size_t length) {
        over = body.size() + length > limit;
        if (!over) body.append(data, length);
        return !over;
      });
      // httplib refuses a Content-Length over set_payload_max_length itself (status 413).
      if (over || res.status == 413) throw StudioError(413, too_large(limit));
      if (!read) throw StudioError(400, "the request body could not be read; send it again");
      handler(req, res, body);
    });
  };
}

// The browser client's id: the cookie set with the page, or an X-Stochtex-Client header.
std::optional<std::string> client_of(const httplib::Request& req) {
  std::string id = req.get_header_value("X-Stochtex-Client");
  if (id.empty()) {
    const std::string cookies = req.get_header_value("Cookie");
    for (std::size_t at = cookies.find(kClientCookie); at != std::string::npos;
         at = cookies.find(kClientCookie, at + 1))
      if (at == 0 || cookies[at - 1] == ' ' || cookies[at - 1] == ';') {
        const std::size_t from = at + kClientCookie.size();
        id = cookies.substr(from, cookies.find(';', from) - from);
        break;
      }
  }
  if (!std::regex_match(id, kClientId)) return std::nullopt;
  return id;
}

// The id of the browser client sending a request that changes something. Requiring it keeps
// other web sites out: the cookie is SameSite=Strict, and a page elsewhere cannot send the header
// without a CORS permission the studio never gives.
std::string required_client(const httplib::Request& req) {
  auto client = client_of(req);
  if (!client)
    throw StudioError(403,
                      "this request carries no studio client id; load the studio page "
                      "first (it sets the cookie) or send an X-Stochtex-Client header of "
                      "16 hexadecimal digits");
  return *client;
}

template <typename T>
std::optional<T> parse_number(const std::string& text) {
  T value{};
  const char* end = text.data() + text.size();
  const auto [at, error] = std::from_chars(text.data(), end, value);
  if (error != std::errc{} || at != end) return std::nullopt;
  if constexpr (std::is_floating_point_v<T>)
    if (!std::isfinite(value)) return std::nullopt;
  return value;
}

// The query parameter `name` as a T, `fallback` when absent; a 400 when it is not one.
template <typename T>
T query(const httplib::Request& req, const char* name, T fallback, const char* what) {
  if (!req.has_param(name)) return fallback;
  const std::string text = req.get_param_value(name);
  const auto value = parse_number<T>(text);
  if (!value)
    throw StudioError(400, fmt::format("the query parameter {}='{}' is not {}", name, text, what));
  return *value;
}

std::uint32_t query_seed(const httplib::Request& req) {
  return query<std::uint32_t>(req, "seed", 0, "a seed from 0 to 4294967295");
}

std::string default_error(const httplib::Request& req, int status, std::size_t max_body) {
  switch (status) {
    case 404:
      return fmt::format("there is nothing at '{}'; the studio serves /, /web/ and /api/",
                         req.path);
    case 405:
      return fmt::format("'{}' does not take the method {}", req.path, req.method);
    case 413:
      return too_large(max_body);
    case 414:
    case 431:
      return "the request's address or headers are too long";
    default:
      return fmt::format("the request failed with HTTP status {}", status);
  }
}

bool allowed_host_header(const std::string& header) {
  if (header.empty()) return true;
  const std::string name = header.front() == '[' ? header.substr(0, header.find(']') + 1)
                                                 : header.substr(0, header.find(':'));
  return name == "localhost" || name == "[::1]" || name.starts_with("127.");
}

// The JSON body of an edit ({"group", then the fields of the model's edit capability, each
// optional with `stochtex edit`'s default}; the store reads it against the capability's records).
nlohmann::ordered_json edit_body(const std::string& text) {
  auto body = nlohmann::ordered_json::parse(text, nullptr, false);
  if (body.is_discarded() || !body.is_object())
    throw StudioError(400,
                      "the body is not a JSON object; send {\"group\": name, ...} with the fields "
                      "of the method's edit (`stochtex methods --json`: \"edit\")");
  return body;
}

void add_routes(httplib::Server& server, StudioStore& store) {
  server.Get("/", guarded([](const httplib::Request& req, httplib::Response& res) {
               const EmbeddedFile* page = find_embedded(embedded_files(), "studio/index.html");
               if (page == nullptr) throw StudioError(500, "the studio page is missing");
               res.set_content(std::string(page->text), std::string(content_type(page->name)));
               if (!client_of(req)) {
                 std::random_device random;
                 res.set_header("Set-Cookie", fmt::format("{}{:08x}{:08x}; Path=/; SameSite=Strict",
                                                          kClientCookie, random(), random()));
               }
             }));
  server.Get("/web/(.+)", guarded([](const httplib::Request& req, httplib::Response& res) {
               const EmbeddedFile* file = find_embedded(embedded_files(), req.matches[1].str());
               if (file == nullptr) throw StudioError(404, default_error(req, 404, 0));
               res.set_content(std::string(file->text), std::string(content_type(file->name)));
             }));
  server.Get("/api/methods", guarded([](const httplib::Request&, httplib::Response& res) {
               res.set_content(methods_json(), kJson);
             }));
  server.Get("/api/languages", guarded([](const httplib::Request&, httplib::Response& res) {
               res.set_content(gl::languages_json(), kJson);
             }));
  server.Post("/api/exemplars",
              with_body(store.limits().max_upload_bytes,
                        [&store](const httplib::Request& req, httplib::Response& res,
                                 const std::string& body) {
                          required_client(req);
                          send_json(res, store.add_exemplar(body), 201);
                        }));
  server.Get("/api/exemplars/" + kId + "/(image|gaussian)\\.png",
             guarded([&store](const httplib::Request& req, httplib::Response& res) {
               res.set_content(store.exemplar_png(req.matches[1], req.matches[2] == "gaussian"),
                               "image/png");
             }));
  server.Post(
      "/api/analyses",
      with_body(kMaxJsonBody, [&store](const httplib::Request& req, httplib::Response& res,
                                       const std::string& text_body) {
        const std::string client = required_client(req);
        const auto body = nlohmann::ordered_json::parse(text_body, nullptr, false);
        if (body.is_discarded() || !body.is_object())
          throw StudioError(400,
                            "the body is not a JSON object; send {\"exemplar\": id, "
                            "\"method\": name, \"params\": {...}, \"seed\": n}");
        const auto text = [&body](const char* key) {
          if (!body.contains(key) || !body[key].is_string())
            throw StudioError(400, fmt::format("the JSON body needs \"{}\" as a string", key));
          return body[key].get<std::string>();
        };
        std::uint32_t seed = 0;
        if (body.contains("seed")) {
          if (!body["seed"].is_number_unsigned() ||
              body["seed"].get<std::uint64_t>() > std::numeric_limits<std::uint32_t>::max())
            throw StudioError(400, "\"seed\" must be an integer from 0 to 4294967295");
          seed = body["seed"].get<std::uint32_t>();
        }
        const std::string id =
            store.start_analysis(client, text("exemplar"), text("method"),
                                 body.value("params", nlohmann::ordered_json::object()), seed);
        send_json(res, store.analysis_status(id), 202);
      }));
  server.Get("/api/analyses/" + kId,
             guarded([&store](const httplib::Request& req, httplib::Response& res) {
               send_json(res, store.analysis_status(req.matches[1]));
             }));
  server.Delete("/api/analyses/" + kId,
                guarded([&store](const httplib::Request& req, httplib::Response& res) {
                  send_json(res, store.cancel_analysis(req.matches[1], required_client(req)));
                }));
  server.Get("/api/models/" + kId + "\\.stx",
             guarded([&store](const httplib::Request& req, httplib::Response& res) {
               res.set_content(store.model_file(req.matches[1]), "application/octet-stream");
               res.set_header("Content-Disposition",
                              fmt::format("attachment; filename=\"{}.stx\"", req.matches[1].str()));
             }));
  server.Get("/api/models/" + kId + "/render\\.png",
             guarded([&store](const httplib::Request& req, httplib::Response& res) {
               RenderRequest render;
               const char* side = "a whole number of pixels";
               render.width = query(req, "width", render.width, side);
               render.height = query(req, "height", render.height, side);
               render.seed = query_seed(req);
               render.scale = query(req, "scale", render.scale, "a finite number");
               render.origin.x = query(req, "x", 0.0, "a finite number");
               render.origin.y = query(req, "y", 0.0, "a finite number");
               res.set_content(store.render_png(req.matches[1], render), "image/png");
             }));
  server.Get("/api/models/" + kId + "/web/(exact|fast)/([A-Za-z0-9_.-]+)",
             guarded([&store](const httplib::Request& req, httplib::Response& res) {
               const std::string name = req.matches[3];
               res.set_content(store.web_file(req.matches[1],
                                              req.matches[2] == "exact" ? ShaderVariant::exact
                                                                        : ShaderVariant::fast,
                                              name),
                               std::string(content_type(name)));
             }));
  // Any word names the language, so that the table (gl/languages.hpp) is the one list of them.
  server.Get(
      "/api/models/" + kId + "/shader-(exact|fast)-([A-Za-z0-9_]+)\\.zip",
      guarded([&store](const httplib::Request& req, httplib::Response& res) {
        const gl::LanguageRow* language = gl::find_language(req.matches[3].str());
        if (language == nullptr)
          throw StudioError(404, fmt::format("there is no shader language '{}'; the export "
                                             "writes {} (GET /api/languages)",
                                             req.matches[3].str(), gl::language_names()));
        ShaderExportOptions options;
        options.variant = req.matches[2] == "exact" ? ShaderVariant::exact : ShaderVariant::fast;
        options.language = language->language;
        res.set_content(store.shader_zip(req.matches[1], options), "application/zip");
        res.set_header("Content-Disposition",
                       fmt::format("attachment; filename=\"{}-shader-{}-{}.zip\"",
                                   req.matches[1].str(), req.matches[2].str(), language->name));
      }));
  server.Get("/api/models/" + kId + "/groups",
             guarded([&store](const httplib::Request& req, httplib::Response& res) {
               send_json(res, store.edit_groups(req.matches[1]));
             }));
  server.Post("/api/models/" + kId + "/edit",
              with_body(kMaxJsonBody, [&store](const httplib::Request& req, httplib::Response& res,
                                               const std::string& text) {
                required_client(req);
                send_json(res, {{"model", store.edit_model(req.matches[1], edit_body(text))}}, 201);
              }));
  server.Get("/api/models/" + kId + "/compare",
             guarded([&store](const httplib::Request& req, httplib::Response& res) {
               send_json(res, store.compare(req.matches[1], query_seed(req)));
             }));
}

// Serves until a signal arrives or `done` is set.
void wait_for_signal(httplib::Server& server, const std::atomic<bool>& done) {
  sigset_t signals;
  sigemptyset(&signals);
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&signals, signal_number);
  const timespec interval{0, 200'000'000};
  while (!done) {
    if (::sigtimedwait(&signals, nullptr, &interval) > 0) {
      // stop() does nothing before listen_after_bind() has started: a signal that came first
      // waits for it.
      while (!done && !server.is_running())
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      server.stop();
      return;
    }
  }
}

}  // namespace

bool is_loopback_host(const std::string& host) {
  return host == "localhost" || host == "::1" || host.starts_with("127.");
}

void serve_studio(const StudioOptions& options,
                  const std::function<void(const std::string& url)>& listening) {
  sigset_t signals;
  sigemptyset(&signals);
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&signals, signal_number);
  ::pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  // Buffers of 256 KiB and more (images, PNGs, request bodies) are mapped and unmapped on their
  // own rather than left in the request threads' heaps, where glibc's dynamic threshold would put
  // them after the first free: the server's memory then follows what it holds.
  ::mallopt(M_MMAP_THRESHOLD, 256 * 1024);
  StudioStore store(options.limits);
  httplib::Server server;
  server.new_task_queue = [] { return new httplib::ThreadPool(8); };
  server.set_payload_max_length(options.limits.max_upload_bytes);
  // SO_REUSEADDR (a restart may bind while old connections linger) but not httplib's default
  // SO_REUSEPORT, with which a second server could bind the same port and take its connections.
  server.set_socket_options([](socket_t sock) {
    const int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
  });
  server.set_keep_alive_timeout(2);
  server.set_default_headers(
      {{"X-Content-Type-Options", "nosniff"},
       {"Cache-Control", "no-store"},
       {"Referrer-Policy", "no-referrer"},
       {"Content-Security-Policy", "default-src 'self' blob: data:; frame-ancestors 'none'"}});
  const bool loopback = is_loopback_host(options.host);
  // A loopback server answers only requests addressed to a loopback name, so that a web page
  // elsewhere cannot reach it by pointing its own domain name at 127.0.0.1 (DNS rebinding).
  server.set_pre_routing_handler([loopback](const httplib::Request& req, httplib::Response& res) {
    if (loopback && !allowed_host_header(req.get_header_value("Host"))) {
      send_error(res, 403, "this studio answers only requests to localhost or 127.0.0.1");
      return httplib::Server::HandlerResponse::Handled;
    }
    return httplib::Server::HandlerResponse::Unhandled;
  });
  const std::size_t max_body = options.limits.max_upload_bytes;
  server.set_error_handler(httplib::Server::HandlerWithResponse(
      [max_body](const httplib::Request& req, httplib::Response& res) {
        if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
        send_error(res, res.status, default_error(req, res.status, max_body));
        return httplib::Server::HandlerResponse::Handled;
      }));
  add_routes(server, store);

  const int port = options.port == 0 ? server.bind_to_any_port(options.host)
                   : server.bind_to_port(options.host, options.port) ? options.port
                                                                     : -1;
  if (port < 0)
    throw Error(ErrorCode::io,
                fmt::format("cannot listen on {} port {}: the port is in use or the address is not "
                            "this machine's; choose another --port (0 picks a free one) or --host",
                            options.host, options.port));
  const std::string host =
      options.host.find(':') != std::string::npos ? "[" + options.host + "]" : options.host;
  listening(fmt::format("http://{}:{}/", host, port));
  std::atomic<bool> done = false;
  std::thread signal_waiter([&] { wait_for_signal(server, done); });
  server.listen_after_bind();
  done = true;
  signal_waiter.join();
}

}  // namespace stochtex::web
