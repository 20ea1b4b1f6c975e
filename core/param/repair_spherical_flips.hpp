#pragma once
// Local repair of a nearly bijective spherical map: the vertices around flipped triangles are
// relaxed by spherical Tutte sweeps (each moves to the normalized average of its neighbours),
// the region growing ring by ring until no triangle is flipped.

#include "core/mesh/mesh.hpp"

namespace meshmark {

struct RepairOptions {
  int max_rounds = 12;         ///< each round grows the relaxed region by one ring
  int sweeps_per_round = 200;  ///< Gauss–Seidel sweeps over the region
};

struct RepairResult {
  int rounds = 0;
  std::size_t relaxed_vertices = 0;  ///< size of the last region
  bool success = false;              ///< no flipped triangle left
};

/// Repairs `S` (unit vectors, one per vertex) in place. Deterministic.
RepairResult repair_spherical_flips(Vertices& S, const Faces& F, const RepairOptions& options = {});

}  // namespace meshmark
