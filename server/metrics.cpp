#include "server/metrics.hpp"

#include <cstdio>

namespace meshmark::server {

void Metrics::count_request(const std::string& method, const std::string& route, int status) {
  std::lock_guard lock(mutex_);
  ++requests_[{method, route, status}];
}

void Metrics::observe_stage(const std::string& kind, const std::string& stage, double seconds) {
  std::lock_guard lock(mutex_);
  auto& s = stages_[{kind, stage}];
  s.seconds += seconds;
  ++s.count;
}

void Metrics::observe_job(const std::string& kind, const std::string& state, double seconds) {
  std::lock_guard lock(mutex_);
  auto& s = jobs_[{kind, state}];
  s.seconds += seconds;
  ++s.count;
}

void Metrics::append_summary(std::string& out, const char* name, const char* help, const char* second_label,
                             const std::map<std::pair<std::string, std::string>, Sum>& sums) {
  out += std::string("# HELP ") + name + " " + help + "\n# TYPE " + name + " summary\n";
  char line[512];
  for (const auto& [key, s] : sums) {
    std::snprintf(line, sizeof line, "%s_sum{kind=\"%s\",%s=\"%s\"} %.6f\n%s_count{kind=\"%s\",%s=\"%s\"} %lld\n", name,
                  key.first.c_str(), second_label, key.second.c_str(), s.seconds, name, key.first.c_str(), second_label,
                  key.second.c_str(), s.count);
    out += line;
  }
}

namespace {

void append_gauge(std::string& out, const char* name, const char* help, std::size_t value) {
  out += std::string("# HELP ") + name + " " + help + "\n# TYPE " + name + " gauge\n";
  out += std::string(name) + " " + std::to_string(value) + "\n";
}

}  // namespace

std::string Metrics::render(const std::map<std::pair<std::string, std::string>, long long>& jobs,
                            const Live& live) const {
  std::lock_guard lock(mutex_);
  std::string out;
  char line[512];
  out += "# HELP meshmark_http_requests_total HTTP requests by method, route and status.\n";
  out += "# TYPE meshmark_http_requests_total counter\n";
  for (const auto& [key, n] : requests_) {
    std::snprintf(line, sizeof line, "meshmark_http_requests_total{method=\"%s\",route=\"%s\",status=\"%d\"} %lld\n",
                  std::get<0>(key).c_str(), std::get<1>(key).c_str(), std::get<2>(key), n);
    out += line;
  }
  out += "# HELP meshmark_instance_info The daemon that answers.\n# TYPE meshmark_instance_info gauge\n";
  out += "meshmark_instance_info{instance=\"" + live.instance + "\"} 1\n";
  out += "# HELP meshmark_jobs Jobs in the store by kind and state (every daemon on it).\n# TYPE meshmark_jobs gauge\n";
  for (const auto& [key, n] : jobs) {
    std::snprintf(line, sizeof line, "meshmark_jobs{kind=\"%s\",state=\"%s\"} %lld\n", key.first.c_str(),
                  key.second.c_str(), n);
    out += line;
  }
  append_gauge(out, "meshmark_queue_depth", "Jobs waiting for a worker.", live.queued);
  append_gauge(out, "meshmark_queue_capacity", "Jobs the queue holds at most.", live.queue_capacity);
  append_gauge(out, "meshmark_jobs_running", "Jobs on a worker now.", live.running);
  append_gauge(out, "meshmark_memory_reserved_bytes", "Memory held by uploads, jobs and cached models.",
               live.memory_reserved);
  append_gauge(out, "meshmark_memory_ceiling_bytes", "What they may hold together.", live.memory_ceiling);
  append_summary(out, "meshmark_stage_seconds", "Time spent in each pipeline stage.", "stage", stages_);
  append_summary(out, "meshmark_job_seconds", "Wall time of finished jobs.", "state", jobs_);
  return out;
}

}  // namespace meshmark::server
