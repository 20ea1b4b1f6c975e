#include "server/http/http_server.hpp"

#include <spdlog/spdlog.h>

// Boost 1.74's asio/awaitable.hpp uses std::exchange without including <utility>.
#include <utility>

#include <fcntl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <cerrno>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <thread>
#include <vector>

#include "server/http/connection_counts.hpp"

namespace meshmark::server {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
using tcp = asio::ip::tcp;
using asio::awaitable;
using asio::use_awaitable;

namespace {

// Counts a connection while it lives.
class ConnectionSlot {
 public:
  ConnectionSlot(ConnectionCounts& counts, std::string client) : counts_(counts), client_(std::move(client)) {}
  ~ConnectionSlot() { counts_.release(client_); }
  ConnectionSlot(const ConnectionSlot&) = delete;
  ConnectionSlot& operator=(const ConnectionSlot&) = delete;

 private:
  ConnectionCounts& counts_;
  const std::string client_;
};

// The peer's address, without its port: what the per-client cap counts.
std::string client_address(const tcp::socket& socket) {
  beast::error_code ec;
  const tcp::endpoint peer = socket.remote_endpoint(ec);
  return ec ? std::string("unknown") : peer.address().to_string();
}

// Where a body goes while it is read: a string, a file, or nowhere.
class BodySink {
 public:
  BodySink(BodyPlan::Kind kind, HttpRequest& request, const std::filesystem::path& dir, unsigned long serial)
      : kind_(kind), request_(request) {
    if (kind_ != BodyPlan::Kind::file) return;
    std::filesystem::create_directories(dir);
    request_.body_file = dir / ("body-" + std::to_string(::getpid()) + "-" + std::to_string(serial));
    fd_ = ::open(request_.body_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    if (fd_ < 0) failed_errno_ = errno;
  }
  ~BodySink() {
    if (fd_ >= 0) ::close(fd_);
  }
  BodySink(const BodySink&) = delete;
  BodySink& operator=(const BodySink&) = delete;

  /// False once a write failed (see error()).
  bool write(const char* data, std::size_t n) {
    request_.body_bytes += n;
    if (kind_ == BodyPlan::Kind::memory) request_.body.append(data, n);
    if (kind_ != BodyPlan::Kind::file || failed_errno_ != 0) return failed_errno_ == 0;
    while (n > 0) {
      const ssize_t w = ::write(fd_, data, n);
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) {
        failed_errno_ = w < 0 ? errno : EIO;
        return false;
      }
      data += w;
      n -= static_cast<std::size_t>(w);
    }
    return true;
  }
  /// Closes the file; false if that failed.
  bool finish() {
    if (fd_ < 0) return failed_errno_ == 0;
    const bool ok = ::close(fd_) == 0;
    fd_ = -1;
    if (!ok && failed_errno_ == 0) failed_errno_ = errno;
    return failed_errno_ == 0;
  }
  int error() const { return failed_errno_; }

 private:
  BodyPlan::Kind kind_;
  HttpRequest& request_;
  int fd_ = -1;
  int failed_errno_ = 0;
};

bool iequals(std::string_view a, std::string_view b) {
  return beast::iequals(beast::string_view(a.data(), a.size()), beast::string_view(b.data(), b.size()));
}

}  // namespace

struct HttpServer::Impl {
  Impl(HttpServerOptions o, HttpHandler& h)
      : options(std::move(o)),
        handler(h),
        connections(options.max_connections, options.max_connections_per_client),
        pool(static_cast<std::size_t>(std::max(1, options.handler_threads))),
        acceptor(io) {}

  HttpServerOptions options;
  HttpHandler& handler;
  ConnectionCounts connections;
  std::atomic<std::size_t> waiting{0};    // requests on or waiting for a handler thread
  std::atomic<std::size_t> in_flight{0};  // requests between their head and their response
  std::atomic<unsigned long> serial{0};
  std::atomic<bool> stopping{false};
  asio::io_context io;
  asio::thread_pool pool;  // declared after io: joined in stop(), destroyed before io
  tcp::acceptor acceptor;
  int port = 0;

  // What one request/response exchange left the connection in.
  struct Outcome {
    bool keep_open = false;
    bool unread_input = false;  // the client may still be sending: drain before closing
  };

  // Runs `f` on the handler pool and resumes on the connection's strand.
  template <typename F>
  awaitable<std::invoke_result_t<F&>> on_pool(F f) {
    using Result = std::invoke_result_t<F&>;
    co_return co_await asio::co_spawn(
        pool, [&f]() -> awaitable<Result> { co_return f(); }, use_awaitable);
  }

  HttpResponse refusal(int status, const std::string& detail) { return handler.refusal(status, detail); }

  awaitable<void> write(beast::tcp_stream& stream, const HttpRequest& request, HttpResponse& response, bool keep_open,
                        unsigned version) {
    http::response<http::string_body> out;
    out.version(version);
    out.result(static_cast<unsigned>(response.status));
    if (!response.content_type.empty()) out.set(http::field::content_type, response.content_type);
    // Answers carry owners' keys and data: no cache keeps them, no browser guesses their type.
    out.set(http::field::cache_control, "no-store");
    out.set("X-Content-Type-Options", "nosniff");
    for (const auto& [name, value] : response.headers) out.insert(name, value);
    out.body() = std::move(response.body);
    out.keep_alive(keep_open);
    out.prepare_payload();
    stream.expires_after(options.write_timeout);
    beast::error_code ec;
    co_await http::async_write(stream, out, asio::redirect_error(use_awaitable, ec));
    response.body = std::move(out.body());
    handler.observe(request, response);
    if (ec) throw beast::system_error(ec);
  }

  awaitable<void> send_100_continue(beast::tcp_stream& stream) {
    http::response<http::empty_body> interim{http::status::continue_, 11};
    stream.expires_after(options.write_timeout);
    co_await http::async_write(stream, interim, use_awaitable);
  }

  // The transport's own checks of a head: framing it refuses outright.
  std::optional<HttpResponse> check_framing(const HttpRequest& head) {
    if (header_count(head.headers, "Transfer-Encoding") > 0)
      return refusal(411, "chunked or otherwise encoded transfers are refused; send the body with a Content-Length");
    if (header_count(head.headers, "Content-Encoding") > 0)
      return refusal(415, "compressed request bodies are refused; send the body as it is");
    if (header_count(head.headers, "Content-Length") > 1)
      return refusal(400, "the request has more than one Content-Length header");
    if (head.content_length && *head.content_length > options.max_body_bytes)
      return refusal(413, "the body is " + std::to_string(*head.content_length) + " bytes; the limit is " +
                              std::to_string(options.max_body_bytes));
    const std::string expect = head.header("Expect");
    if (!expect.empty() && !iequals(expect, "100-continue"))
      return refusal(417, "the only expectation served is 'Expect: 100-continue'");
    return std::nullopt;
  }

  // A refusal from the head's checks: what to say and whether a body is left unread.
  std::optional<HttpResponse> check_plan(const HttpRequest& head, const BodyPlan& plan) {
    const std::uint64_t length = head.content_length.value_or(0);
    if (plan.length_required && !head.content_length) return refusal(411, "this request needs a Content-Length header");
    if (plan.kind == BodyPlan::Kind::file && length == 0)
      return refusal(400, "the body is empty; send the file as the request body");
    const std::size_t limit = plan.kind == BodyPlan::Kind::none ? options.max_unplanned_body_bytes : plan.limit;
    if (length > limit)
      return refusal(413,
                     "the body is " + std::to_string(length) + " bytes; the limit here is " + std::to_string(limit));
    return std::nullopt;
  }

  // Reads the body as planned; a response when it could not be read whole. The idle timer
  // cancels the read rather than closing the socket, so that the client still gets the answer.
  awaitable<std::optional<HttpResponse>> read_body(beast::tcp_stream& stream, beast::flat_buffer& buffer,
                                                   http::request_parser<http::buffer_body>& parser,
                                                   HttpRequest& request, BodyPlan::Kind kind) {
    BodySink sink(kind, request, options.upload_dir, serial.fetch_add(1));
    if (sink.error() != 0) co_return storage_refusal(sink.error());
    std::vector<char> chunk(64 * 1024);
    bool stored = true;
    stream.expires_never();
    while (!parser.is_done()) {
      parser.get().body().data = chunk.data();
      parser.get().body().size = chunk.size();
      asio::steady_timer idle(stream.get_executor(), options.body_idle_timeout);
      idle.async_wait([&stream](const beast::error_code& e) {
        if (!e) stream.socket().cancel();  // the read below ends with operation_aborted
      });
      beast::error_code ec;
      co_await http::async_read(stream, buffer, parser, asio::redirect_error(use_awaitable, ec));
      idle.cancel();
      const std::size_t got = chunk.size() - parser.get().body().size;
      if (got > 0 && stored) stored = sink.write(chunk.data(), got);
      if (ec == http::error::need_buffer) ec = {};
      if (ec)
        co_return refusal(400, "the body ended after " + std::to_string(request.body_bytes) +
                                   " bytes, before its Content-Length (" +
                                   std::to_string(request.content_length.value_or(0)) + ")");
    }
    stored = sink.finish() && stored;
    if (!stored) co_return storage_refusal(sink.error());
    co_return std::nullopt;
  }

  HttpResponse storage_refusal(int error) {
    const bool full = error == ENOSPC || error == EDQUOT;
    return refusal(full ? 507 : 500,
                   full ? "the server's storage is full; retry later" : "the upload could not be stored");
  }

  static HttpRequest head_of(const http::request_parser<http::buffer_body>& parser) {
    const auto& m = parser.get();
    HttpRequest r;
    r.method = std::string(m.method_string());
    r.target = std::string(m.target());
    for (const auto& field : m) r.headers.emplace_back(std::string(field.name_string()), std::string(field.value()));
    if (const auto length = parser.content_length()) r.content_length = *length;
    r.keep_alive = parser.keep_alive();
    return r;
  }

  // One request and its response.
  awaitable<Outcome> exchange(beast::tcp_stream& stream, beast::flat_buffer& buffer) {
    http::request_parser<http::buffer_body> parser;
    parser.header_limit(static_cast<std::uint32_t>(options.max_header_bytes));
    // The Content-Length is checked against our limits (413) before the body is read. (Not
    // boost::none: Beast 1.74 compares the length with the optional, and none is below every length.)
    parser.body_limit(std::numeric_limits<std::uint64_t>::max());
    stream.expires_after(options.header_timeout);
    beast::error_code ec;
    co_await http::async_read_header(stream, buffer, parser, asio::redirect_error(use_awaitable, ec));
    if (ec == http::error::end_of_stream || ec == asio::error::eof || ec == beast::error::timeout ||
        ec == asio::error::connection_reset || ec == asio::error::operation_aborted)
      co_return Outcome{};  // gone, idle or too slow: nothing to answer
    in_flight.fetch_add(1);
    struct Done {
      std::atomic<std::size_t>& n;
      ~Done() { n.fetch_sub(1); }
    } done{in_flight};
    if (ec) {
      const bool too_big = ec == http::error::header_limit || ec == http::error::buffer_overflow;
      HttpResponse r = too_big ? refusal(431, "the request line and headers exceed " +
                                                  std::to_string(options.max_header_bytes) + " bytes")
                               : refusal(400, "malformed request: " + ec.message());
      const HttpRequest unread;
      co_await write(stream, unread, r, false, 11);
      co_return Outcome{false, true};
    }
    HttpRequest request = head_of(parser);
    const unsigned version = parser.get().version();
    if (auto early = screen(request)) {
      co_await write(stream, request, early->response, early->outcome.keep_open, version);
      co_return early->outcome;
    }
    co_return co_await admit_and_serve(stream, buffer, parser, request, version);
  }

  struct EarlyAnswer {
    HttpResponse response;
    Outcome outcome;
  };

  // The answers given from the head alone: a malformed target or framing, a route answered at
  // once (health), or busy.
  std::optional<EarlyAnswer> screen(HttpRequest& request) {
    const bool has_body = request.content_length.value_or(0) > 0;
    if (!split_target(request.target, request.path, request.query))
      return EarlyAnswer{refusal(400, "the request target has a malformed percent-escape"), {false, true}};
    if (auto refused = check_framing(request)) return EarlyAnswer{std::move(*refused), {false, true}};
    if (!has_body && !stopping.load())
      if (auto now = handler.answer_at_once(request)) return EarlyAnswer{std::move(*now), {request.keep_alive, false}};
    if (stopping.load() || waiting.load() >= options.max_waiting_requests) {
      HttpResponse busy = refusal(503, "the daemon is busy or stopping; retry shortly");
      busy.set_header("Retry-After", std::to_string(options.busy_retry_after_seconds));
      return EarlyAnswer{std::move(busy), {false, has_body}};
    }
    return std::nullopt;
  }

  // Admission (route, authentication, parameters) before a byte of the body is read; then the
  // body, the handler and the response.
  awaitable<Outcome> admit_and_serve(beast::tcp_stream& stream, beast::flat_buffer& buffer,
                                     http::request_parser<http::buffer_body>& parser, HttpRequest& request,
                                     unsigned version) {
    const bool has_body = request.content_length.value_or(0) > 0;
    waiting.fetch_add(1);
    auto admitted = co_await on_pool([&]() -> std::variant<HttpResponse, BodyPlan> { return admit(request); });
    waiting.fetch_sub(1);
    if (auto* answer = std::get_if<HttpResponse>(&admitted)) {
      co_await write(stream, request, *answer, request.keep_alive && !has_body, version);
      co_return Outcome{request.keep_alive && !has_body, has_body};
    }
    const BodyPlan plan = std::get<BodyPlan>(admitted);
    if (auto wrong = check_plan(request, plan)) {
      co_await write(stream, request, *wrong, false, version);
      co_return Outcome{false, has_body};
    }
    if (has_body) {
      if (!request.header("Expect").empty()) co_await send_100_continue(stream);
      if (auto failed = co_await read_body(stream, buffer, parser, request, plan.kind)) {
        std::error_code ignored;
        std::filesystem::remove(request.body_file, ignored);
        co_await write(stream, request, *failed, false, version);
        co_return Outcome{false, !parser.is_done()};
      }
    }
    waiting.fetch_add(1);
    HttpResponse response = co_await on_pool([&]() -> HttpResponse { return respond(request); });
    waiting.fetch_sub(1);
    std::error_code ignored;
    if (!request.body_file.empty()) std::filesystem::remove(request.body_file, ignored);
    const bool keep_open = request.keep_alive && !stopping.load();
    co_await write(stream, request, response, keep_open, version);
    co_return Outcome{keep_open, false};
  }

  // The handler answers its own failures; one that escapes it is a bug, logged here.
  HttpResponse escaped_failure(const char* step) {
    try {
      throw;
    } catch (const std::exception& e) {
      spdlog::error("HTTP handler {} threw: {}", step, e.what());
    } catch (...) {
      spdlog::error("HTTP handler {} threw a non-exception", step);
    }
    return refusal(500, "internal error");
  }
  std::variant<HttpResponse, BodyPlan> admit(HttpRequest& request) {
    try {
      return handler.admit(request);
    } catch (...) {
      return escaped_failure("admission");
    }
  }
  HttpResponse respond(HttpRequest& request) {
    try {
      return handler.respond(request);
    } catch (...) {
      return escaped_failure("response");
    }
  }

  // Closes after a FIN and a short drain, so that the client reads our answer rather than a
  // reset caused by the bytes it was still sending.
  awaitable<void> close(beast::tcp_stream& stream, bool drain) {
    beast::error_code ec;
    stream.socket().shutdown(tcp::socket::shutdown_send, ec);
    if (drain && !ec) {
      std::vector<char> scratch(16 * 1024);
      std::size_t drained = 0;
      stream.expires_after(std::chrono::seconds(2));
      while (drained < (4u << 20)) {
        const std::size_t n =
            co_await stream.async_read_some(asio::buffer(scratch), asio::redirect_error(use_awaitable, ec));
        if (ec) break;
        drained += n;
      }
    }
    stream.socket().close(ec);
  }

  awaitable<void> session(tcp::socket socket, std::string client) {
    ConnectionSlot slot(connections, std::move(client));
    beast::tcp_stream stream(std::move(socket));
    beast::flat_buffer buffer(options.max_header_bytes + 64 * 1024);
    Outcome outcome;
    try {
      do {
        outcome = co_await exchange(stream, buffer);
      } while (outcome.keep_open && !stopping.load());
    } catch (const std::exception&) {
      outcome = Outcome{false, false};  // a write failed or timed out: the client is gone
    }
    co_await close(stream, outcome.unread_input);
  }

  // Over a connection cap: a short answer without a session, then close.
  void refuse_connection(tcp::socket& socket, const std::string& why) {
    HttpResponse r = refusal(503, why);
    std::string text = "HTTP/1.1 503 Service Unavailable\r\nContent-Type: " + r.content_type +
                       "\r\nContent-Length: " + std::to_string(r.body.size()) +
                       "\r\nRetry-After: 1\r\nConnection: close\r\n\r\n" + r.body;
    ::send(socket.native_handle(), text.data(), text.size(), MSG_DONTWAIT | MSG_NOSIGNAL);
    beast::error_code ec;
    socket.shutdown(tcp::socket::shutdown_send, ec);
    socket.close(ec);
  }

  awaitable<void> accept_loop() {
    while (!stopping.load()) {
      tcp::socket socket(asio::make_strand(io));
      beast::error_code ec;
      co_await acceptor.async_accept(socket, asio::redirect_error(use_awaitable, ec));
      if (ec) {
        if (stopping.load() || ec == asio::error::operation_aborted) co_return;
        // Out of descriptors or memory: let the backlog wait rather than spin.
        asio::steady_timer pause(io, std::chrono::milliseconds(50));
        co_await pause.async_wait(asio::redirect_error(use_awaitable, ec));
        continue;
      }
      std::string client = client_address(socket);
      if (const auto admission = connections.admit(client); admission != ConnectionCounts::Admission::admitted) {
        refuse_connection(socket, admission == ConnectionCounts::Admission::client_full
                                      ? "too many connections from your address; close some and retry"
                                      : "too many connections; retry shortly");
        continue;
      }
      socket.set_option(tcp::no_delay(true), ec);
      // The executor first: the arguments' order is unspecified, and session() takes the socket.
      const auto executor = socket.get_executor();
      asio::co_spawn(executor, session(std::move(socket), std::move(client)), asio::detached);
    }
  }
};

HttpServer::HttpServer(HttpServerOptions options, HttpHandler& handler)
    : impl_(std::make_unique<Impl>(std::move(options), handler)) {}

HttpServer::~HttpServer() {
  if (!impl_->stopping.load()) stop();
}

int HttpServer::bind() {
  Impl& s = *impl_;
  const std::string where = s.options.host + ":" + std::to_string(s.options.port);
  beast::error_code ec;
  tcp::resolver resolver(s.io);
  const auto endpoints = resolver.resolve(s.options.host, std::to_string(s.options.port),
                                          tcp::resolver::passive | tcp::resolver::numeric_service, ec);
  if (ec || endpoints.empty()) throw std::runtime_error("cannot listen on " + where + ": " + ec.message());
  const tcp::endpoint endpoint = endpoints.begin()->endpoint();
  s.acceptor.open(endpoint.protocol(), ec);
  // SO_REUSEADDR lets a restart bind while old connections linger in TIME_WAIT; unlike
  // SO_REUSEPORT it never lets a second daemon listen on the same port.
  if (!ec) s.acceptor.set_option(tcp::acceptor::reuse_address(true), ec);
  if (!ec) s.acceptor.bind(endpoint, ec);
  if (!ec) s.acceptor.listen(1024, ec);
  if (ec) {
    const std::string hint = ec == asio::error::address_in_use ? " (is another meshmarkd running?)" : "";
    throw std::runtime_error("cannot listen on " + where + ": " + ec.message() + hint);
  }
  s.port = s.acceptor.local_endpoint().port();
  return s.port;
}

void HttpServer::run() {
  Impl& s = *impl_;
  asio::co_spawn(s.io, s.accept_loop(), asio::detached);
  std::vector<std::thread> extra;
  for (int i = 1; i < s.options.io_threads; ++i) extra.emplace_back([&s] { s.io.run(); });
  s.io.run();
  for (auto& t : extra) t.join();
}

void HttpServer::stop() {
  Impl& s = *impl_;
  if (s.stopping.exchange(true)) return;
  asio::post(s.io, [&s] {
    beast::error_code ec;
    s.acceptor.close(ec);
  });
  s.pool.join();  // handlers that run now finish; new requests are refused while stopping
  // Let the answers of the last handlers be written.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (s.in_flight.load() > 0 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  s.io.stop();
}

std::size_t HttpServer::open_connections() const { return impl_->connections.total(); }

}  // namespace meshmark::server
