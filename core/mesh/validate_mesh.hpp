#pragma once
// Everything that decides whether a mesh can be watermarked, measured on the raw face list
// (nothing is repaired first): topology, degeneracy and orientation, with problems in words.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/mesh/mesh.hpp"

namespace meshmark {

enum class Orientation { outward, inward, inconsistent };
std::string to_string(Orientation orientation);

enum class MeshBasis {
  none,           ///< cannot be watermarked
  sphere,         ///< spherical wavelets on the mesh's own spherical map (the paper's method)
  sphere_filled,  ///< the same, its holes closed virtually for the parameterization only
  bumps,          ///< multiscale bumps on the mesh itself: handles, several parts, non-manifold spots
};
std::string to_string(MeshBasis basis);  ///< "none", "sphere", "sphere-filled", "bumps"

/// Components with fewer vertices carry no watermark (they are left as they are)...
inline constexpr std::size_t kMinMarkedComponentVertices = 64;
/// ... unless the larger parts alone would hold too few vertices: then a low-poly model of many
/// small parts shares one payload across every part of at least this many.
inline constexpr std::size_t kMinLowPolyComponentVertices = 16;
/// Fewer marked vertices than this carry no useful payload on any basis (how many bits a mesh
/// above it carries is the embedder's to say: payload_capacity_bits, and every copy is read back).
inline constexpr std::size_t kMinMarkedVertices = 100;

struct ValidateOptions {
  /// A face is "zero-area" when its area is below this times the squared bounding-box diagonal.
  double zero_area_tolerance = 1e-14;
  /// How many examples of each defect to name.
  std::size_t max_examples = 5;
  /// Above 1, the checks of the positions alone run on a second thread beside the
  /// connectivity's. The report is the same either way.
  int threads = 1;
};

struct MeshReport {
  std::size_t vertices = 0;
  std::size_t faces = 0;
  std::size_t components = 0;      ///< connected components of the faces (through shared vertices)
  std::size_t boundary_edges = 0;  ///< edges used by exactly one face
  std::size_t boundary_loops = 0;
  std::size_t nonmanifold_edges = 0;     ///< edges used by more than two faces
  std::size_t nonmanifold_vertices = 0;  ///< vertices whose faces form more than one fan (pinches)
  std::size_t zero_area_faces = 0;
  std::size_t duplicate_vertices = 0;  ///< vertices at exactly the position of an earlier one
  std::size_t isolated_vertices = 0;   ///< vertices no face uses
  long long euler_characteristic = 0;  ///< V − E + F over the vertices faces use
  std::optional<int> genus;            ///< none unless the mesh is a 2-manifold with a whole genus
  Orientation orientation = Orientation::inconsistent;
  double bbox_diagonal = 0;

  std::vector<int> nonmanifold_vertex_examples;
  std::vector<std::array<int, 2>> nonmanifold_edge_examples;
  std::vector<std::array<int, 2>> boundary_edge_examples;
  std::vector<int> zero_area_face_examples;

  /// One closed, 2-manifold, genus-0, consistently oriented surface without degenerate faces or
  /// isolated vertices: the paper's spherical scheme applies as it is.
  bool closed_genus_zero = false;
  std::vector<std::string> sphere_problems;  ///< why it is not, in words

  /// What carries the watermark (see choose_basis in validate_mesh.cpp): the sphere as it is, the
  /// sphere after closing the holes of a genus-0 surface virtually, or bumps on the mesh itself.
  MeshBasis basis = MeshBasis::none;
  std::string basis_reason;                                          ///< why that basis, in words
  std::size_t marked_component_floor = kMinMarkedComponentVertices;  ///< or kMinLowPolyComponentVertices
  std::size_t small_components = 0;          ///< components below marked_component_floor: left unmarked
  std::size_t small_component_vertices = 0;  ///< the vertices they hold

  bool valid = false;                 ///< the mesh can be watermarked (basis is not none)
  std::vector<std::string> problems;  ///< why it cannot be watermarked at all, in words
  std::vector<std::string> warnings;  ///< things worth knowing that do not stop watermarking

  bool operator==(const MeshReport&) const = default;
};

/// Checks a mesh. Never throws on bad topology: a bad mesh gets a report with `valid == false`.
/// Indices in examples and messages are 0-based.
MeshReport validate_mesh(const Mesh& mesh, const ValidateOptions& options = {});

}  // namespace meshmark
