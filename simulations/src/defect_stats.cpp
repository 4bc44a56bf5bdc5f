#include "carbonmesh/simulations/defect_stats.hpp"

#include <algorithm>
#include <climits>
#include <cstdlib>

namespace carbonmesh {

RingSizeCounts ring_size_counts(const RingStructure& rs) {
  RingSizeCounts c;
  for (std::size_t r = 0; r < rs.size(); ++r) ++(rs.open[r] ? c.open : c.closed)[rs.sizes[r]];
  return c;
}

NearestDistances nearest_same_size(const RingStructure& rs, int size) {
  NearestDistances out;
  out.size = size;
  const std::size_t n = rs.size();
  std::vector<int> label(n, -1), dist(n, INT_MAX), queue;
  for (std::size_t r = 0; r < n; ++r)
    if (!rs.open[r] && rs.sizes[r] == size) {
      label[r] = static_cast<int>(out.rings.size());
      dist[r] = 0;
      out.rings.push_back(static_cast<int>(r));
      queue.push_back(static_cast<int>(r));
    }
  for (std::size_t q = 0; q < queue.size(); ++q) {
    const int u = queue[q];
    for (int v : rs.neighbors[u])
      if (label[v] < 0) {
        label[v] = label[u];
        dist[v] = dist[u] + 1;
        queue.push_back(v);
      }
  }
  std::vector<int> best(out.rings.size(), INT_MAX);
  for (std::size_t u = 0; u < n; ++u) {
    if (label[u] < 0) continue;
    for (int v : rs.neighbors[u]) {
      if (label[v] < 0 || label[v] == label[static_cast<int>(u)]) continue;
      const int d = dist[u] + 1 + dist[v];
      best[label[u]] = std::min(best[label[u]], d);
      best[label[v]] = std::min(best[label[v]], d);
    }
  }
  out.distance.resize(out.rings.size());
  for (std::size_t k = 0; k < out.rings.size(); ++k) {
    if (best[k] == INT_MAX) {
      ++out.unreachable;
    } else {
      out.distance[k] = best[k];
      ++out.histogram[best[k]];
    }
  }
  return out;
}

PairStats pentagon_heptagon_pairs(const RingStructure& rs) {
  PairStats p;
  std::vector<bool> used(rs.size(), false);
  auto is = [&](int r, int s) { return !rs.open[r] && rs.sizes[r] == s; };
  for (std::size_t r = 0; r < rs.size(); ++r) {
    const int ri = static_cast<int>(r);
    if (is(ri, 7)) ++p.heptagons;
    if (!is(ri, 5)) continue;
    ++p.pentagons;
    bool matched = false;
    for (int s : rs.neighbors[r]) {  // sorted: the lowest index first
      if (!is(s, 7)) continue;
      ++p.adjacent_pairs;
      if (!matched && !used[s]) {
        used[s] = true;
        matched = true;
        p.matching.emplace_back(ri, s);
      }
    }
  }
  p.matched_pairs = p.matching.size();
  return p;
}

TopologicalFloor topological_floor(const RingStructure& rs) {
  TopologicalFloor t;
  t.euler = rs.euler;
  t.closed = rs.closed_surface;
  for (std::size_t r = 0; r < rs.size(); ++r) {
    if (rs.open[r]) continue;
    t.sum_six_minus_size += 6 - rs.sizes[r];
    if (rs.sizes[r] != 6) ++t.non_hexagons;
  }
  if (t.euler && t.closed) {
    t.six_chi = 6 * *t.euler;
    t.floor = std::labs(*t.six_chi);
  }
  return t;
}

}  // namespace carbonmesh
