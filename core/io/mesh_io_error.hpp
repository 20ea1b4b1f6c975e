#pragma once

#include <string>

#include "core/util/input_error.hpp"

namespace meshmark {

/// A mesh file that cannot be read or written; the message says what and where.
class MeshIoError : public InputError {
 public:
  using InputError::InputError;
};

/// A mesh file beyond a reader's limits (vertices, faces, bytes).
class MeshLimitError : public MeshIoError {
 public:
  using MeshIoError::MeshIoError;
};

}  // namespace meshmark
