#pragma once
// Areas: per face, and lumped per vertex.

#include <Eigen/Core>

#include "core/mesh/mesh.hpp"

namespace meshmark {

/// #F triangle areas.
Eigen::VectorXd face_areas(const Vertices& V, const Faces& F);

/// #V barycentric lumped mass: a third of the area of each face around the vertex.
/// (The diagonal of the lumped mass matrix; Σ = total area.)
Eigen::VectorXd vertex_areas(const Vertices& V, const Faces& F);

}  // namespace meshmark
