#pragma once
// A carbon nanostructure: atom positions and elements, bonds and rings.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "carbonmesh/dual/dual_mesh.hpp"
#include "carbonmesh/dual/graph_stats.hpp"
#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

enum class Element { C, H };
const char* element_symbol(Element e);
double element_mass(Element e);  // g/mol: 12.011 for C, 1.008 for H

struct CarbonStructure {
  std::vector<Vec3> positions;
  std::vector<Element> elements;
  std::vector<AtomPair> bonds;          // first < second
  std::vector<std::vector<int>> rings;  // closed rings, atoms in order

  std::size_t atoms() const { return positions.size(); }
  std::size_t count(Element e) const;
  bool has_hydrogen() const { return count(Element::H) > 0; }
  // Number of bonds of every atom.
  std::vector<int> coordination() const;
  // Every bond angle j-i-k (bond_angles of graph_stats.hpp).
  std::vector<AtomTriple> angles() const;
};

// The all-carbon structure of a dual: atom i of the dual is atom i, its bonds, its closed rings.
CarbonStructure carbon_structure(const Dual& dual);

// An axis-aligned box around the atoms with `vacuum` of empty space on every side.
struct Box {
  Vec3 lo{0, 0, 0}, hi{0, 0, 0};
};
Box vacuum_box(const std::vector<Vec3>& positions, double vacuum);

}  // namespace carbonmesh
