#pragma once
// The part of a triangular lattice inside a region of a plane: the lattice triangles whose centroid (the atom of the
// dual) lies in the region, made manifold. Shared by the flat sheet (lattice_sheet.cpp) and the lattice rolled into a
// tube (lattice_tube.cpp), where lattice points one chiral vector apart are one point. Internal to remesh.
#include <array>
#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh::lattice {

struct Point2 {
  double x = 0, y = 0;
};

using Triangle2 = std::array<Point2, 3>;

// The lattice: point (i, j) at origin + i e1 + j e2, e2 turned 60 degrees counter-clockwise from e1 and as long.
struct Lattice {
  Point2 origin, e1, e2;
  Point2 at(double i, double j) const { return {origin.x + i * e1.x + j * e2.x, origin.y + i * e1.y + j * e2.y}; }
  std::pair<double, double> coordinates(Point2 p) const;  // lattice coordinates (i, j) of p
};

// Lattice points (i, j) and (i + k n, j + k m) are one point for every integer k: the lattice rolled into a tube of
// chiral vector n e1 + m e2. n = m = 0: the plane.
struct Period {
  long n = 0, m = 0;
};

// The one of the points (i + k n, j + k m) whose projection onto the chiral vector lies in [0, |n e1 + m e2|) (exact,
// in integers); (i, j) itself without a period.
std::pair<long, long> reduce(long i, long j, Period period);

// Up triangle (i, j): corners (i, j), (i + 1, j), (i, j + 1); down triangle (i, j): (i + 1, j), (i + 1, j + 1),
// (i, j + 1); both counter-clockwise.
struct LatticeTriangle {
  long i = 0, j = 0;
  int down = 0;
};
std::array<std::pair<long, long>, 3> corners(const LatticeTriangle& t);

struct InsideTriangles {
  std::vector<LatticeTriangle> triangles;  // each once, its (i, j) reduced; sorted by (j, i, down)
  std::size_t dropped = 0;  // inside, but left out where they touched the rest at one point only
};

// The lattice triangles whose centroid lies in one of the `region` triangles (or on its border). Where the kept
// triangles around a point form more than one fan, the largest fan stays (ties: the first counter-clockwise from
// up triangle (i, j)) and the others are dropped, until no point has two: the triangles form a manifold mesh.
InsideTriangles triangles_inside(const std::vector<Triangle2>& region, const Lattice& lattice, Period period);

// The mesh of `inside`: its vertices the triangles' corners (reduced), in (j, i) order, at place(i, j); its faces in
// the order of `inside`, each with its corners reversed if `reverse`. Throws std::logic_error if they do not form a
// manifold mesh (a period shorter than three lattice edges can make a triangle meet itself).
TriMesh lattice_mesh(const InsideTriangles& inside, Period period, const std::function<Vec3(long, long)>& place,
                     bool reverse);

}  // namespace carbonmesh::lattice
