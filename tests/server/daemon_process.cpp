#include "tests/server/daemon_process.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <regex>
#include <stdexcept>
#include <thread>

namespace meshmark::test {

std::filesystem::path temp_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("meshmark-" + name + "-" + std::to_string(::getpid()) + "-" +
                    std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
  std::filesystem::create_directories(dir);
  return dir;
}

DaemonProcess::DaemonProcess(std::filesystem::path data, std::vector<std::string> flags) : data_(std::move(data)) {
  std::filesystem::create_directories(data_);
  int out[2];
  if (::pipe(out) != 0) throw std::runtime_error("pipe failed");
  pid_ = ::fork();
  if (pid_ < 0) throw std::runtime_error("fork failed");
  if (pid_ == 0) {
    ::dup2(out[1], STDOUT_FILENO);
    ::close(out[0]);
    ::close(out[1]);
    ::setenv("MESHMARK_DAEMON", MESHMARK_DAEMON, 1);
    ::setenv("MESHMARK_ADMIN_TOKEN", admin_token(), 1);
    ::setenv("MESHMARK_LOG_LEVEL", "warn", 1);
    std::vector<std::string> args = {MESHMARK_START_SCRIPT, "--listen", "127.0.0.1:0", "--data", data_.string()};
    args.insert(args.end(), flags.begin(), flags.end());
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
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
        length_at < end ? std::stoul(response.substr(length_at + 16, response.find("\r\n", length_at) - length_at - 16)) : 0;
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
