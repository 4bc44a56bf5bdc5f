#pragma once
// Stability of a carbon structure over a simulation: the final frame against the structure as built. Carbon
// atoms only (hydrogen is left out of the coordination, bond and ring figures; C-H bonds are not C-C bonds).
//
// Verdict rule (docs/simulate.md): "stable" when at least 99% of the carbon atoms that had three carbon
// neighbours still have exactly three, and no more than 1% of the rings changed, where the rings changed are
// max(rings lost, rings formed) over the rings of the built structure; a ring is its cycle of atoms (SP rings,
// Franzblau) and is lost when that cycle is not a ring of the final frame.
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "carbonmesh/remesh/mesh.hpp"
#include "carbonmesh/simulations/kabsch.hpp"
#include "carbonmesh/simulations/sp_rings.hpp"

namespace carbonmesh {

struct StabilitySettings {
  double cutoff = 1.85;                   // C-C bond cutoff (Angstrom)
  SpRingSettings rings;                   // SP ring search
  double min_three_kept = 0.99;           // fraction of three-bonded carbons that must stay three-bonded
  double max_rings_changed = 0.01;        // fraction of rings that may change
};

struct StabilityVerdict {
  bool stable = false;
  std::string rule;    // the rule with its thresholds
  std::string reason;  // the figures against the thresholds
};

struct FrameComparison {
  std::size_t carbon_atoms = 0;
  std::map<int, std::size_t> coordination_before, coordination_after;  // C neighbours -> carbon atoms
  std::size_t three_before = 0, three_kept = 0;                         // three-bonded before / still after
  double three_kept_fraction = 1;
  std::size_t bonds_before = 0, bonds_after = 0, bonds_broken = 0, bonds_formed = 0;
  std::map<int, std::size_t> rings_before, rings_after;  // ring size -> rings
  std::size_t ring_count_before = 0, ring_count_after = 0, rings_lost = 0, rings_formed = 0;
  double rings_changed_fraction = 0;  // max(lost, formed) / rings before
  double mean_bond_before = 0, mean_bond_after = 0;
  Alignment alignment;  // final frame aligned onto the built structure (carbon atoms)
  StabilityVerdict verdict;
};

// The rule as printed with the verdict.
std::string stability_rule(const StabilitySettings& settings);

// Applies the rule to the two fractions.
StabilityVerdict stability_verdict(double three_kept_fraction, double rings_changed_fraction,
                                   const StabilitySettings& settings);

// `before` and `after` hold the same atoms in the same order; `carbon[i]` is false for hydrogen.
// Throws std::invalid_argument for mismatched sizes.
FrameComparison compare_frames(const std::vector<Vec3>& before, const std::vector<Vec3>& after,
                               const std::vector<bool>& carbon, const StabilitySettings& settings = {});

nlohmann::json to_json(const FrameComparison& c);

}  // namespace carbonmesh
