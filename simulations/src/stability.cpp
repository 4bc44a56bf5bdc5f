#include "carbonmesh/simulations/stability.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "carbonmesh/simulations/atom_graph.hpp"

namespace carbonmesh {
namespace {

nlohmann::json counts_json(const std::map<int, std::size_t>& m) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [k, v] : m) j[std::to_string(k)] = v;
  return j;
}

double mean_bond(const std::vector<Vec3>& p, const std::vector<Bond>& bonds) {
  if (bonds.empty()) return 0;
  double sum = 0;
  for (const auto& b : bonds) sum += (p[b[0]] - p[b[1]]).norm();
  return sum / static_cast<double>(bonds.size());
}

// Elements of `a` not in `b` (both sorted).
template <class T>
std::size_t missing(const std::vector<T>& a, const std::vector<T>& b) {
  std::vector<T> d;
  std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(d));
  return d.size();
}

}  // namespace

std::string stability_rule(const StabilitySettings& s) {
  return fmt::format(
      "stable when >= {:g}% of the three-bonded carbons keep three C neighbours (cutoff {:g} A) and <= {:g}% of "
      "the rings change (max(lost, formed) / rings before; SP rings)",
      100 * s.min_three_kept, s.cutoff, 100 * s.max_rings_changed);
}

StabilityVerdict stability_verdict(double three_kept, double rings_changed, const StabilitySettings& s) {
  StabilityVerdict v;
  v.stable = three_kept >= s.min_three_kept && rings_changed <= s.max_rings_changed;
  v.rule = stability_rule(s);
  v.reason = fmt::format("three-bonded kept {:.2f}% ({} {:g}%), rings changed {:.2f}% ({} {:g}%)", 100 * three_kept,
                         three_kept >= s.min_three_kept ? ">=" : "<", 100 * s.min_three_kept, 100 * rings_changed,
                         rings_changed <= s.max_rings_changed ? "<=" : ">", 100 * s.max_rings_changed);
  return v;
}

FrameComparison compare_frames(const std::vector<Vec3>& before, const std::vector<Vec3>& after,
                               const std::vector<bool>& carbon, const StabilitySettings& s) {
  if (before.size() != after.size() || before.size() != carbon.size())
    throw std::invalid_argument("compare_frames: frames and element mask differ in size");
  std::vector<Vec3> cb, ca;
  for (std::size_t i = 0; i < before.size(); ++i)
    if (carbon[i]) cb.push_back(before[i]), ca.push_back(after[i]);

  FrameComparison c;
  c.carbon_atoms = cb.size();
  if (cb.empty()) {
    c.verdict = stability_verdict(0, 1, s);
    return c;
  }
  AtomGraph gb = make_atom_graph(cb.size(), bonds_by_cutoff(cb, s.cutoff), cb);
  AtomGraph ga = make_atom_graph(ca.size(), bonds_by_cutoff(ca, s.cutoff), ca);
  for (std::size_t i = 0; i < cb.size(); ++i) {
    const int db = gb.degree(static_cast<int>(i)), da = ga.degree(static_cast<int>(i));
    ++c.coordination_before[db];
    ++c.coordination_after[da];
    if (db == 3) {
      ++c.three_before;
      if (da == 3) ++c.three_kept;
    }
  }
  c.three_kept_fraction = c.three_before ? static_cast<double>(c.three_kept) / c.three_before : 1.0;
  c.bonds_before = gb.bonds.size();
  c.bonds_after = ga.bonds.size();
  c.bonds_broken = missing(gb.bonds, ga.bonds);  // bonds are sorted and unique
  c.bonds_formed = missing(ga.bonds, gb.bonds);
  c.mean_bond_before = mean_bond(cb, gb.bonds);
  c.mean_bond_after = mean_bond(ca, ga.bonds);

  // Rings come canonical (smallest atom first, second < last): compare them as sorted lists.
  std::vector<std::vector<int>> rb = find_sp_rings(gb, s.rings).rings, ra = find_sp_rings(ga, s.rings).rings;
  for (const auto& r : rb) ++c.rings_before[static_cast<int>(r.size())];
  for (const auto& r : ra) ++c.rings_after[static_cast<int>(r.size())];
  std::sort(rb.begin(), rb.end());
  std::sort(ra.begin(), ra.end());
  c.ring_count_before = rb.size();
  c.ring_count_after = ra.size();
  c.rings_lost = missing(rb, ra);
  c.rings_formed = missing(ra, rb);
  const std::size_t changed = std::max(c.rings_lost, c.rings_formed);
  c.rings_changed_fraction = rb.empty() ? (changed ? 1.0 : 0.0) : static_cast<double>(changed) / rb.size();

  c.alignment = kabsch_align(cb, ca);
  c.verdict = stability_verdict(c.three_kept_fraction, c.rings_changed_fraction, s);
  return c;
}

nlohmann::json to_json(const FrameComparison& c) {
  return {{"carbon_atoms", c.carbon_atoms},
          {"coordination_before", counts_json(c.coordination_before)},
          {"coordination_after", counts_json(c.coordination_after)},
          {"three_bonded_before", c.three_before},
          {"three_bonded_kept", c.three_kept},
          {"percent_three_bonded_kept", 100 * c.three_kept_fraction},
          {"bonds_before", c.bonds_before},
          {"bonds_after", c.bonds_after},
          {"bonds_broken", c.bonds_broken},
          {"bonds_formed", c.bonds_formed},
          {"mean_bond_before", c.mean_bond_before},
          {"mean_bond_after", c.mean_bond_after},
          {"rings_before", counts_json(c.rings_before)},
          {"rings_after", counts_json(c.rings_after)},
          {"ring_count_before", c.ring_count_before},
          {"ring_count_after", c.ring_count_after},
          {"rings_lost", c.rings_lost},
          {"rings_formed", c.rings_formed},
          {"percent_rings_changed", 100 * c.rings_changed_fraction},
          {"rmsd", c.alignment.rmsd},
          {"max_displacement", c.alignment.max_displacement},
          {"max_displacement_atom", c.alignment.max_atom},
          {"stable", c.verdict.stable},
          {"verdict", c.verdict.stable ? "stable" : "unstable"},
          {"rule", c.verdict.rule},
          {"reason", c.verdict.reason}};
}

}  // namespace carbonmesh
