#pragma once
// Starting positions for the dual optimisation of a mesh that was remeshed coarse to fine (RemeshSettings::
// coarse_levels): the optimised dual of the coarse level (a quarter of the atoms, bonds of 2 b) already holds the
// long-range part of the solution, which L-BFGS finds slowest on the fine net: how far the lattice has to flow to
// even out the density of the remeshed triangles. Each fine atom is moved by the displacement of the coarse atoms
// around it (distance weights of the nearest few), so the fine optimisation is left the short-range part.
#include <cstddef>
#include <vector>

#include "carbonmesh/dual/dual_mesh.hpp"
#include "carbonmesh/dual/optimize.hpp"
#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

struct DisplacementTransfer {
  std::size_t atoms = 0;                 // fine atoms moved
  double mean_shift = 0, max_shift = 0;  // how far (Angstrom)
};

// `from`: the coarse atoms where the coarse optimisation started (triangle centroids); `to`: where it ended, in
// the unscaled frame (on or near the surface itself). Moves every atom of `fine` by the displacement to - from of
// the six coarse atoms nearest it, weighted by Franke and Little's ((R - d) / (R d))^2 with R the distance of the
// seventh (a continuous field). Deterministic. Throws std::invalid_argument if from and to differ in size.
DisplacementTransfer transfer_displacements(Dual& fine, const std::vector<Vec3>& from, const std::vector<Vec3>& to);

struct CoarseStartResult {
  int level = 1;                  // the coarse level (remeshed at 2^level times the interval)
  std::size_t coarse_atoms = 0;
  DualOptimizeResult coarse;      // the coarse dual's optimisation
  DisplacementTransfer transfer;  // what it did to the atoms of the next finer net
};

// Builds the dual of `coarse_mesh`, optimises it on `surface` with `settings` at twice the bond and the bond window
// (every other setting as given), and moves the atoms of `fine` by its displacements (transfer_displacements).
CoarseStartResult coarse_start(Dual& fine, const TriMesh& coarse_mesh, const TriMesh& surface,
                               const DualOptimizeSettings& settings);

// A mesh of coarse level k: remeshed at 2^k times the interval of the fine mesh.
struct CoarseLevel {
  int level = 1;
  TriMesh mesh;
};

// Coarse to fine over several levels: the coarsest level's dual is optimised at 2^k times the bond and the window,
// its displacements move the atoms of the next finer level's dual, which is optimised from there, and so on; the
// finest coarse level's displacements (from its triangle centroids, so they include every coarser level's) move
// the atoms of `fine`. The coarse net at level k then starts with the flow of level k + 1 done and needs fewer
// iterations. `levels` in any order (distinct levels >= 1). Returns a result per level, coarsest first.
std::vector<CoarseStartResult> coarse_start(Dual& fine, const std::vector<CoarseLevel>& levels,
                                            const TriMesh& surface, const DualOptimizeSettings& settings);

nlohmann::json to_json(const CoarseStartResult& r);
// The finest coarse level's keys (as to_json of one level) and "levels": every level, coarsest first.
nlohmann::json to_json(const std::vector<CoarseStartResult>& levels);

}  // namespace carbonmesh
