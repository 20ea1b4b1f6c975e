#pragma once
// Consistent winding for meshes that are not one closed surface: faces joined across manifold
// edges form patches, wound alike within each (as far as the patch is orientable); a closed patch
// is then turned outward (positive signed volume), an open one to the winding most of its faces
// had. Used for normals and areas only: the mesh's own faces are never changed.

#include <cstddef>

#include "core/mesh/mesh.hpp"

namespace meshmark {

struct OrientedPatches {
  Faces faces;  ///< #F×3, each the input face or its reverse
  std::size_t patches = 0;
  std::size_t reversed = 0;  ///< faces reversed relative to the input
};

OrientedPatches orient_patches(const Vertices& V, const Faces& F);

}  // namespace meshmark
