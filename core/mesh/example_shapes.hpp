#pragma once
// Shapes made by code, each with one feature that matters to the pipeline (thin limbs, a handle,
// holes, several parts, a pinch vertex, inward winding, a double-sided sheet): for trying
// meshmark without a mesh of one's own (`meshmark example`) and for the tests. Deterministic:
// the same mesh on every machine.

#include <string>

#include "core/mesh/mesh.hpp"

namespace meshmark {

/// A unit icosahedron subdivided `levels` times and projected on the sphere, outward
/// (10·4^levels + 2 vertices).
Mesh icosphere(int levels);

/// icosphere(levels) with every vertex slid along the sphere by up to a fifth of an edge, the
/// same way on every machine: a ball tessellated unevenly, as exporters leave one. Every turn
/// fits its shape; its vertices alone tell the turns apart.
Mesh uneven_ball(int levels);

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

/// The shapes `meshmark example` writes, by name: "creature" (creature(4)), "creature-large"
/// (creature(5)), "torus" (lumpy_torus(96, 40, 1): 3,840 vertices), "creature-holes"
/// (creature(5) with three holes), "parts" (a creature and a torus side by side). Throws
/// std::invalid_argument naming the shapes for another name.
Mesh example_shape(const std::string& name);

/// The names example_shape() knows, comma-separated.
std::string example_shape_names();

}  // namespace meshmark
