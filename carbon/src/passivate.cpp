#include "carbonmesh/carbon/passivate.hpp"

#include <spdlog/spdlog.h>

#include <nlohmann/json.hpp>
#include <stdexcept>

namespace carbonmesh {

PassivationResult passivate(CarbonStructure& s, const PassivationSettings& settings) {
  if (!(settings.ch_bond > 0)) throw std::invalid_argument("passivate: the C-H bond length must be positive");
  PassivationResult r;
  const std::size_t n = s.atoms();
  std::vector<std::vector<int>> neighbours(n);
  for (const auto& b : s.bonds) {
    neighbours[static_cast<std::size_t>(b[0])].push_back(b[1]);
    neighbours[static_cast<std::size_t>(b[1])].push_back(b[0]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (s.elements[i] != Element::C) continue;
    const auto& nb = neighbours[i];
    if (nb.size() == 1) ++r.one_coordinated;
    if (nb.size() != 2) continue;
    const Vec3 x = s.positions[i];
    const Vec3 u = (x - s.positions[static_cast<std::size_t>(nb[0])]).normalized();
    const Vec3 v = (x - s.positions[static_cast<std::size_t>(nb[1])]).normalized();
    const Vec3 d = u + v;
    if (d.norm() < 1e-6) {
      ++r.collinear;
      continue;
    }
    s.positions.push_back(x + d.normalized() * settings.ch_bond);
    s.elements.push_back(Element::H);
    s.bonds.push_back({static_cast<int>(i), static_cast<int>(s.positions.size() - 1)});
    ++r.hydrogens;
  }
  spdlog::info("passivation: {} H added", r.hydrogens);
  if (r.collinear) spdlog::warn("passivation: {} two-coordinated carbons with collinear bonds left bare", r.collinear);
  if (r.one_coordinated) spdlog::warn("passivation: {} one-coordinated carbons left bare", r.one_coordinated);
  return r;
}

nlohmann::json to_json(const PassivationResult& r) {
  return {{"hydrogens", r.hydrogens}, {"collinear_left_bare", r.collinear}, {"one_coordinated", r.one_coordinated}};
}

}  // namespace carbonmesh
