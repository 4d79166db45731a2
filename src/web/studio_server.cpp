#include "web/studio_server.hpp"

#include <fmt/core.h>
#include <httplib.h>
#include <malloc.h>
#include <netdb.h>
#include <netinet/in.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <random>
#include <regex>
#include <semaphore>
#include <thread>
#include <vector>

#include "gl/languages.hpp"
#include "stochtex/error.hpp"
#include "stochtex/stochtex.hpp"
#include "web/assets.hpp"

namespace stochtex::web {

namespace {

constexpr const char* kJson = "application/json";
constexpr std::string_view kClientCookie = "stochtex_client";
const std::regex kClientId("[0-9a-f]{16}");
const std::string kId = "([0-9a-f]{16})";  // the ids the store makes
constexpr std::size_t kMaxJsonBody = 64 * 1024;

// What a connection may hold and for how long, so that slow or idle clients cannot take the
// server from the others (docs/studio.md, "Safety"). Each connection is served by a thread of its
// own, up to kConnectionThreads at once (more wait their turn).
constexpr std::size_t kConnectionThreads = 64;
// Uploads read and decoded at once (the others wait): at most this many bodies of up to
// StudioLimits::max_upload_bytes are held, however many connections upload.
constexpr std::ptrdiff_t kUploadSlots = 8;
using UploadSlots = std::counting_semaphore<kUploadSlots>;

// One of the upload slots, held while it lives.
class UploadSlot {
 public:
  explicit UploadSlot(UploadSlots& slots) : slots_(slots) { slots_.acquire(); }
  ~UploadSlot() { slots_.release(); }
  UploadSlot(const UploadSlot&) = delete;
  UploadSlot& operator=(const UploadSlot&) = delete;

 private:
  UploadSlots& slots_;
};

// The wait for a request's first byte, on a new connection and between the requests of one kept
// alive.
constexpr int kIdleSeconds = 2;
// A request's head (request line and headers): at most kMaxHead bytes, all within kHeadTime of its
// first byte however slowly they come.
constexpr std::size_t kMaxHead = 64 * 1024;
constexpr auto kHeadTime = std::chrono::seconds(3);
// A request's body, and then its answer, each within kTransferTime.
constexpr auto kTransferTime = std::chrono::seconds(30);
// The longest wait for the client to send or take a byte.
constexpr auto kStallTime = std::chrono::seconds(5);

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

// The value of the request's cookie `name`, empty when it has none.
std::string cookie(const httplib::Request& req, std::string_view name) {
  const std::string cookies = req.get_header_value("Cookie");
  const std::string key = std::string(name) + "=";
  for (std::size_t at = cookies.find(key); at != std::string::npos; at = cookies.find(key, at + 1))
    if (at == 0 || cookies[at - 1] == ' ' || cookies[at - 1] == ';') {
      const std::size_t from = at + key.size();
      return cookies.substr(from, cookies.find(';', from) - from);
    }
  return {};
}

// The browser client's id: the cookie set with the page, or an X-Stochtex-Client header.
std::optional<std::string> client_of(const httplib::Request& req) {
  std::string id = req.get_header_value("X-Stochtex-Client");
  if (id.empty()) id = cookie(req, kClientCookie);
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
    case 400:
      return fmt::format(
          "the request could not be read: its head (request line and headers) must be HTTP/1.1, "
          "at most {} KiB and arrive within {} s",
          kMaxHead / 1024, kHeadTime.count());
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

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

// The numeric address and port of a socket: its own (getsockname) or its peer's (getpeername).
void socket_address(socket_t sock, bool peer, std::string& ip, int& port) {
  sockaddr_storage address{};
  socklen_t length = sizeof(address);
  auto* generic = reinterpret_cast<sockaddr*>(&address);
  if ((peer ? ::getpeername(sock, generic, &length) : ::getsockname(sock, generic, &length)) != 0)
    return;
  std::array<char, NI_MAXHOST> host{};
  std::array<char, NI_MAXSERV> service{};
  if (::getnameinfo(generic, length, host.data(), host.size(), service.data(), service.size(),
                    NI_NUMERICHOST | NI_NUMERICSERV) != 0)
    return;
  ip = host.data();
  std::from_chars(service.data(), service.data() + std::strlen(service.data()), port);
}

// Whether the socket is bound to a loopback address (127.0.0.0/8, ::1 or ::ffff:127.0.0.0/104).
bool bound_to_loopback(socket_t sock) {
  sockaddr_storage address{};
  socklen_t length = sizeof(address);
  if (::getsockname(sock, reinterpret_cast<sockaddr*>(&address), &length) != 0) return false;
  if (address.ss_family == AF_INET) {
    sockaddr_in v4{};
    std::memcpy(&v4, &address, sizeof(v4));
    return (ntohl(v4.sin_addr.s_addr) >> 24) == 127;
  }
  if (address.ss_family != AF_INET6) return false;
  sockaddr_in6 v6{};
  std::memcpy(&v6, &address, sizeof(v6));
  return IN6_IS_ADDR_LOOPBACK(&v6.sin6_addr) ||
         (IN6_IS_ADDR_V4MAPPED(&v6.sin6_addr) && v6.sin6_addr.s6_addr[12] == 127);
}

// A connection's socket as httplib reads and writes it, within the limits above (kMaxHead,
// kHeadTime, kTransferTime, kStallTime). A request that breaks one is answered where it can be,
// and its connection closed.
class ConnectionStream final : public httplib::Stream {
 public:
  explicit ConnectionStream(socket_t sock) : sock_(sock) {}

  // A request's first byte has come: its head is read from now on.
  void start_request() {
    set_phase(Phase::head, kHeadTime);
    head_bytes_ = 0;
  }
  // The head has been read: the body, if any, from now on.
  void head_read() { set_phase(Phase::body, kTransferTime); }
  bool broke_limit() const { return broke_limit_; }
  bool has_buffered() const { return begin_ < end_; }

  bool is_readable() const override { return has_buffered() || wait_for(POLLIN); }
  bool is_writable() const override { return wait_for(POLLOUT); }
  ssize_t read(char* out, std::size_t size) override;
  ssize_t write(const char* data, std::size_t size) override;
  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    socket_address(sock_, true, ip, port);
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    socket_address(sock_, false, ip, port);
  }
  socket_t socket() const override { return sock_; }

 private:
  enum class Phase { head, body, answer };
  void set_phase(Phase phase, std::chrono::seconds time) {
    phase_ = phase;
    deadline_ = std::chrono::steady_clock::now() + time;
  }
  // Waits for the socket to be ready for `events`, within the phase's deadline and kStallTime.
  bool wait_for(short events) const;

  socket_t sock_;
  Phase phase_ = Phase::head;
  std::chrono::steady_clock::time_point deadline_;
  std::size_t head_bytes_ = 0;
  mutable bool broke_limit_ = false;
  std::array<char, 4096> buffer_{};  // httplib reads a head a byte at a time
  std::size_t begin_ = 0;
  std::size_t end_ = 0;
};

bool ConnectionStream::wait_for(short events) const {
  for (;;) {
    const auto left = deadline_ - std::chrono::steady_clock::now();
    if (left <= left.zero()) break;
    const auto wait = std::chrono::ceil<std::chrono::milliseconds>(
        std::min<std::chrono::steady_clock::duration>(left, kStallTime));
    pollfd descriptor{sock_, events, 0};
    const int ready = ::poll(&descriptor, 1, static_cast<int>(wait.count()));
    if (ready > 0) return true;
    if (ready == 0) break;
    if (errno != EINTR) return false;
  }
  broke_limit_ = true;
  return false;
}

ssize_t ConnectionStream::read(char* out, std::size_t size) {
  std::size_t most = size;
  if (phase_ == Phase::head) {
    if (head_bytes_ >= kMaxHead) {
      broke_limit_ = true;
      return -1;
    }
    most = std::min(most, kMaxHead - head_bytes_);
  }
  if (!has_buffered()) {
    ssize_t received = 0;
    do {
      if (!wait_for(POLLIN)) return -1;
      received = ::recv(sock_, buffer_.data(), buffer_.size(), MSG_DONTWAIT);
    } while (received < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR));
    if (received <= 0) return received;
    begin_ = 0;
    end_ = static_cast<std::size_t>(received);
  }
  const std::size_t count = std::min(most, end_ - begin_);
  std::memcpy(out, buffer_.data() + begin_, count);
  begin_ += count;
  if (phase_ == Phase::head) head_bytes_ += count;
  return static_cast<ssize_t>(count);
}

ssize_t ConnectionStream::write(const char* data, std::size_t size) {
  if (phase_ != Phase::answer) set_phase(Phase::answer, kTransferTime);
  for (;;) {
    if (!wait_for(POLLOUT)) return -1;
    const ssize_t sent = ::send(sock_, data, size, MSG_DONTWAIT | MSG_NOSIGNAL);
    if (sent >= 0 || (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) return sent;
  }
}

// httplib's server with each connection read and written through a ConnectionStream: httplib's
// own stream waits for each byte up to its read timeout, with no limit on a whole request, so a
// head sent a byte a second held a thread for good.
class StudioHttpServer final : public httplib::Server {
 public:
  // The listening socket, once bound.
  socket_t listening_socket() const { return svr_sock_; }

 private:
  bool process_and_close_socket(socket_t sock) override;
  // Whether a request's first byte comes within kIdleSeconds (and the server is still running).
  bool request_comes(socket_t sock) const;
};

bool StudioHttpServer::request_comes(socket_t sock) const {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(kIdleSeconds);
  // In slices, so that a stopping server does not wait for its idle connections.
  constexpr auto slice = std::chrono::milliseconds(100);
  while (svr_sock_ != INVALID_SOCKET) {
    const auto left = deadline - std::chrono::steady_clock::now();
    if (left <= left.zero()) return false;
    const auto wait = std::chrono::ceil<std::chrono::milliseconds>(
        std::min<std::chrono::steady_clock::duration>(left, slice));
    pollfd descriptor{sock, POLLIN, 0};
    const int ready = ::poll(&descriptor, 1, static_cast<int>(wait.count()));
    if (ready > 0) return true;
    if (ready < 0 && errno != EINTR) return false;
  }
  return false;
}

bool StudioHttpServer::process_and_close_socket(socket_t sock) {
  ConnectionStream stream(sock);
  bool served = false;
  for (std::size_t left = keep_alive_max_count_; left > 0; --left) {
    if (!stream.has_buffered() && !request_comes(sock)) break;
    stream.start_request();
    bool closed = false;
    served = process_request(stream, left == 1, closed,
                             [&stream](httplib::Request&) { stream.head_read(); });
    if (!served || closed || stream.broke_limit()) break;
  }
  ::shutdown(sock, SHUT_RDWR);
  ::close(sock);
  return served;
}

// Who may use the studio, checked before any route reads a request (docs/studio.md, "Safety"). A
// studio bound to loopback answers only requests addressed to its loopback names and port (no
// other web site can point its name at it: DNS rebinding). One bound to another address can be
// reached by any name, so each request needs the studio's token instead: a 128-bit random number
// printed with its address, as Jupyter's, which the page's address sets as a cookie. Either way a
// request that changes something (any method but GET and HEAD) is refused when a browser says that
// a page of another origin sent it (Origin, Sec-Fetch-Site).
class Gate {
 public:
  Gate(bool loopback, const std::string& bound_ip, int port);

  const std::string& token() const { return token_; }  // empty on loopback
  std::string token_cookie() const { return fmt::format("stochtex_token_{}", port_); }
  // Throws the refusal of `req`, a StudioError, if any.
  void check(const httplib::Request& req) const;

 private:
  bool has_token(const httplib::Request& req) const;

  int port_;
  std::vector<std::string> hosts_;  // the Host values a loopback studio answers, lower case
  std::string token_;
};

Gate::Gate(bool loopback, const std::string& bound_ip, int port) : port_(port) {
  if (!loopback) {
    std::random_device random;
    token_ = fmt::format("{:08x}{:08x}{:08x}{:08x}", random(), random(), random(), random());
    return;
  }
  std::vector<std::string> names = {"localhost", "127.0.0.1", "[::1]"};
  const std::string bound =
      bound_ip.find(':') != std::string::npos ? "[" + bound_ip + "]" : bound_ip;
  if (std::find(names.begin(), names.end(), bound) == names.end()) names.push_back(bound);
  for (const std::string& name : names) hosts_.push_back(fmt::format("{}:{}", name, port));
  // On port 80, the default, a browser leaves the port out. (The first three stay the message's.)
  if (port == 80) hosts_.insert(hosts_.end(), names.begin(), names.end());
}

bool Gate::has_token(const httplib::Request& req) const {
  // Compared in a time that tells nothing of how much of it matched.
  const auto equal = [this](const std::string& given) {
    if (given.size() != token_.size()) return false;
    unsigned char difference = 0;
    for (std::size_t i = 0; i < given.size(); ++i)
      difference |= static_cast<unsigned char>(given[i] ^ token_[i]);
    return difference == 0;
  };
  return equal(req.get_param_value("token")) || equal(cookie(req, token_cookie()));
}

void Gate::check(const httplib::Request& req) const {
  if (req.get_header_value_count("Host") != 1)
    throw StudioError(400, "the request must carry exactly one Host header");
  const std::string host = lowercase(req.get_header_value("Host"));
  if (token_.empty()) {
    if (std::find(hosts_.begin(), hosts_.end(), host) == hosts_.end())
      throw StudioError(403, fmt::format("this studio answers only requests addressed to {}, {} or "
                                         "{}, not '{}'",
                                         hosts_[0], hosts_[1], hosts_[2], host));
  } else if (!has_token(req)) {
    throw StudioError(403,
                      "this studio listens beyond loopback and answers only requests with its "
                      "token: open the address it printed, which ends in ?token=, or add "
                      "?token=TOKEN to the request");
  }
  if (req.method == "GET" || req.method == "HEAD") return;
  if (req.has_header("Origin") && lowercase(req.get_header_value("Origin")) != "http://" + host)
    throw StudioError(403, fmt::format("the studio takes changes only from its own page, not from "
                                       "a page of '{}'",
                                       req.get_header_value("Origin")));
  const std::string site = req.get_header_value("Sec-Fetch-Site");
  if (req.has_header("Sec-Fetch-Site") && site != "same-origin" && site != "none")
    throw StudioError(403, fmt::format("the studio takes changes only from its own page, not from "
                                       "a page of another origin (Sec-Fetch-Site: {})",
                                       site));
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

void add_routes(httplib::Server& server, StudioStore& store, const Gate& gate,
                UploadSlots& uploads) {
  server.Get(
      "/", guarded([&gate](const httplib::Request& req, httplib::Response& res) {
        const EmbeddedFile* page = find_embedded(embedded_files(), "studio/index.html");
        if (page == nullptr) throw StudioError(500, "the studio page is missing");
        res.set_content(std::string(page->text), std::string(content_type(page->name)));
        if (!client_of(req)) {
          std::random_device random;
          res.set_header("Set-Cookie", fmt::format("{}={:08x}{:08x}; Path=/; SameSite=Strict",
                                                   kClientCookie, random(), random()));
        }
        // The page's address with the token (the gate has checked it): the page's own
        // requests then carry it. Cookies are per host, not per port: the name is this
        // port's, so that studios on other ports keep theirs.
        if (!gate.token().empty() && req.has_param("token"))
          res.set_header("Set-Cookie", fmt::format("{}={}; Path=/; HttpOnly; SameSite=Strict",
                                                   gate.token_cookie(), gate.token()));
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
  server.Post(
      "/api/exemplars",
      [&uploads, upload = with_body(store.limits().max_upload_bytes,
                                    [&store](const httplib::Request& req, httplib::Response& res,
                                             const std::string& body) {
                                      required_client(req);
                                      send_json(res, store.add_exemplar(body), 201);
                                    })](const httplib::Request& req, httplib::Response& res,
                                        const httplib::ContentReader& reader) {
        const UploadSlot slot(uploads);
        upload(req, res, reader);
      });
  server.Get("/api/exemplars/" + kId + "/(image|gaussian)\\.png",
             guarded([&store](const httplib::Request& req, httplib::Response& res) {
               res.set_content(store.exemplar_png(req.matches[1], req.matches[2] == "gaussian"),
                               "image/png");
             }));
  server.Post("/api/analyses",
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
                    throw StudioError(400,
                                      fmt::format("the JSON body needs \"{}\" as a string", key));
                  return body[key].get<std::string>();
                };
                std::uint32_t seed = 0;
                if (body.contains("seed")) {
                  if (!body["seed"].is_number_unsigned() ||
                      body["seed"].get<std::uint64_t>() > std::numeric_limits<std::uint32_t>::max())
                    throw StudioError(400, "\"seed\" must be an integer from 0 to 4294967295");
                  seed = body["seed"].get<std::uint32_t>();
                }
                std::string colour_space = "auto";
                if (body.contains("colour_space")) colour_space = text("colour_space");
                const std::string id = store.start_analysis(
                    client, text("exemplar"), text("method"),
                    body.value("params", nlohmann::ordered_json::object()), seed, colour_space);
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

void serve_studio(const StudioOptions& options,
                  const std::function<void(const StudioAddress& address)>& listening) {
  sigset_t signals;
  sigemptyset(&signals);
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&signals, signal_number);
  ::pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  // Buffers of 256 KiB and more (images, PNGs, request bodies) are mapped and unmapped on their
  // own rather than left in the request threads' heaps, where glibc's dynamic threshold would put
  // them after the first free: the server's memory then follows what it holds.
  ::mallopt(M_MMAP_THRESHOLD, 256 * 1024);
  StudioStore store(options.limits);
  StudioHttpServer server;
  server.new_task_queue = [] { return new httplib::ThreadPool(kConnectionThreads); };
  server.set_payload_max_length(options.limits.max_upload_bytes);
  // SO_REUSEADDR (a restart may bind while old connections linger) but not httplib's default
  // SO_REUSEPORT, with which a second server could bind the same port and take its connections.
  server.set_socket_options([](socket_t sock) {
    const int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
  });
  server.set_keep_alive_timeout(kIdleSeconds);
  server.set_default_headers(
      {{"X-Content-Type-Options", "nosniff"},
       {"Cache-Control", "no-store"},
       {"Referrer-Policy", "no-referrer"},
       {"Content-Security-Policy", "default-src 'self' blob: data:; frame-ancestors 'none'"}});
  const std::size_t max_body = options.limits.max_upload_bytes;
  server.set_error_handler(httplib::Server::HandlerWithResponse(
      [max_body](const httplib::Request& req, httplib::Response& res) {
        if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
        send_error(res, res.status, default_error(req, res.status, max_body));
        return httplib::Server::HandlerResponse::Handled;
      }));

  const int port = options.port == 0 ? server.bind_to_any_port(options.host)
                   : server.bind_to_port(options.host, options.port) ? options.port
                                                                     : -1;
  if (port < 0)
    throw Error(ErrorCode::io,
                fmt::format("cannot listen on {} port {}: the port is in use or the address is not "
                            "this machine's; choose another --port (0 picks a free one) or --host",
                            options.host, options.port));
  // httplib listens with a backlog of 5: the connections of a burst beyond it (a page's requests,
  // clients holding connections) were dropped, and their TCP tried again a second or more later.
  ::listen(server.listening_socket(), SOMAXCONN);
  // Loopback or not is the bound address's, not the name's: --host may name any address.
  const bool loopback = bound_to_loopback(server.listening_socket());
  std::string bound_ip;
  int bound_port = port;
  socket_address(server.listening_socket(), false, bound_ip, bound_port);
  const Gate gate(loopback, bound_ip, bound_port);
  server.set_pre_routing_handler([&gate](const httplib::Request& req, httplib::Response& res) {
    try {
      gate.check(req);
    } catch (const StudioError& e) {
      send_error(res, e.status(), e.what());
      return httplib::Server::HandlerResponse::Handled;
    }
    return httplib::Server::HandlerResponse::Unhandled;
  });
  UploadSlots uploads(kUploadSlots);
  add_routes(server, store, gate, uploads);

  const std::string host =
      options.host.find(':') != std::string::npos ? "[" + options.host + "]" : options.host;
  listening({fmt::format("http://{}:{}/{}", host, port,
                         gate.token().empty() ? "" : "?token=" + gate.token()),
             loopback});
  std::atomic<bool> done = false;
  std::thread signal_waiter([&] { wait_for_signal(server, done); });
  server.listen_after_bind();
  done = true;
  signal_waiter.join();
}

}  // namespace stochtex::web
