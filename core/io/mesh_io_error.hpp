#pragma once

#include <stdexcept>
#include <string>

namespace meshmark {

/// A mesh file that cannot be read or written; the message says what and where.
class MeshIoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace meshmark
