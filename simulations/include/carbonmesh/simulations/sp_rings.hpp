#pragma once
// Shortest-path rings (Franzblau 1991) of an atom graph: a cycle is an SP ring when, for every pair of its
// atoms, the shorter arc of the cycle is a shortest path of the graph. Unlike "smallest ring per bond" this
// finds a heptagon whose every bond is shared with hexagons.
#include <cstddef>
#include <vector>

#include "carbonmesh/simulations/atom_graph.hpp"

namespace carbonmesh {

struct SpRingSettings {
  int max_size = 10;                    // largest ring searched (3..32)
  std::size_t max_paths_per_end = 256;  // shortest paths enumerated per ring end; beyond, candidates are dropped
  std::size_t max_candidates_per_atom = 20000;  // guards against over-bonded input (a far too large cutoff)
};

struct SpRingResult {
  std::vector<std::vector<int>> rings;  // atoms in cyclic order; starts at the smallest index, second < last
  std::size_t candidates = 0;           // cycles tested
  std::size_t truncated_ends = 0;       // ring ends with more shortest paths than max_paths_per_end (should be 0)
  std::size_t truncated_atoms = 0;      // atoms whose candidates exceeded max_candidates_per_atom (should be 0)
};

// Deterministic: rings sorted by (smallest atom, then lexicographically). Parallel over atoms (OpenMP).
// Throws std::invalid_argument for max_size out of range.
SpRingResult find_sp_rings(const AtomGraph& graph, const SpRingSettings& settings = {});

}  // namespace carbonmesh
