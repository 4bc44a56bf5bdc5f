#include "carbonmesh/carbon/structure.hpp"

#include <algorithm>
#include <limits>

namespace carbonmesh {

const char* element_symbol(Element e) { return e == Element::H ? "H" : "C"; }

double element_mass(Element e) { return e == Element::H ? 1.008 : 12.011; }

std::size_t CarbonStructure::count(Element e) const {
  return static_cast<std::size_t>(std::count(elements.begin(), elements.end(), e));
}

std::vector<int> CarbonStructure::coordination() const {
  std::vector<int> out(atoms(), 0);
  for (const auto& b : bonds) {
    ++out[static_cast<std::size_t>(b[0])];
    ++out[static_cast<std::size_t>(b[1])];
  }
  return out;
}

std::vector<AtomTriple> CarbonStructure::angles() const { return bond_angles(atoms(), bonds); }

CarbonStructure carbon_structure(const Dual& dual) {
  CarbonStructure s;
  s.positions = dual.positions();
  s.elements.assign(s.positions.size(), Element::C);
  s.bonds = dual.bonds;
  for (std::size_t r = 0; r < dual.rings.size(); ++r)
    if (dual.ring_closed[r]) s.rings.push_back(dual.rings[r]);
  return s;
}

Box vacuum_box(const std::vector<Vec3>& positions, double vacuum) {
  Box box;
  if (positions.empty()) {
    box.lo = Vec3(-vacuum, -vacuum, -vacuum);
    box.hi = Vec3(vacuum, vacuum, vacuum);
    return box;
  }
  const double inf = std::numeric_limits<double>::infinity();
  box.lo = Vec3(inf, inf, inf);
  box.hi = Vec3(-inf, -inf, -inf);
  for (const auto& p : positions)
    for (int k = 0; k < 3; ++k) {
      box.lo[k] = std::min(box.lo[k], p[k]);
      box.hi[k] = std::max(box.hi[k], p[k]);
    }
  for (int k = 0; k < 3; ++k) {
    box.lo[k] -= vacuum;
    box.hi[k] += vacuum;
  }
  return box;
}

}  // namespace carbonmesh
