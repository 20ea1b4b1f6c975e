#pragma once
// Fixture for the layering check: a file of core/mesh that reaches up into core/watermark.
#include "core/mesh/mesh.hpp"
#include "core/watermark/watermark.hpp"
