#pragma once
// What expanding a scene may spend, whatever its hierarchy claims. glTF nodes and 3MF components
// may form a DAG: a kilobyte that lists each level's child twice places a mesh 2^depth times. So
// every placement visited and every further instance copied is counted as it is made (before
// its copy is built), against fixed ceilings and the reader's limits, and the job's deadline and
// cancellation are polled as the walk goes.

#include <cstddef>
#include <string>

#include "core/io/read_options.hpp"

namespace meshmark {

/// Node or component placements one scene walk may visit.
inline constexpr std::size_t kMaxScenePlacements = 1'000'000;
/// Further instances (placements of a mesh already placed) one scene may hold.
inline constexpr std::size_t kMaxFurtherInstances = 10'000;

class SceneBudget {
 public:
  SceneBudget(const ReadOptions& limits, std::string source) : limits_(limits), source_(std::move(source)) {}

  /// One more node or component visited; MeshLimitError beyond kMaxScenePlacements.
  void visit();
  /// A further instance of `vertices` and `faces` about to be copied; MeshLimitError when it
  /// would pass kMaxFurtherInstances or the reader's vertex or face limit (counted over every
  /// further instance).
  void add_instance(std::size_t vertices, std::size_t faces);

 private:
  [[noreturn]] void fail(const std::string& what) const;

  ReadOptions limits_;
  std::string source_;
  std::size_t placements_ = 0, instances_ = 0, vertices_ = 0, faces_ = 0;
};

}  // namespace meshmark
