#pragma once
// The triangular lattice folded onto a polyhedron whose faces are lattice triangles (the Goldberg-Coxeter
// construction on any such net): the surface's vertices are the lattice points of the faces, its triangles the
// lattice triangles whose centroid lies on a face. A corner where less than 360 degrees of lattice meet becomes a
// vertex of lower valence (60 degrees less: valence 5, a pentagon of the dual), every other vertex has valence 6.
#include <array>
#include <vector>

namespace carbonmesh::lattice_net {

using LatticePoint = std::array<long, 2>;  // (i, j): the point i e1 + j e2, e1 and e2 unit edges 60 degrees apart

long det(LatticePoint a, LatticePoint b);        // twice the area of the triangle 0, a, b in unit triangles
LatticePoint turned(LatticePoint p, int sixths);  // p turned counter-clockwise by sixths * 60 degrees
LatticePoint operator+(LatticePoint a, LatticePoint b);
LatticePoint operator-(LatticePoint a, LatticePoint b);
LatticePoint operator*(long s, LatticePoint a);
long squared_length(LatticePoint a);  // in unit edges: i^2 + ij + j^2

// A face of the polyhedron: its corners (indices of the polyhedron's corners), counter-clockwise seen from outside,
// and where they lie in the face's own lattice chart (counter-clockwise there too: det(at1 - at0, at2 - at0) > 0).
struct NetFace {
  std::array<int, 3> corners{};
  std::array<LatticePoint, 3> at{};
};

// Where a vertex of the folded lattice lies: on face `face` at these barycentric weights of its corners.
struct Place {
  int face = -1;
  std::array<double, 3> weights{};
};

struct Folded {
  // By vertex: the polyhedron's corners (by index), then the edges' inner points (edge by edge in the order the faces
  // name the edges, each from its smaller corner), then each face's inner points row by row (j, then i, ascending).
  std::vector<Place> places;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside
};

// The lattice folded onto the polyhedron with corners 0 .. corner_count - 1 and `faces`. Every edge must be shared by
// two faces, once in each direction, with lattice vectors of the same length. A lattice triangle whose centroid lies
// on an edge goes to the face of smaller index. Throws std::logic_error if the net does not fit together.
Folded fold_lattice(int corner_count, const std::vector<NetFace>& faces);

}  // namespace carbonmesh::lattice_net
