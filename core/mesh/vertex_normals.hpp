#pragma once

#include "core/mesh/mesh.hpp"

namespace meshmark {

/// #V×3 unit vertex normals: the area-weighted sum of the normals of the faces around each
/// vertex (faces wound counter-clockwise seen from outside give outward normals).
/// An isolated vertex gets a zero row.
Vertices vertex_normals(const Vertices& V, const Faces& F);

/// #F×3 unit face normals (zero rows for degenerate faces).
Vertices face_normals(const Vertices& V, const Faces& F);

}  // namespace meshmark
