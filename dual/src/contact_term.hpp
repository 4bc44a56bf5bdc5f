#pragma once
// The contact term of the dual optimisation (internal to dual): w_c sum max(0, r_c - |x_i - x_j|)^2 over pairs of
// atoms that are not bonded. With r_c = sqrt(2) b it keeps the atoms two bonds apart at a bond angle of at
// least 90 degrees and every other pair at least r_c apart: where the surface has features thinner than the
// bond scale, the bond term alone folds the net over itself (atoms a fraction of an Angstrom apart).
//
// ContactTerm covers the pairs more than two bonds apart. Pairs come from a cell grid with a skin, rebuilt only
// when the atoms may have moved into range, so the term is the same function of the positions whichever list it
// was evaluated with. The pairs two bonds apart are the ends of the bond angles: the energy adds them in its
// pass over the angles (dual_energy.cpp), so the list holds only the rare close pairs of a folded or crowded net
// instead of every second neighbour, which sits at sqrt(3) b, inside the list's reach.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace carbonmesh::detail {

// The bonded neighbours of every atom: atom[first[i] .. first[i + 1]) ascending (CSR). Shared by the contact term
// (which pairs to leave out) and the energy's per-atom pass (dual_energy.cpp: its neighbour slots).
struct BondAdjacency {
  std::vector<std::uint32_t> first, atom;
  std::size_t atoms() const { return first.empty() ? 0 : first.size() - 1; }
  bool bonded(std::uint32_t i, std::uint32_t j) const;
};
BondAdjacency bond_adjacency(std::size_t atoms, const std::vector<std::array<int, 2>>& bonds);

// The contact term of one pair at (scaled) distance r: adds w_c (r_c - r)^2 to `energy` and returns dE/dr, 0 from
// r_c on.
inline double contact_derivative(double cutoff, double weight, double r, double& energy) {
  const double gap = cutoff - r;
  if (gap <= 0) return 0;
  energy += weight * gap * gap;
  return -2 * weight * gap;
}

class ContactTerm {
 public:
  // `bonds`: the bonded neighbours (pairs within two bonds are excluded; held by reference). cutoff r_c and
  // weight w_c as above.
  ContactTerm(const BondAdjacency& bonds, double cutoff, double weight);

  // Adds the term for atoms at x_i = c + s (y_i - c) (y: 3 coordinates per atom) to `gradient` (dE/dy) and
  // `gradient_scale` (dE/ds); returns its energy. Rebuilds the pair list when needed.
  double add(const double* y, double s, double* gradient, double& gradient_scale);

  std::size_t rebuilds() const { return rebuilds_; }

 private:
  void rebuild(const double* y, double s);
  bool within_two_bonds(int i, int j) const;

  std::size_t atoms_;
  double cutoff_, weight_, skin_;
  const BondAdjacency& bonds_;
  std::vector<std::array<int, 2>> pairs_;
  std::vector<double> built_at_;  // y at the last rebuild
  double built_scale_ = 0;
  std::size_t rebuilds_ = 0;
};

}  // namespace carbonmesh::detail
