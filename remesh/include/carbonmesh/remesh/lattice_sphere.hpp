#pragma once
// A spherical surface replaced by the triangular lattice folded onto an icosahedron (`carbonmesh build --lattice`):
// the Goldberg-Coxeter sphere (h, k) (carbonmesh/remesh/shapes.hpp), whose dual is the icosahedral fullerene C_20T,
// T = h^2 + hk + k^2: 12 pentagons, the fewest a closed carbon cage can have, and hexagons otherwise. The remesher
// cannot give that: a sphere remeshed to 2000 atoms keeps 50 pentagons and 38 heptagons.
#include <limits>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

// The sphere through the vertices (least squares over the centre and the radius, on every vertex a face uses) and
// how far the farthest vertex is from it.
struct Sphere {
  Vec3 centre{0, 0, 0};
  double radius = 0;
  double distance = std::numeric_limits<double>::infinity();  // mesh units; infinity where no sphere fits
};

Sphere sphere_fit(const TriMesh& mesh);

// Goldberg-Coxeter indices of an icosahedral fullerene: (h, 0) and (h, h) of symmetry Ih, 0 < k < h chiral (I);
// (k, h) is the mirror image of (h, k).
struct GoldbergIndices {
  int h = 1, k = 0;
};

// The radius of the sphere whose area 20 T flat triangles of edge `edge` cover: edge sqrt(5 sqrt(3) T / (4 pi)).
double fullerene_radius(GoldbergIndices g, double edge);

// The indices h >= k >= 0 whose fullerene_radius is nearest to `radius` (ties: the smaller T, then the smaller k:
// (7, 0) before (5, 3), both T = 49), T at most kMaxTriangulationNumber.
GoldbergIndices nearest_goldberg_indices(double radius, double edge);

struct LatticeFullerene {
  TriMesh mesh;             // the Goldberg-Coxeter sphere on the input's centre
  GoldbergIndices indices;  // as asked
  double radius = 0;        // where its vertices lie: its mean edge is `edge` (the input's radius is sphere.radius)
};

// The Goldberg-Coxeter sphere `indices` of mean edge `edge` on the centre of `sphere`, its icosahedron's two-fold
// axes along x, y and z (corners at (0, +-1, +-phi) and their cyclic permutations), its faces facing the side the input's faces face (out of or into the sphere). Throws InputError if `edge`
// is not positive or the indices are not valid (check_goldberg_coxeter).
LatticeFullerene lattice_fullerene(const TriMesh& input, const Sphere& sphere, double edge, GoldbergIndices indices);

}  // namespace carbonmesh
