// The HTTP transport on arbitrary bytes, over a real loopback socket: the bytes are one client's
// side of a connection (pipelined requests, bodies, framing tricks), then its half-close. The
// server answers with well-formed responses (a status line of the request's version, headers, and exactly the body its
// Content-Length announces) or closes; it never crashes or hangs, and a handler never sees a body
// longer than its plan allows.

#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <thread>

#include "server/http/http_server.hpp"
#include "tests/fuzz/fuzz_target.hpp"

namespace {

using namespace meshmark::server;

constexpr std::size_t kMemoryLimit = 4096, kFileLimit = 65536;

class PlanningHandler : public HttpHandler {
 public:
  std::optional<HttpResponse> answer_at_once(HttpRequest& head) override {
    if (head.path == "/livez") return HttpResponse{200, "text/plain", "ok", {}};
    return std::nullopt;
  }
  std::variant<HttpResponse, BodyPlan> admit(HttpRequest& head) override {
    if (head.path == "/memory") return BodyPlan{BodyPlan::Kind::memory, kMemoryLimit, true};
    if (head.path == "/file") return BodyPlan{BodyPlan::Kind::file, kFileLimit, true};
    if (head.path == "/refuse") return HttpResponse{403, "text/plain", "no", {}};
    return BodyPlan{};
  }
  HttpResponse respond(HttpRequest& request) override {
    if (request.body.size() > kMemoryLimit || request.body_bytes > kFileLimit) __builtin_trap();
    if (!request.body_file.empty() && std::filesystem::file_size(request.body_file) != request.body_bytes)
      __builtin_trap();
    return {200, "text/plain", std::to_string(request.body_bytes), {}};
  }
  HttpResponse refusal(int status, const std::string& detail) override { return {status, "text/plain", detail, {}}; }
  void observe(const HttpRequest&, const HttpResponse&) override {}
};

// One server for the whole run, on its own threads.
int server_port() {
  static PlanningHandler handler;
  static const int port = [] {
    HttpServerOptions options;
    options.port = 0;
    options.io_threads = 1;
    options.handler_threads = 2;
    options.header_timeout = std::chrono::milliseconds(2000);
    options.body_idle_timeout = std::chrono::milliseconds(2000);
    options.upload_dir = std::filesystem::temp_directory_path() / ("fuzz-http-" + std::to_string(::getpid()));
    auto* server = new HttpServer(options, handler);  // lives as long as the process
    const int bound = server->bind();
    std::thread([server] { server->run(); }).detach();
    return bound;
  }();
  return port;
}

// A connection to the server. It is reset when closed (SO_LINGER 0), not left in TIME_WAIT:
// thousands of exchanges a second would otherwise use up the ephemeral ports.
int connect_to(int port) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    const linger reset{1, 0};
    ::setsockopt(fd, SOL_SOCKET, SO_LINGER, &reset, sizeof reset);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0) return fd;
    ::close(fd);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  __builtin_trap();  // the server no longer accepts
}

// Everything the server sends until it closes (or 5 s pass).
std::string exchange(int port, std::string_view bytes) {
  const int fd = connect_to(port);
  for (std::size_t sent = 0; sent < bytes.size();) {
    const ssize_t n = ::send(fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) break;  // the server closed first (a refusal)
    sent += static_cast<std::size_t>(n);
  }
  ::shutdown(fd, SHUT_WR);
  std::string answer;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  char buffer[16384];
  while (std::chrono::steady_clock::now() < deadline) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 100) <= 0) continue;
    const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
    if (n <= 0) break;
    answer.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fd);
  return answer;
}

// Walks the responses: each a status line, headers and the body its Content-Length announces.
void check_responses(std::string_view answer) {
  while (!answer.empty()) {
    if (answer.substr(0, 9) != "HTTP/1.1 " && answer.substr(0, 9) != "HTTP/1.0 ") __builtin_trap();  // as asked
    const auto head_end = answer.find("\r\n\r\n");
    if (head_end == std::string_view::npos) __builtin_trap();
    const std::string_view head = answer.substr(0, head_end);
    std::size_t length = 0;
    if (const auto at = head.find("\r\nContent-Length: "); at != std::string_view::npos)
      length = std::stoul(std::string(head.substr(at + 18, head.find("\r\n", at + 2) - at - 18)));
    if (answer.size() < head_end + 4 + length) __builtin_trap();
    answer.remove_prefix(head_end + 4 + length);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  check_responses(exchange(server_port(), as_text(data, size)));
  return 0;
}
