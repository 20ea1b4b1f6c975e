#pragma once
// Fixture for the layering check: a file of core/mesh that includes only mesh and util.
#include "core/mesh/mesh.hpp"
#include "core/util/parallel_for.hpp"
#include <vector>
