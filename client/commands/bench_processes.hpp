#pragma once
// `meshmark bench --processes` and `--versus`: whole processes of our own commands (a cold and a
// warm embed, detection with a record and with the original), side by side with any other
// command, alternating, each also as a multiple of reading and writing the same mesh.

#include <string>
#include <vector>

namespace meshmark::cli {

struct ProcessBenchArguments {
  std::vector<std::string> meshes;
  bool default_meshes = false;
  int subdivide = 0;  ///< also the first mesh Loop-subdivided this many times (0: not)
  int runs = 5;
  int threads = 0;
  std::vector<std::string> versus;  ///< NAME=COMMAND, compared with our row NAME when there is one
  bool json = false;
};

/// Runs the rounds and prints the table (or JSON); returns the exit status.
int run_process_bench(const ProcessBenchArguments& arguments);

}  // namespace meshmark::cli
