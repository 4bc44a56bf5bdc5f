#include "carbonmesh/simulations/sp_rings.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace carbonmesh {
namespace {

// Per-thread scratch: BFS distances with a stamp instead of clearing.
struct Scratch {
  std::vector<std::uint32_t> stamp;
  std::vector<int> dist;
  std::vector<std::uint32_t> vstamp;  // for verification BFS
  std::vector<int> vdist;
  std::vector<int> pos_on_ring;       // index of an atom on the ring being verified, valid with rstamp
  std::vector<std::uint32_t> rstamp;
  std::uint32_t current = 0, vcurrent = 0, rcurrent = 0;
  std::vector<int> queue, vqueue;  // root BFS, verification BFS
  std::vector<int> preds_offset;  // per visited vertex (by visit order): start in preds
  std::vector<int> preds;
  std::vector<int> order_of;      // vertex -> visit order
  explicit Scratch(std::size_t n)
      : stamp(n, 0), dist(n, 0), vstamp(n, 0), vdist(n, 0), pos_on_ring(n, 0), rstamp(n, 0), order_of(n, 0) {}
};

// Is the cycle an SP ring? For every atom a on it, a BFS bounded by floor(n/2)-1 must not reach another ring
// atom b before the arc distance between a and b.
bool is_sp_ring(const AtomGraph& g, const std::vector<int>& ring, Scratch& s) {
  const int n = static_cast<int>(ring.size());
  ++s.rcurrent;
  for (int k = 0; k < n; ++k) {
    if (s.rstamp[ring[k]] == s.rcurrent) return false;  // repeated atom
    s.rstamp[ring[k]] = s.rcurrent;
    s.pos_on_ring[ring[k]] = k;
  }
  const int limit = n / 2 - 1;  // a shortcut has length <= floor(n/2) - 1
  if (limit < 1) return true;
  for (int k = 0; k < n; ++k) {
    ++s.vcurrent;
    s.vqueue.clear();
    s.vqueue.push_back(ring[k]);
    s.vstamp[ring[k]] = s.vcurrent;
    s.vdist[ring[k]] = 0;
    for (std::size_t q = 0; q < s.vqueue.size(); ++q) {
      const int u = s.vqueue[q];
      const int du = s.vdist[u];
      if (du >= limit) continue;
      for (const int* it = g.begin(u); it != g.end(u); ++it) {
        const int v = *it;
        if (s.vstamp[v] == s.vcurrent) continue;
        s.vstamp[v] = s.vcurrent;
        s.vdist[v] = du + 1;
        if (s.rstamp[v] == s.rcurrent) {
          const int d = std::abs(s.pos_on_ring[v] - k);
          const int arc = std::min(d, n - d);
          if (du + 1 < arc) return false;
        }
        s.vqueue.push_back(v);
      }
    }
  }
  return true;
}

// All shortest paths root -> v (as vertex lists from root), at most `cap`; returns false if truncated.
bool paths_to(int v, const Scratch& s, std::size_t cap, std::vector<std::vector<int>>& out) {
  out.clear();
  std::vector<int> stack_path{v};
  bool complete = true;
  // Iterative DFS over predecessors.
  struct Frame {
    int vertex, next;
  };
  std::vector<Frame> frames{{v, 0}};
  while (!frames.empty()) {
    Frame& f = frames.back();
    const int ord = s.order_of[f.vertex];
    const int begin = s.preds_offset[ord], end = s.preds_offset[ord + 1];
    if (begin == end) {  // the root
      out.emplace_back(stack_path.rbegin(), stack_path.rend());
      if (out.size() >= cap) {
        complete = false;
        break;
      }
      frames.pop_back();
      stack_path.pop_back();
      continue;
    }
    if (f.next >= end - begin) {
      frames.pop_back();
      stack_path.pop_back();
      continue;
    }
    const int p = s.preds[begin + f.next++];
    frames.push_back({p, 0});
    stack_path.push_back(p);
  }
  return complete;
}

void canonical(std::vector<int>& ring) {
  auto m = std::min_element(ring.begin(), ring.end());
  std::rotate(ring.begin(), m, ring.end());
  if (ring.size() > 2 && ring.back() < ring[1]) std::reverse(ring.begin() + 1, ring.end());
}

// SP rings whose smallest atom is `root`. The BFS runs in the subgraph of atoms >= root: a ring through root
// with only larger atoms has its two half-paths inside that subgraph and they are shortest there too.
void rings_at(const AtomGraph& g, int root, const SpRingSettings& settings, Scratch& s,
              std::vector<std::vector<int>>& out, std::size_t& candidates, std::size_t& truncated,
              std::size_t& truncated_atoms) {
  const int max_size = settings.max_size;
  const std::size_t cap = settings.max_paths_per_end;
  std::size_t tested = 0;
  bool over = false;
  const int depth = max_size / 2;
  ++s.current;
  s.queue.clear();
  s.preds.clear();
  s.preds_offset.clear();
  s.queue.push_back(root);
  s.stamp[root] = s.current;
  s.dist[root] = 0;
  // Predecessors are collected per visit order; BFS layer by layer so that a vertex's preds are final before
  // the next layer starts.
  std::vector<std::vector<int>> found;
  std::size_t layer_begin = 0;
  s.preds_offset.push_back(0);
  s.order_of[root] = 0;
  // preds for root: none
  s.preds_offset.push_back(0);
  for (int d = 0; d < depth; ++d) {
    const std::size_t layer_end = s.queue.size();
    if (layer_begin == layer_end) break;
    // Discover the next layer.
    for (std::size_t q = layer_begin; q < layer_end; ++q) {
      const int u = s.queue[q];
      for (const int* it = g.begin(u); it != g.end(u); ++it) {
        const int v = *it;
        if (v <= root) continue;
        if (s.stamp[v] != s.current) {
          s.stamp[v] = s.current;
          s.dist[v] = d + 1;
          s.order_of[v] = static_cast<int>(s.queue.size());
          s.queue.push_back(v);
        }
      }
    }
    // Predecessors of the new layer, in visit order (the ones of layer u come from layer d).
    for (std::size_t q = layer_end; q < s.queue.size(); ++q) {
      const int v = s.queue[q];
      for (const int* it = g.begin(v); it != g.end(v); ++it) {
        const int u = *it;
        if (u >= root && s.stamp[u] == s.current && s.dist[u] == d && (u != root || d == 0)) s.preds.push_back(u);
      }
      s.preds_offset.push_back(static_cast<int>(s.preds.size()));
    }
    layer_begin = layer_end;
  }

  std::vector<std::vector<int>> pa, pb;
  auto try_ring = [&](std::vector<int> ring) {
    if (++tested > settings.max_candidates_per_atom) {
      over = true;
      return;
    }
    ++candidates;
    if (is_sp_ring(g, ring, s)) {
      canonical(ring);
      found.push_back(std::move(ring));
    }
  };
  for (std::size_t q = 1; q < s.queue.size() && !over; ++q) {
    const int v = s.queue[q];
    const int dv = s.dist[v];
    const int ord = static_cast<int>(q);
    const int pbeg = s.preds_offset[ord], pend = s.preds_offset[ord + 1];
    // Even rings 2*dv: two distinct predecessors whose paths from root are interior-disjoint.
    if (2 * dv <= max_size && pend - pbeg >= 2) {
      for (int a = pbeg; a < pend; ++a)
        for (int b = a + 1; b < pend; ++b) {
          if (!paths_to(s.preds[a], s, cap, pa)) ++truncated;
          if (!paths_to(s.preds[b], s, cap, pb)) ++truncated;
          for (const auto& x : pa)
            for (const auto& y : pb) {
              bool disjoint = true;
              for (std::size_t k = 1; k < x.size() && disjoint; ++k) disjoint = x[k] != y[k];
              if (!disjoint) continue;
              std::vector<int> ring(x.begin(), x.end());
              ring.push_back(v);
              for (std::size_t k = y.size(); k-- > 1;) ring.push_back(y[k]);
              try_ring(std::move(ring));
            }
        }
    }
    // Odd rings 2*dv+1: an edge (v, w) with w at the same depth, w > v (each edge once).
    if (2 * dv + 1 <= max_size) {
      for (const int* it = g.begin(v); it != g.end(v); ++it) {
        const int w = *it;
        if (w <= v || w <= root || s.stamp[w] != s.current || s.dist[w] != dv) continue;
        if (!paths_to(v, s, cap, pa)) ++truncated;
        if (!paths_to(w, s, cap, pb)) ++truncated;
        for (const auto& x : pa)
          for (const auto& y : pb) {
            bool disjoint = true;
            for (std::size_t k = 1; k < x.size() && disjoint; ++k) disjoint = x[k] != y[k];
            if (!disjoint) continue;
            std::vector<int> ring(x.begin(), x.end());
            for (std::size_t k = y.size(); k-- > 1;) ring.push_back(y[k]);
            try_ring(std::move(ring));
          }
      }
    }
  }
  if (over) ++truncated_atoms;
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  for (auto& r : found) out.push_back(std::move(r));
}

}  // namespace

SpRingResult find_sp_rings(const AtomGraph& graph, const SpRingSettings& settings) {
  if (settings.max_size < 3 || settings.max_size > 32)
    throw std::invalid_argument("max ring size " + std::to_string(settings.max_size) + " out of range 3..32");
  SpRingResult result;
  const long n = static_cast<long>(graph.atoms());
  constexpr long kBlock = 2048;
  const long blocks = (n + kBlock - 1) / kBlock;
  std::vector<std::vector<std::vector<int>>> per_block(blocks);
  std::vector<std::size_t> cand(blocks, 0), trunc(blocks, 0), trunc_atoms(blocks, 0);
#pragma omp parallel
  {
    Scratch scratch(graph.atoms());
#pragma omp for schedule(dynamic, 1)
    for (long b = 0; b < blocks; ++b) {
      const long end = std::min(n, (b + 1) * kBlock);
      for (long i = b * kBlock; i < end; ++i)
        rings_at(graph, static_cast<int>(i), settings, scratch, per_block[b], cand[b], trunc[b], trunc_atoms[b]);
    }
  }
  for (long b = 0; b < blocks; ++b) {
    for (auto& r : per_block[b]) result.rings.push_back(std::move(r));
    result.candidates += cand[b];
    result.truncated_ends += trunc[b];
    result.truncated_atoms += trunc_atoms[b];
  }
  return result;
}

}  // namespace carbonmesh
