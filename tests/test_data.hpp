#pragma once
// Where tests find the shared meshes (never copied into the repository) and small synthetic ones.

#include <filesystem>
#include <string>

#include "core/mesh/mesh.hpp"

namespace meshmark::test {

/// ../shared/meshes (or $MESHMARK_MESHES), with `name` appended.
std::filesystem::path shared_mesh(const std::string& name);

/// ../shared/assets (or $MESHMARK_ASSETS), with `relative` appended: the real assets.
std::filesystem::path shared_asset(const std::string& relative);

/// Reads a shared mesh (cached per process; meshes are immutable).
const Mesh& load_shared(const std::string& name);

/// A unit icosahedron subdivided `levels` times and projected on the sphere, outward.
Mesh icosphere(int levels);

/// An axis-aligned box [0,1]^3 as 12 triangles, outward.
Mesh cube();

/// A torus (genus 1) with the given resolution.
Mesh torus(int rings, int segments);

/// spot with three faces taken out: three small holes, still one genus-0 2-manifold (a
/// filled-sphere mesh small enough for the sanitizer build).
Mesh spot_with_holes();

/// Two meshes in one: `a`, then `b` moved by `shift` along every axis (two components).
Mesh side_by_side(const Mesh& a, const Mesh& b, double shift = 3.0);

}  // namespace meshmark::test
