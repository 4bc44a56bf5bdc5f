#pragma once
// An undirected atom graph (positions + bonds) in compressed adjacency form.
#include <array>
#include <cstddef>
#include <vector>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

using Bond = std::array<int, 2>;  // atom indices, first < second

struct AtomGraph {
  std::vector<Vec3> positions;     // may be empty for a purely combinatorial graph
  std::vector<Bond> bonds;         // sorted, unique, first < second
  std::vector<int> offsets;        // size atoms()+1; neighbours of i are adjacency[offsets[i] .. offsets[i+1])
  std::vector<int> adjacency;      // sorted within each atom

  std::size_t atoms() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  int degree(int i) const { return offsets[i + 1] - offsets[i]; }
  const int* begin(int i) const { return adjacency.data() + offsets[i]; }
  const int* end(int i) const { return adjacency.data() + offsets[i + 1]; }
};

// Builds the graph of `atoms` atoms from a bond list (any order, duplicates and self-bonds dropped).
// Throws std::invalid_argument for an index out of range.
AtomGraph make_atom_graph(std::size_t atoms, std::vector<Bond> bonds, std::vector<Vec3> positions = {});

// Bonds between atoms closer than `cutoff` (non-periodic), found with a cell list: O(n) for a bounded density.
std::vector<Bond> bonds_by_cutoff(const std::vector<Vec3>& positions, double cutoff);

}  // namespace carbonmesh
