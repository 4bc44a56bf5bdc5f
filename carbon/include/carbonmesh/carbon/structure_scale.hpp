#pragma once
// The size of the model: a triangle of edge a = sqrt(3) b has one atom at its centroid, and the centroids of
// two neighbouring equilateral triangles are b apart, so the primal mesh is remeshed to edges of about a and
// a surface of area A becomes about A / ((sqrt(3)/4) a^2) atoms (2.62 A^2 per atom for b = 1.42 A).
#include <nlohmann/json_fwd.hpp>

#include "carbonmesh/remesh/mesh.hpp"
#include "carbonmesh/remesh/metrics.hpp"  // surface_area

namespace carbonmesh {

// The primal edge length for bond length b: sqrt(3) b (2.46 A for 1.42 A).
double target_edge(double bond);
// The area of one atom's triangle: (sqrt(3)/4) a^2 with a = target_edge(bond).
double area_per_atom(double bond);

enum class ScaleMode {
  None,    // keep the input size (coordinates are Angstrom)
  Size,    // value = the longest side of the bounding box after scaling (Angstrom)
  Factor,  // value = the scale factor
  Atoms,   // value = about this many atoms: area after scaling = value * area_per_atom
};

struct ScaleSettings {
  ScaleMode mode = ScaleMode::None;
  double value = 0;
  double bond = 1.42;                          // target C-C bond length b (Angstrom)
  double low = 0.8, high = 1.2;                // edge interval as multiples of target_edge(bond)
};

struct StructureScale {
  double factor = 1;         // multiply the input coordinates by this
  double edge = 0;           // target primal edge a
  double emin = 0, emax = 0;  // remeshing interval
  double area = 0;           // surface area after scaling
  double longest_side = 0;   // longest bounding-box side after scaling
  double expected_atoms = 0;  // area / area_per_atom
};

// Throws InputError for a non-positive bond or value, an empty mesh, or low >= high.
StructureScale structure_scale(const TriMesh& mesh, const ScaleSettings& settings);

// Multiplies every point by `factor` (about the origin) and updates the normals.
void scale_mesh(TriMesh& mesh, double factor);

nlohmann::json to_json(const StructureScale& s);

}  // namespace carbonmesh
