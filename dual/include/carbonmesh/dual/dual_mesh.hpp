#pragma once
// The dual of a triangle mesh as a carbon network: one atom per triangle (at its centroid), one bond per
// interior edge, one ring per vertex (ring size = valence). Border vertices give open rings and the atoms of
// border triangles have fewer than three bonds.
#include <array>
#include <cstddef>
#include <map>
#include <vector>

#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <nlohmann/json_fwd.hpp>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

struct DualTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::PrevHalfedge);
  FaceAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::Normal);
};

// Vertex i is atom i; every closed ring is a face, oriented like the primal surface.
using DualMesh = OpenMesh::PolyMesh_ArrayKernelT<DualTraits>;

using AtomPair = std::array<int, 2>;  // two atom indices, first < second

struct DualCounts {
  std::size_t atoms = 0, bonds = 0;
  std::size_t closed_rings = 0, open_rings = 0;
  std::map<int, std::size_t> ring_sizes;    // closed rings: size -> count
  std::map<int, std::size_t> coordination;  // bonds per atom -> atom count
  std::size_t border_atoms = 0;             // atoms with fewer than three bonds
  double percent_three_bonds = 0;           // atoms with exactly three bonds
};

struct Dual {
  DualMesh mesh;
  std::vector<AtomPair> bonds;       // one per interior primal edge, in primal edge order
  std::vector<int> bond_edge;        // primal edge index of each bond
  std::vector<int> atom_face;        // primal face index of each atom
  std::vector<int> face_atom;        // primal face index -> atom (-1 for deleted faces)
  std::vector<std::vector<int>> rings;  // atoms of each ring, counter-clockwise seen from outside
  std::vector<bool> ring_closed;     // false for the open ring of a border vertex
  std::vector<int> ring_vertex;      // primal vertex index of each ring
  std::vector<int> vertex_ring;      // primal vertex index -> ring (-1 for isolated or deleted vertices)
  std::vector<int> ring_face;        // DualMesh face of each closed ring (-1 for open rings)
  DualCounts counts;

  std::size_t atoms() const { return atom_face.size(); }
  // Current atom positions (the DualMesh points).
  std::vector<Vec3> positions() const;
  void set_positions(const std::vector<Vec3>& positions);
};

// Builds the dual of `primal`. Deleted elements (status) are skipped. Throws std::runtime_error if the ring
// faces cannot form a manifold polygon mesh (a non-manifold primal mesh).
Dual build_dual(const TriMesh& primal);

DualCounts count_dual(const Dual& dual);

nlohmann::json to_json(const DualCounts& counts);

}  // namespace carbonmesh
