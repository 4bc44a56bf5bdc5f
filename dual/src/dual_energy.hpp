#pragma once
// The energy the dual optimisation minimises (optimize.hpp) and its gradient. Internal to dual.
//
// The unknowns are y (3n coordinates) and, with a free scale, u: the atoms sit at x = c + s (y - c) with
// s = 1 + u / radius, c the area centroid of S and radius the RMS distance of S from c. Bond lengths are s |y_i - y_j|,
// angles do not depend on s, and the distance of x to s S is s d(y, S). So a change of u moves every atom and
// the surface together, and the size of the structure is one well-conditioned direction of the minimisation
// (holding atoms on a moving surface through the surface springs instead converges very slowly).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "carbonmesh/dual/dual_mesh.hpp"
#include "carbonmesh/dual/graph_stats.hpp"
#include "carbonmesh/dual/optimize.hpp"
#include "contact_term.hpp"
#include "surface_projector.hpp"

namespace carbonmesh::detail {

// An evaluation is one pass over the atoms and then one over their neighbour slots, both parallel with no two
// threads writing the same place. Atom c computes its bonds (each bond from both ends, its energy counted at the
// lower one), the angles centred on it with the contact term of the pair at the angle's ends, and its surface
// distance: the gradient on c goes straight into g, the gradient the angles put on c's neighbours into c's
// slots. The second pass adds to every atom the slots that name it, in a fixed order. The contact term of the
// pairs more than two bonds apart comes from ContactTerm. Energies are summed per fixed chunk of atoms and the
// chunks in order: the result does not depend on the thread count.
class DualEnergy {
 public:
  // `angles` sorted by centre atom; target_cosines[a] the cosine angle a is pulled to (held by reference);
  // faces[i] the surface face atom i starts its closest-point walk from.
  DualEnergy(const std::vector<AtomPair>& bonds, const std::vector<AtomTriple>& angles,
             const std::vector<double>& target_cosines, const SurfaceProjector& projector, double radius,
             std::vector<int> faces, const DualOptimizeSettings& settings);

  // The energy at x (3n coordinates, then u with a free scale); its gradient into g.
  double operator()(const Eigen::VectorXd& x, Eigen::VectorXd& g);

  double scale(const Eigen::VectorXd& x) const { return s_.free_scale ? 1.0 + x[x.size() - 1] / radius_ : 1.0; }
  const std::vector<int>& faces() const { return faces_; }
  std::size_t contact_rebuilds() const { return contacts_.rebuilds(); }

  static constexpr std::size_t kParallelAtoms = 20000;  // smaller structures are evaluated in one thread
  static constexpr std::uint32_t kMaxBonds = 8;         // per atom (a dual of a triangle mesh has at most 3)

 private:
  bool parallel() const { return faces_.size() >= kParallelAtoms; }

  const SurfaceProjector& projector_;
  double radius_;
  std::vector<int> faces_;  // the surface face each atom was last projected to (the walk's start)
  const DualOptimizeSettings& s_;
  BondAdjacency slots_;  // neighbour slots of each atom: slot k of atom c names atom slots_.atom[k]
  ContactTerm contacts_;
  std::vector<std::uint32_t> first_angle_;                 // angles by centre
  std::vector<std::array<std::uint32_t, 2>> angle_slots_;  // an angle's two arms as slots of its centre
  std::vector<std::uint8_t> angle_contact_;                // 1: the angle adds the contact term of its end pair
  const std::vector<double>& target_cosines_;  // the caller's, by angle
  std::vector<std::uint32_t> first_gather_, gather_;       // the slots that name each atom
  std::vector<double> slot_gradient_;                      // 3 per slot: the gradient on the slot's atom
  std::vector<std::array<double, 3>> partial_sums_;
};

}  // namespace carbonmesh::detail
