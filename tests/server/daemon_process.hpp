#pragma once
// The real meshmarkd, started through deploy/start-daemon.sh on a free loopback port with its
// own data directory, for integration tests; plus a few raw HTTP helpers.

#include "client/httplib.hpp"
#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

namespace meshmark::test {

class DaemonProcess {
 public:
  /// Starts a daemon on `data` (created if missing) with extra flags; waits until it listens.
  /// `wrapper`: a command the start script runs under (e.g. unshare), its arguments first.
  explicit DaemonProcess(std::filesystem::path data, std::vector<std::string> flags = {},
                         std::vector<std::string> wrapper = {});
  ~DaemonProcess();
  DaemonProcess(const DaemonProcess&) = delete;
  DaemonProcess& operator=(const DaemonProcess&) = delete;

  int port() const { return port_; }
  pid_t pid() const { return pid_; }
  std::string url() const { return "http://127.0.0.1:" + std::to_string(port_); }
  httplib::Client client() const;
  const std::filesystem::path& data() const { return data_; }

  /// SIGTERM and wait; returns the exit status.
  int terminate();
  /// SIGTERM without waiting (the daemon drains); then wait_exit().
  void send_term();
  /// Waits for the process to end; returns the exit status (-1 if killed by a signal).
  int wait_exit();
  /// SIGKILL and wait.
  void kill_hard();
  bool running() const { return pid_ > 0; }

  static const char* admin_token() { return "integration-test-admin-token"; }

 private:
  std::filesystem::path data_;
  pid_t pid_ = -1;
  int port_ = 0;
};

/// A fresh temporary directory, removed by the caller's choice (tests keep it on failure).
std::filesystem::path temp_dir(const std::string& name);

/// Sends raw bytes on a new connection and returns everything answered until the peer closes.
std::string raw_http(int port, const std::string& request);

/// The status code of a raw HTTP response ("HTTP/1.1 411 ..." → 411).
int status_of(const std::string& raw_response);

/// One TCP connection to the daemon, driven byte by byte: for framing, pipelining and slow or
/// idle clients.
class RawConnection {
 public:
  /// Connects to the daemon on 127.0.0.1 from `source` (another loopback address is another client).
  explicit RawConnection(int port, const std::string& source = "127.0.0.1");
  ~RawConnection();
  RawConnection(const RawConnection&) = delete;
  RawConnection& operator=(const RawConnection&) = delete;

  /// Sends bytes; false once the peer has closed.
  bool send(const std::string& bytes);
  /// One response (head and the body its Content-Length announces); empty when the peer closed
  /// first or nothing whole came within `timeout`.
  std::string read_response(std::chrono::milliseconds timeout = std::chrono::milliseconds(5000));
  /// True when the peer closes the connection within `timeout` (whatever else it sends first).
  bool closed_within(std::chrono::milliseconds timeout);

 private:
  int fd_ = -1;
  std::string pending_;  // bytes read past the last response
};

/// Runs meshmarkd (through the start script) with `args` until it exits (at most 20 s); its
/// exit status and everything it printed.
struct DaemonRun {
  int exit_status = -1;
  std::string output;
};
DaemonRun run_daemon_until_exit(const std::vector<std::string>& args, const std::string& environment = "");

}  // namespace meshmark::test
