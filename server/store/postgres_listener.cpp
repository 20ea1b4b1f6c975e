#include "server/store/postgres_listener.hpp"

#include <libpq-fe.h>
#include <fcntl.h>
#include <poll.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cerrno>
#include <memory>
#include <stdexcept>

#include "server/store/postgres_database.hpp"
#include "server/store/storage_error.hpp"

namespace meshmark::server {

namespace {
constexpr std::chrono::milliseconds kFirstReconnectPause{500}, kLastReconnectPause{30'000};
}  // namespace

PostgresListener::PostgresListener(std::string conninfo, std::string channel, std::function<void()> heard)
    : conninfo_(std::move(conninfo)), channel_(std::move(channel)), heard_(std::move(heard)) {
  if (::pipe2(stop_pipe_, O_CLOEXEC) != 0) throw std::runtime_error("listener: cannot make a pipe");
  thread_ = std::thread([this] {
    auto pause = kFirstReconnectPause;
    while (!stopping_) {
      try {
        listen_while_connected();
        pause = kFirstReconnectPause;
      } catch (const std::exception& e) {  // polling still finds the work meanwhile
        spdlog::warn("listening for new jobs: {}; again in {} ms", e.what(), pause.count());
        if (!pause_unless_stopped(pause)) break;
        pause = std::min(pause * 2, kLastReconnectPause);
      }
    }
  });
}

PostgresListener::~PostgresListener() {
  stopping_ = true;
  const char byte = 0;
  [[maybe_unused]] const auto written = ::write(stop_pipe_[1], &byte, 1);
  thread_.join();
  ::close(stop_pipe_[0]);
  ::close(stop_pipe_[1]);
}

bool PostgresListener::pause_unless_stopped(std::chrono::milliseconds pause) const {
  pollfd stop{stop_pipe_[0], POLLIN, 0};
  ::poll(&stop, 1, static_cast<int>(pause.count()));
  return !stopping_;
}

void PostgresListener::listen_while_connected() {
  const std::unique_ptr<PGconn, void (*)(PGconn*)> connection(postgres_connect(conninfo_), PQfinish);
  PGconn* c = connection.get();
  char* quoted = PQescapeIdentifier(c, channel_.data(), channel_.size());
  if (!quoted) throw StorageError("listener: cannot quote the channel", StorageError::Kind::permanent);
  const std::string listen = "LISTEN " + std::string(quoted);
  PQfreemem(quoted);
  const std::unique_ptr<PGresult, void (*)(PGresult*)> result(PQexec(c, listen.c_str()), PQclear);
  if (PQresultStatus(result.get()) != PGRES_COMMAND_OK)
    throw StorageError(std::string("LISTEN: ") + PQerrorMessage(c), StorageError::Kind::unavailable);
  heard_();  // what was announced while nobody listened
  while (!stopping_) {
    pollfd fds[2] = {{PQsocket(c), POLLIN, 0}, {stop_pipe_[0], POLLIN, 0}};
    if (::poll(fds, 2, -1) < 0 && errno != EINTR) throw std::runtime_error("listener: poll failed");
    if (stopping_) return;
    if (PQconsumeInput(c) == 0) throw StorageError(PQerrorMessage(c), StorageError::Kind::unavailable);
    bool announced = false;
    while (PGnotify* n = PQnotifies(c)) {
      announced = true;
      PQfreemem(n);
    }
    if (announced) {
      heard_();
      pause_unless_stopped(kListenerSpacing);  // a burst is heard once
    }
  }
}

}  // namespace meshmark::server
