#pragma once
// Assets the tests make themselves, as studios have them, so that the document suites run
// without the real assets: the creature (procedural_meshes.hpp) with texture coordinates cut
// along a seam (so that its vertices are stored split), normals, a texture file and a material,
// in each format. Written once per process into a temporary folder.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace meshmark::test {

/// The main file of the asset `kind`:
///   "gltf"  .gltf + .bin + texture.png (POSITION, NORMAL, TEXCOORD_0, u16 indices)
///   "glb"   the same in one binary container, the texture embedded in its buffer
///   "obj"   .obj with vt and vn + .mtl naming texture.png
///   "ply"   binary PLY with normals and colours
///   "stl"   binary STL
///   "3mf"   a deflated 3MF package: the model part, relationships, content types, a texture
///   "skinned-glb"  skinned_glb()
/// Throws std::invalid_argument for another kind.
std::filesystem::path procedural_asset(const std::string& kind);

/// The creature (2,562 vertices) as a binary glTF bound to two joints by height (JOINTS_0 u8,
/// WEIGHTS_0, inverse bind matrices), with one morph target that pushes it outward and an
/// animation that turns the upper joint a quarter about z: what a rigged character carries.
std::string skinned_glb();

/// "procedural/<kind>": procedural_asset(kind); any other name: shared_asset(name).
std::filesystem::path named_asset(const std::string& name);

/// A ZIP archive of (name, bytes) in order, each entry deflated (raw deflate, method 8, with
/// zlib) or stored: how a zip tool packs files; written here, not with the code under test.
std::string zip_of(const std::vector<std::pair<std::string, std::string>>& files, bool deflate = true);

/// A 3MF package (deflated) around `model`, the XML of its model part: content types,
/// relationships, the model's own relationships and a texture.
std::string threemf_package(const std::string& model);

}  // namespace meshmark::test
