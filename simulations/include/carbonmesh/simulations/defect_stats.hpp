#pragma once
// Defect statistics on a ring structure: ring sizes, distances between like defects, 5-7 pairs, and the
// topological floor (sum over rings of 6 - size = 6 chi on a closed surface).
#include <cstddef>
#include <map>
#include <optional>
#include <vector>

#include "carbonmesh/simulations/ring_structure.hpp"

namespace carbonmesh {

struct RingSizeCounts {
  std::map<int, std::size_t> closed;  // size -> rings (complete rings)
  std::map<int, std::size_t> open;    // size -> border rings (mesh input), reported apart
};
RingSizeCounts ring_size_counts(const RingStructure& rs);

// For each closed ring of `size` (in ring order), the number of ring-to-ring steps to the nearest other closed
// ring of the same size (rings adjacent when they share a bond); nullopt when there is no other one reachable.
struct NearestDistances {
  int size = 0;
  std::vector<int> rings;                   // ring indices of that size
  std::vector<std::optional<int>> distance;  // parallel to rings
  std::map<int, std::size_t> histogram;     // distance -> rings
  std::size_t unreachable = 0;
};
// Exact, O(rings + adjacencies): one multi-source BFS labels every ring with its nearest defect of `size`; a
// defect's nearest other one is the best d(u) + 1 + d(v) over adjacencies (u, v) of differently labelled rings.
NearestDistances nearest_same_size(const RingStructure& rs, int size);

// Pentagon-heptagon pairing: adjacent (5, 7) ring pairs, and a maximal matching of them (pentagons in index
// order take their lowest-index free heptagon neighbour): the number of 5-7 dislocation pairs.
struct PairStats {
  std::size_t adjacent_pairs = 0;
  std::size_t matched_pairs = 0;
  std::size_t pentagons = 0, heptagons = 0;
  std::vector<std::pair<int, int>> matching;  // (pentagon ring, heptagon ring)
};
PairStats pentagon_heptagon_pairs(const RingStructure& rs);

struct TopologicalFloor {
  std::optional<long> euler;  // chi
  bool closed = false;
  long sum_six_minus_size = 0;  // over closed rings
  std::optional<long> six_chi;  // 6 chi (equals the sum on a closed sp2 surface)
  std::optional<long> floor;    // |6 chi|: fewest non-hexagons the topology forces (all pentagons or heptagons)
  std::size_t non_hexagons = 0;  // observed closed rings of size != 6
};
TopologicalFloor topological_floor(const RingStructure& rs);

}  // namespace carbonmesh
