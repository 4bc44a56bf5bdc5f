#pragma once
// The contact term of the dual optimisation (internal to dual): w_c sum max(0, r_c - |x_i - x_j|)^2 over pairs of
// atoms that are not bonded. With r_c = sqrt(2) b it keeps the atoms two bonds apart at a bond angle of at
// least 90 degrees and every other pair at least r_c apart: where the surface has features thinner than the
// bond scale, the bond term alone folds the net over itself (atoms a fraction of an Angstrom apart). Pairs come
// from a cell grid with a skin, rebuilt only when the atoms may have moved into range, so the term is the same
// function of the positions whichever list it was evaluated with.
#include <array>
#include <vector>

namespace carbonmesh::detail {

class ContactTerm {
 public:
  // `bonds`: the bonded pairs (excluded), atoms 0..atoms-1. cutoff r_c and weight w_c as above.
  ContactTerm(std::size_t atoms, const std::vector<std::array<int, 2>>& bonds, double cutoff, double weight);

  // Adds the term for atoms at x_i = c + s (y_i - c) (y: 3 coordinates per atom) to `gradient` (dE/dy) and
  // `gradient_scale` (dE/ds); returns its energy. Rebuilds the pair list when needed.
  double add(const double* y, double s, double* gradient, double& gradient_scale);

  std::size_t rebuilds() const { return rebuilds_; }

 private:
  void rebuild(const double* y, double s);
  bool bonded(int i, int j) const;

  std::size_t atoms_;
  double cutoff_, weight_, skin_;
  std::vector<int> first_, neighbours_;  // CSR of the bonded neighbours
  std::vector<std::array<int, 2>> pairs_;
  std::vector<double> built_at_;  // y at the last rebuild
  double built_scale_ = 0;
  std::size_t rebuilds_ = 0;
};

}  // namespace carbonmesh::detail
