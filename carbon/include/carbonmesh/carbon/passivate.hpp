#pragma once
// Hydrogen passivation of border carbons.
#include <cstddef>

#include <nlohmann/json_fwd.hpp>

#include "carbonmesh/carbon/structure.hpp"

namespace carbonmesh {

struct PassivationSettings {
  double ch_bond = 1.09;  // C-H bond length (Angstrom)
};

struct PassivationResult {
  std::size_t hydrogens = 0;        // H atoms added (one per two-coordinated carbon)
  std::size_t collinear = 0;        // two-coordinated carbons left bare: their two bonds are collinear
  std::size_t one_coordinated = 0;  // carbons with a single bond (left bare, reported)
};

// Adds one H to every carbon with exactly two bonds: in the plane of the two bonds, along the bisector pointing
// away from both neighbours, ch_bond from the carbon, bonded to it. New atoms are appended in carbon order.
PassivationResult passivate(CarbonStructure& structure, const PassivationSettings& settings = {});

nlohmann::json to_json(const PassivationResult& r);

}  // namespace carbonmesh
