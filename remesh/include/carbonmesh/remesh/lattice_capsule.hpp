#pragma once
// A capsule (a cylinder closed by two hemispheres) replaced by a capped nanotube (`carbonmesh build --lattice`): the
// triangulation of make_capped_tube, the lattice folded onto the icosahedron lengthened along a five-fold axis, whose
// dual is the tube (5h, 5k) closed by the two halves of the icosahedral fullerene C_20T, or for other indices onto a
// tube closed by apex caps: 12 pentagons, hexagons otherwise. The remesher cannot give that: a capsule
// remeshed keeps pentagon-heptagon pairs.
#include <array>
#include <limits>

#include "carbonmesh/remesh/mesh.hpp"
#include "carbonmesh/remesh/shapes.hpp"

namespace carbonmesh {

// The capsule through the vertices (least squares over its centre, axis, radius and straight length, on at most 4096
// of them, every k-th in index order) and how far the farthest vertex is from it.
struct Capsule {
  Vec3 centre{0, 0, 0};
  Vec3 axis{0, 0, 1};  // unit; its largest component positive
  double radius = 0;
  double length = 0;   // of the straight part
  double distance = std::numeric_limits<double>::infinity();  // mesh units; infinity where no capsule fits
};

Capsule capsule_fit(const TriMesh& mesh);
double capsule_area(const Capsule& capsule);

// The chiral indices (5h, 5k), h >= k >= 0, whose capped tube's radius is nearest to `radius` (ties: the smaller
// circumference, then the smaller k), T = h^2 + hk + k^2 at most kMaxTriangulationNumber.
std::array<int, 2> nearest_capped_chirality(double radius, double edge);

struct LatticeCappedTube {
  TriMesh mesh;          // the capped tube on the capsule's axis, centred on its centre
  std::array<int, 2> chirality{};
  int periods = 0;       // tube periods between the caps (icosahedral caps; 0 with apex caps)
  CapKind caps = CapKind::icosahedral;
  double radius = 0;     // the tube's radius (the capsule's is capsule.radius)
  double length = 0;     // the straight part the points lie on (the capsule's is capsule.length)
};

// The capped tube `chirality` of lattice edge `edge` whose straight part is nearest the capsule's, on its axis and
// centre, its faces facing the side the input's faces face (out of or into the capsule). Throws InputError for bad
// indices (check_capped_tube), a tube too thin for a cap (make_capped_tube) or an edge that is not positive.
LatticeCappedTube lattice_capped_tube(const TriMesh& input, const Capsule& capsule, double edge,
                                      std::array<int, 2> chirality);

}  // namespace carbonmesh
