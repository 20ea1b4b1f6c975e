#pragma once
// Re-saving as text: every coordinate kept to a number of significant decimal digits, as a tool
// writing "%.6g" (a common default) keeps it.

#include "core/mesh/mesh.hpp"

namespace meshmark {

/// Every coordinate rounded to `digits` significant decimal digits (1..17).
Mesh round_digits(const Mesh& mesh, int digits);
void round_digits_in_place(Vertices& V, int digits);

}  // namespace meshmark
