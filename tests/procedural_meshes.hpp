#pragma once
// Meshes the tests make themselves, so that every suite runs without the real meshes: each has
// one feature that matters to the pipeline (thin limbs, a handle, holes, several parts, inward
// winding, a double-sided sheet). Deterministic: the same mesh on every machine.

#include <filesystem>
#include <string>

#include "core/mesh/mesh.hpp"

namespace meshmark::test {

/// A unit icosahedron subdivided `levels` times and projected on the sphere, outward
/// (10·4^levels + 2 vertices).
Mesh icosphere(int levels);

/// An axis-aligned box [0,1]^3 as 12 triangles, outward.
Mesh cube();

/// A torus (genus 1) with the given resolution: symmetric about its axis.
Mesh torus(int rings, int segments);

/// A torus whose tube thickness and path vary around the ring by `lumps` (0: torus()), so that
/// no rotation maps it onto itself: a handle that can be registered.
Mesh lumpy_torus(int rings, int segments, double lumps);

/// A closed genus-0 "creature" of 10·4^levels + 2 vertices: an icosphere pushed out radially into
/// a lumpy, elongated body with six thin limbs (narrow horns 0.8 to 1.6 body radii long, like
/// legs, ears and a tail: what conformal maps shrink) and fine surface detail. levels 4: 2,562
/// vertices (about spot's size), 5: 10,242.
Mesh creature(int levels);

/// `mesh` with the faces whose centroid lies in a ball of radius `radius` around each of the
/// `holes` vertices spread evenly through its vertex order removed, and the vertices no face
/// uses any more: a surface with holes.
Mesh with_holes(const Mesh& mesh, int holes, double radius);

/// Two meshes in one: `a`, then `b` moved by `shift` along every axis (two components).
Mesh side_by_side(const Mesh& a, const Mesh& b, double shift = 3.0);

/// Two creature(3) touching at one vertex: one component with a pinch (non-manifold) vertex.
Mesh pinched();

/// Every face wound the other way: a mesh whose faces all point inward.
Mesh wound_inward(const Mesh& mesh);

/// Every face stored twice, once per side (the second copy reversed, on the same vertices): a
/// double-sided surface as game assets and CAD exports have them.
Mesh double_sided(const Mesh& mesh);

/// The named shapes the suites share, made once per process: "creature_small" (creature(3):
/// 642 vertices), "creature" (creature(4)),
/// "creature_large" (creature(5)), "torus" (a lumpy handle: 3,840 vertices), "torus_small" (480 vertices),
/// "creature_holes" (creature_large with three holes), "creature_scan" (creature(4) remeshed: evenly spaced vertices on
/// the surface, so its limbs hold many, as on a scan), "creature_coarse" (the same with edges 1.5 times as long: about
/// 1,100 vertices), "parts" (a creature and a torus side by side), "pinched" (pinched()). Throws std::invalid_argument
/// for another name.
const Mesh& procedural_mesh(const std::string& shape);

/// A folder made once per process under the temporary directory (`prefix`-XXXXXX), removed when
/// the process exits.
std::filesystem::path process_temp_folder(const std::string& prefix);

/// procedural_mesh(shape) written once per process as `shape`.`extension` (obj, off, ply, stl)
/// into a temporary folder: for the command line and the daemon.
std::filesystem::path procedural_file(const std::string& shape, const std::string& extension = "obj");

}  // namespace meshmark::test
