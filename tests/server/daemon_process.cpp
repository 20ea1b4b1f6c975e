#include "tests/server/daemon_process.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <poll.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <regex>
#include <stdexcept>
#include <thread>

#include "tests/build_paths.hpp"

namespace meshmark::test {

std::filesystem::path temp_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("meshmark-" + name + "-" + std::to_string(::getpid()) + "-" +
                    std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
  std::filesystem::create_directories(dir);
  return dir;
}

DaemonProcess::DaemonProcess(std::filesystem::path data, std::vector<std::string> flags,
                             std::vector<std::string> wrapper)
    : data_(std::move(data)) {
  std::filesystem::create_directories(data_);
  int out[2];
  if (::pipe(out) != 0) throw std::runtime_error("pipe failed");
  pid_ = ::fork();
  if (pid_ < 0) throw std::runtime_error("fork failed");
  if (pid_ == 0) {
    // A test that dies (an assertion, a sanitizer abort) takes its daemon with it, instead of
    // leaving it holding ctest's output pipe until the time limit.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    ::dup2(out[1], STDOUT_FILENO);
    ::close(out[0]);
    ::close(out[1]);
    ::setenv("MESHMARK_DAEMON", daemon_program(), 1);
    ::setenv("MESHMARK_ADMIN_TOKEN", admin_token(), 1);
    ::setenv("MESHMARK_LOG_LEVEL", "warn", 1);
    std::vector<std::string> args = wrapper;
    for (const std::string& a : {std::string(start_script()), std::string("--listen"), std::string("127.0.0.1:0"),
                                 std::string("--data"), data_.string()})
      args.push_back(a);
    args.insert(args.end(), flags.begin(), flags.end());
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execvp(argv[0], argv.data());
    ::_exit(127);
  }
  ::close(out[1]);
  // Read stdout until the daemon says where it listens.
  std::string text;
  char buffer[512];
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  const std::regex listening(R"(listening on http://[0-9.]+:([0-9]+))");
  std::smatch m;
  while (!std::regex_search(text, m, listening)) {
    if (std::chrono::steady_clock::now() > deadline) throw std::runtime_error("the daemon did not start: " + text);
    const ssize_t n = ::read(out[0], buffer, sizeof buffer);
    if (n <= 0) throw std::runtime_error("the daemon exited before listening: " + text);
    text.append(buffer, static_cast<std::size_t>(n));
  }
  port_ = std::stoi(m[1]);
  ::close(out[0]);  // the daemon prints no more to stdout
}

DaemonProcess::~DaemonProcess() {
  if (pid_ > 0) kill_hard();
}

httplib::Client DaemonProcess::client() const {
  httplib::Client c("127.0.0.1", port_);
  c.set_read_timeout(120, 0);
  c.set_write_timeout(120, 0);
  return c;
}

int DaemonProcess::terminate() {
  send_term();
  return wait_exit();
}

void DaemonProcess::send_term() { ::kill(pid_, SIGTERM); }

int DaemonProcess::wait_exit() {
  int status = 0;
  ::waitpid(pid_, &status, 0);
  pid_ = -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

void DaemonProcess::kill_hard() {
  ::kill(pid_, SIGKILL);
  int status = 0;
  ::waitpid(pid_, &status, 0);
  pid_ = -1;
}

std::string raw_http(int port, const std::string& request) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<uint16_t>(port));
  ::inet_pton(AF_INET, "127.0.0.1", &addr.sin_addr);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    ::close(fd);
    throw std::runtime_error("cannot connect");
  }
  timeval timeout{20, 0};  // longer than the daemon's read timeout (10 s)
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  std::size_t sent = 0;
  while (sent < request.size()) {
    const ssize_t n = ::send(fd, request.data() + sent, request.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) break;  // the daemon may answer and close before reading everything
    sent += static_cast<std::size_t>(n);
  }
  // Read one response: the headers, then as many bytes as they announce. (No half-close:
  // cpp-httplib drops the response when it sees the peer's FIN.)
  std::string response;
  char buffer[4096];
  ssize_t n;
  while ((n = ::recv(fd, buffer, sizeof buffer, 0)) > 0) {
    response.append(buffer, static_cast<std::size_t>(n));
    const std::size_t end = response.find("\r\n\r\n");
    if (end == std::string::npos) continue;
    const std::size_t length_at = response.find("Content-Length: ");
    const std::size_t length =
        length_at < end ? std::stoul(response.substr(length_at + 16, response.find("\r\n", length_at) - length_at - 16))
                        : 0;
    if (response.size() >= end + 4 + length) break;
  }
  ::close(fd);
  return response;
}

int status_of(const std::string& raw_response) {
  if (raw_response.size() < 12 || raw_response.rfind("HTTP/1.", 0) != 0) return -1;
  return std::stoi(raw_response.substr(9, 3));
}

}  // namespace meshmark::test

namespace meshmark::test {

namespace {

int connect_loopback(int port, const std::string& source = "127.0.0.1") {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in from{};
  from.sin_family = AF_INET;
  ::inet_pton(AF_INET, source.c_str(), &from.sin_addr);
  if (::bind(fd, reinterpret_cast<sockaddr*>(&from), sizeof from) != 0) {
    ::close(fd);
    throw std::runtime_error("cannot bind to " + source);
  }
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<uint16_t>(port));
  ::inet_pton(AF_INET, "127.0.0.1", &addr.sin_addr);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    ::close(fd);
    throw std::runtime_error("cannot connect to 127.0.0.1:" + std::to_string(port));
  }
  return fd;
}

// Length of the first whole response in `text`, or 0 if it is not all there yet.
std::size_t whole_response(const std::string& text) {
  const std::size_t end = text.find("\r\n\r\n");
  if (end == std::string::npos) return 0;
  std::size_t length = 0;
  const std::string head = text.substr(0, end);
  const std::size_t at = head.find("Content-Length: ");
  if (at != std::string::npos) length = std::stoul(head.substr(at + 16, head.find("\r\n", at) - at - 16));
  return text.size() >= end + 4 + length ? end + 4 + length : 0;
}

}  // namespace

RawConnection::RawConnection(int port, const std::string& source) : fd_(connect_loopback(port, source)) {}

RawConnection::~RawConnection() {
  if (fd_ >= 0) ::close(fd_);
}

bool RawConnection::send(const std::string& bytes) {
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    const ssize_t n = ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) return false;
    sent += static_cast<std::size_t>(n);
  }
  return true;
}

std::string RawConnection::read_response(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  char buffer[16384];
  while (whole_response(pending_) == 0) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return {};
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) return {};
    const ssize_t n = ::recv(fd_, buffer, sizeof buffer, 0);
    if (n <= 0) return {};
    pending_.append(buffer, static_cast<std::size_t>(n));
  }
  const std::size_t length = whole_response(pending_);
  std::string response = pending_.substr(0, length);
  pending_.erase(0, length);
  return response;
}

bool RawConnection::closed_within(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  char buffer[16384];
  while (true) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) return false;
    const ssize_t n = ::recv(fd_, buffer, sizeof buffer, 0);
    if (n <= 0) return true;  // FIN or reset
    pending_.append(buffer, static_cast<std::size_t>(n));
  }
}

DaemonRun run_daemon_until_exit(const std::vector<std::string>& args, const std::string& environment) {
  std::string command =
      environment + " MESHMARK_DAEMON=" + std::string(daemon_program()) + " timeout 20 " + std::string(start_script());
  for (const std::string& a : args) command += " '" + a + "'";
  command += " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run " + command);
  DaemonRun run;
  char buffer[4096];
  std::size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) run.output.append(buffer, n);
  const int status = ::pclose(pipe);
  run.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

}  // namespace meshmark::test
