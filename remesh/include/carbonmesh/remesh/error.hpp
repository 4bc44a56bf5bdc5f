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

// Exit code of the CLI when the remesher's topology guard fired: the final mesh had another surface type
// (genus, components, borders) than the input, and the best mesh with the input's surface type was written.
inline constexpr int kExitTopologyViolation = 3;

}  // namespace carbonmesh
