#pragma once
// meshmarkd's HTTP/1.1 transport, on Boost.Beast and Asio.
//
// Sockets are served asynchronously by a few I/O threads, so an idle or slow connection costs a
// socket and a buffer, never a thread; handlers (which touch the store or parse meshes) run on a
// separate pool. Framing is strict: a request head must arrive whole within a deadline and
// within a size limit; Transfer-Encoding, Content-Encoding, duplicate or malformed
// Content-Length are refused; a request refused before its body was read closes the
// connection (after answering), so the unread body can never be taken for a request. Requests
// pipelined on one connection are answered in order.

#include <atomic>
#include <chrono>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <variant>

#include "server/http/http_message.hpp"

namespace meshmark::server {

struct HttpServerOptions {
  std::string host = "127.0.0.1";
  int port = 8080;                               ///< 0: any free port (see HttpServer::port)
  int io_threads = 2;                            ///< threads that read and write sockets; they never block
  int handler_threads = 16;                      ///< threads that run handlers
  std::size_t max_connections = 1024;            ///< open at once; beyond, new ones get 503 and are closed
  std::size_t max_connections_per_client = 256;  ///< open at once from one address; beyond, the same
  std::size_t max_header_bytes = 16 * 1024;      ///< request line and headers; beyond: 431
  std::size_t max_body_bytes = 256ull << 20;     ///< any body; beyond: 413 before a byte is read
  std::size_t max_unplanned_body_bytes =
      64 * 1024;  ///< a body on a route that takes none is read and dropped up to this
  std::chrono::milliseconds header_timeout{
      10'000};  ///< a request head (or the next one, on a kept connection) must arrive within this
  std::chrono::milliseconds body_idle_timeout{10'000};  ///< every read of a body must bring bytes within this
  std::chrono::milliseconds write_timeout{30'000};      ///< a response must be taken within this
  std::size_t max_waiting_requests = 4096;              ///< requests waiting for a handler thread; beyond: 503
  int busy_retry_after_seconds = 2;                     ///< the Retry-After of that 503
  std::filesystem::path upload_dir;                     ///< where bodies read to files go (created)
};

/// How admission wants the body read.
struct BodyPlan {
  enum class Kind { none, memory, file } kind = Kind::none;
  std::size_t limit = 0;         ///< bytes; a longer Content-Length gets 413 before the body is read
  bool length_required = false;  ///< no Content-Length: 411
};

/// What the transport asks of the application. admit() and respond() run on the handler pool
/// and may block; answer_at_once() runs on an I/O thread and must not.
class HttpHandler {
 public:
  virtual ~HttpHandler() = default;
  /// Requests that need neither a handler thread nor a body (liveness): the answer, else nullopt.
  virtual std::optional<HttpResponse> answer_at_once(HttpRequest& head) = 0;
  /// From the head alone (route, authentication, parameters): a response now, or how to read the body.
  virtual std::variant<HttpResponse, BodyPlan> admit(HttpRequest& head) = 0;
  /// The answer to a request whose body was read as planned.
  virtual HttpResponse respond(HttpRequest& request) = 0;
  /// The response to a request the transport refused (malformed, too large, overloaded).
  virtual HttpResponse refusal(int status, const std::string& detail) = 0;
  /// After every response (access log, metrics); `request` may hold only a head.
  virtual void observe(const HttpRequest& request, const HttpResponse& response) = 0;
};

class HttpServer {
 public:
  HttpServer(HttpServerOptions options, HttpHandler& handler);
  ~HttpServer();
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  /// Binds and listens (no SO_REUSEPORT: a port in use is an error). Throws std::runtime_error
  /// with the reason. Returns the port (the chosen one for port 0).
  int bind();
  /// Serves until stop(); call after bind().
  void run();
  /// Stops accepting, lets the handlers that run finish, closes every connection; run() returns.
  void stop();

  std::size_t open_connections() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace meshmark::server
