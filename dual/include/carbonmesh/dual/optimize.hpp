#pragma once
// Dual optimisation: moves the atoms so that every bond is close to the target length b and every bond angle
// close to 120 degrees while the atoms stay on the input surface. Minimises, with L-BFGS,
//   E(x) = sum_bonds (|x_i - x_j| - b)^2 + w_h max(0, ||x_i - x_j| - b| - delta)^2
//          + w_a b^2 sum_angles (cos theta - cos theta_0)^2 + w_s sum_atoms d(x_i, s S)^2
// where S is the primal triangle mesh (closest points from a CGAL AABB tree) and theta_0 is the interior angle
// of a regular polygon of the size of the ring the angle lies in: 120 degrees in hexagons (and outside closed
// rings, at borders), 108 in pentagons, 128.6 in heptagons, so defects are not forced flat. Deterministic.
#include <nlohmann/json_fwd.hpp>

#include "carbonmesh/dual/dual_mesh.hpp"
#include "carbonmesh/dual/graph_stats.hpp"
#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

struct DualOptimizeSettings {
  double bond = 1.42;                 // target bond length b (Angstrom)
  // w_a. On a curved surface equal bonds and ideal angles exclude each other (a flat net cannot cover a
  // sphere without metric distortion). Chosen by the REBO2 energy of the result (tools/bench/angle_weight.py):
  // from 0.01 to 0.1 it falls by 40-60 meV/atom (0.2 gains under 1 meV more), the angle spread narrows
  // (std 10.4 -> 8.3 degrees on bunny at 20000 atoms, angles above 150 degrees 0.45% -> 0.13%) while every
  // bond stays within b +- 0.05 A (the window hinge); 0.2 lets bunny's reach b + 0.054.
  double angle_weight = 0.1;
  double surface_weight = 10.0;       // w_s (per Angstrom^2)
  // Window hinge: + w_h sum max(0, |l - b| - delta)^2. The quadratic bond term alone lets a few bonds at
  // crowded 5-7 defects of large structures drift to b +- 0.06 A while the rest sit within 0.03; bond
  // stretching is far stiffer than bending in real sp2 carbon, so bonds outside b +- delta pay 100 times more.
  double bond_window = 0.04;          // delta (Angstrom)
  double bond_window_weight = 100.0;  // w_h (0: off)
  // Contact term: + w_c sum max(0, sqrt(2) b - |x_i - x_j|)^2 over non-bonded pairs. Keeps bond angles at 90
  // degrees or more and other atoms sqrt(2) b apart where the surface is thinner than the bond scale (without
  // it the bond term folds the net there: atoms 0.14 A apart on armadillo at 20000 atoms).
  double contact_weight = 100.0;      // w_c (per Angstrom^2; 0: off)
  int max_iterations = 2000;          // L-BFGS iterations at most (0: only measure)
  double gradient_tolerance = 1e-4;   // converged when every |dE/dx| is below this (bonds then settle to ~1e-4 A)
  // ... or when E fell by less than energy_tolerance * E over the last 10 iterations (0: off). The tail after
  // that moves bonds by ~1e-3 A and costs most of the iterations (fertility at 20000 atoms: 200 instead of
  // 2000 iterations, bond extremes within 0.004 A of the fully converged ones).
  double energy_tolerance = 1e-3;
  int memory = 8;                     // L-BFGS history length
  // Hold the atoms on s S with the scale s free (one more unknown) instead of on S itself: the shape is
  // prescribed, the size follows from the atom count and b (see docs/algorithm.md, "Dual optimisation").
  bool free_scale = true;
};

struct DualOptimizeResult {
  SampleStats bonds_before, bonds_after;    // bond lengths (Angstrom)
  SampleStats angles_before, angles_after;  // bond angles (degrees)
  // Atoms with a bond angle outside [90, 150] degrees (sp2 rings of 5..8 atoms have 108..135): strained
  // spots, e.g. where the surface has features thinner than the bond scale.
  std::size_t strained_before = 0, strained_after = 0;
  double surface_max_before = 0, surface_max_after = 0;  // largest atom distance to the surface
  double surface_rms_after = 0;
  double energy_before = 0, energy_after = 0;
  double surface_scale = 1;  // s (1 without free_scale); surface distances are to s S
  Vec3 scale_centre{0, 0, 0};  // c: the atoms x sit at c + s (y - c), y on or near S
  int iterations = 0, evaluations = 0;
  bool converged = false;
  double seconds = 0;
};

// Moves the atoms of `dual` (its DualMesh points). `surface` is the primal mesh the dual was built from.
// Throws std::invalid_argument for a non-positive bond length or negative weights.
DualOptimizeResult optimize_dual(Dual& dual, const TriMesh& surface, const DualOptimizeSettings& settings = {});

nlohmann::json to_json(const DualOptimizeResult& r);

}  // namespace carbonmesh
