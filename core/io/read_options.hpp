#pragma once
// The limits every reader keeps to, whatever a file's header claims.

#include <cstddef>

#include "core/util/job_control.hpp"

namespace meshmark {

/// Limits that keep a hostile file from taking the machine down. Every reader's work is linear
/// (or n log n) in the file's size, whatever its header claims.
struct ReadOptions {
  std::size_t max_vertices = 50'000'000;    ///< refuse files with more vertices (MeshLimitError)
  std::size_t max_faces = 100'000'000;      ///< refuse files with more (triangulated) faces (MeshLimitError)
  std::size_t max_file_bytes = 4ull << 30;  ///< refuse larger files (read_mesh from a path)
  const JobControl* control = nullptr;      ///< polled while reading: a time limit or a cancel stops it
};

/// A glTF's JSON may hold at most this many values (json_shape's bound, before it is parsed):
/// its parsed tree costs ~100 bytes per value, ~80 times the text.
inline constexpr std::size_t kMaxGltfJsonValues = 4'000'000;

/// Coordinates beyond this magnitude are refused: the pipeline multiplies coordinates (areas,
/// normals, squared distances), and must stay far from overflow.
inline constexpr double kMaxCoordinate = 1e30;

}  // namespace meshmark
