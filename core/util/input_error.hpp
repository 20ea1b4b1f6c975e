#pragma once
// A failure caused by the input (a file, a mesh, an option), with a message meant for the person
// who gave it. The core also reports bad arguments as std::invalid_argument; any other exception
// is a bug or an environment failure, and services show it to no one but their log.

#include <stdexcept>

namespace meshmark {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace meshmark
