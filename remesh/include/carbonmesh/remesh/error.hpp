#pragma once
#include <stdexcept>
#include <string>

namespace carbonmesh {

// Bad input (a file, a value): the CLI prints what() on one line and exits with code 2.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Exit code of the CLI for bad input.
inline constexpr int kExitBadInput = 2;

}  // namespace carbonmesh
