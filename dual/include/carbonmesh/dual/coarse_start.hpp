#pragma once
// Starting positions for the dual optimisation of a mesh that was remeshed coarse to fine (RemeshSettings::
// coarse_levels): the optimised dual of the coarse level (a quarter of the atoms, bonds of 2 b) already holds the
// long-range part of the solution, which L-BFGS finds slowest on the fine net: how far the lattice has to flow to
// even out the density of the remeshed triangles. Each fine atom is moved by the displacement of the coarse atoms
// around it (inverse-distance weights of the nearest few), so the fine optimisation is left the short-range part.
#include <cstddef>
#include <vector>

#include "carbonmesh/dual/dual_mesh.hpp"

namespace carbonmesh {

struct CoarseStartResult {
  std::size_t atoms = 0;              // fine atoms moved
  double mean_shift = 0, max_shift = 0;  // how far (Angstrom)
};

// `from`: the coarse atoms where the coarse optimisation started (triangle centroids); `to`: where it ended, on
// the unscaled surface (DualOptimizeResult::unscaled). Moves the atoms of `fine`. Deterministic.
CoarseStartResult coarse_start(Dual& fine, const std::vector<Vec3>& from, const std::vector<Vec3>& to);

}  // namespace carbonmesh
