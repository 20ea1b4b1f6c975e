// meshmarkd: the meshmark watermarking daemon.

#include <signal.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <exception>

#include "server/config.hpp"
#include "core/util/huge_pages.hpp"
#include "server/daemon.hpp"

int main(int argc, char** argv) {
  meshmark::restart_with_huge_pages(argv);  // first: nothing done yet is lost to the restart
  meshmark::server::DaemonConfig config;
  int exit_code = 0;
  if (!meshmark::server::parse_config(argc, argv, config, exit_code)) return exit_code;
  // Logs on stderr; stdout carries only the "listening on" line that scripts wait for.
  spdlog::set_default_logger(spdlog::stderr_color_mt("meshmarkd"));
  // A client that hangs up mid-response must not kill the daemon.
  ::signal(SIGPIPE, SIG_IGN);
  spdlog::set_level(spdlog::level::from_str(config.log_level));
  try {
    return meshmark::server::run_daemon(config);
  } catch (const std::exception& e) {
    spdlog::critical("meshmarkd cannot start: {}", e.what());
    return 1;
  }
}
