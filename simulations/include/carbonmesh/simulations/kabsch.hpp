#pragma once
// Optimal rigid alignment (Kabsch 1976): the rotation and translation that bring one set of points closest, in
// the least-squares sense, to another with the same atoms in the same order. Proper rotations only (det +1).
#include <array>
#include <vector>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

struct Alignment {
  std::array<std::array<double, 3>, 3> rotation{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};  // row-major
  Vec3 translation{0, 0, 0};  // aligned = rotation * moving + translation
  double rmsd = 0;            // root-mean-square distance after alignment
  double max_displacement = 0;  // largest distance of one atom after alignment
  int max_atom = -1;            // the atom with that distance
};

// Aligns `moving` onto `reference` (same size, at least one point). Throws std::invalid_argument otherwise.
Alignment kabsch_align(const std::vector<Vec3>& reference, const std::vector<Vec3>& moving);

// `moving` with the alignment applied.
std::vector<Vec3> apply_alignment(const Alignment& alignment, const std::vector<Vec3>& moving);

}  // namespace carbonmesh
