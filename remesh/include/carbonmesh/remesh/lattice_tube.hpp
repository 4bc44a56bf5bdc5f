#pragma once
// A cylindrical surface cut from a triangular lattice (`carbonmesh build --lattice`): an open tube from the lattice
// rolled into a tube, whose dual is a carbon nanotube of chiral indices (n, m), and a part of a cylinder that does not
// go around its axis from the flat lattice rolled onto it. Hexagons only: the remesher cannot give that (an open tube
// of 20000 atoms remeshed has 374 pentagons and 374 heptagons), and a cylinder, being developable, needs none.
#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

// The cylinder through the vertices (least squares over the axis, its position and the radius, on at most 4096 of
// them, every k-th in index order) and how far the farthest vertex is from it.
struct Cylinder {
  Vec3 point{0, 0, 0};  // on the axis, level with the vertices' centroid
  Vec3 axis{0, 0, 1};   // unit; its largest component positive
  double radius = 0;
  double distance = std::numeric_limits<double>::infinity();  // mesh units; infinity where no cylinder fits
};

Cylinder cylinder_fit(const TriMesh& mesh);

// Chiral indices: the tube's circumference is the lattice vector n e1 + m e2 (e1, e2 lattice edges 60 degrees
// apart), |n e1 + m e2| = a sqrt(n^2 + nm + m^2) for lattice edge a. (n, 0) is a zigzag tube, (n, n) an armchair
// tube; (m, n) is the mirror image of (n, m).
struct Chirality {
  int n = 0, m = 0;
};

// n^2 + nm + m^2 must be at least this (a circumference of sqrt(7) lattice edges: (2, 1)); below it a lattice
// triangle would meet itself around the tube.
constexpr long kMinChiralNorm = 7;

// Throws InputError unless n, m >= 0 and n^2 + nm + m^2 >= kMinChiralNorm.
void check_chirality(Chirality c);

double chiral_circumference(Chirality c, double edge);
double chiral_angle_deg(Chirality c);  // from the zigzag direction: 0 for (n, 0), 30 for (n, n)

// The chirality n >= m >= 0 with n^2 + nm + m^2 >= kMinChiralNorm whose circumference is nearest to 2 pi `radius`
// (ties: the smaller m, nearer to zigzag).
Chirality nearest_chirality(double radius, double edge);

struct LatticeTube {
  TriMesh mesh;         // the lattice triangles inside the input's outline, rolled onto the tube's cylinder
  TriMesh surface;      // the tube's cylinder over the input's length, finely tessellated (the atoms' surface)
  Chirality chirality;  // as asked
  double radius = 0;    // |n e1 + m e2| / (2 pi): where the lattice points lie (the input's radius is cylinder.radius)
  std::size_t dropped = 0;  // triangles inside that were left out where they touched the rest at one vertex only
};

// The triangles of a triangular lattice of edge `edge`, rolled into the tube of `chirality` on the axis of
// `cylinder`, whose centroid lies in the region the input's faces cover once the cylinder is unrolled (its
// circumference scaled to the tube's). The lattice has a point at the input vertex lowest along the axis (the first
// such), with the chiral vector around the tube, so a rim square to the axis is a zigzag edge of the carbon net in a
// (n, 0) tube. Faces face the side the input's faces face (out of or into the tube). Throws InputError if `edge` is
// not positive or n^2 + nm + m^2 < kMinChiralNorm or n or m is negative.
LatticeTube lattice_tube(const TriMesh& input, const Cylinder& cylinder, double edge, Chirality chirality);

// The cylinder of `radius` on the axis of `cylinder`, from height z0 to z1 along the axis (from cylinder.point), its
// chords within 1e-4 `edge` of the circle, its faces facing out of the cylinder (into it if `inward`).
TriMesh cylinder_surface(const Cylinder& cylinder, double radius, double z0, double z1, double edge, bool inward);

// Each vertex's angle about the axis of `cylinder` (radians, by vertex index), unwrapped along the edges from the
// first vertex of each component; std::nullopt if the surface goes around the axis (a loop of its edges winds once
// around it: a tube, whose lattice must close on itself).
std::optional<std::vector<double>> angles_along_surface(const TriMesh& mesh, const Cylinder& cylinder);

struct CurvedSheet {
  TriMesh mesh;            // the lattice triangles inside the input's outline, on the input's cylinder
  TriMesh surface;         // that cylinder over the input's length, finely tessellated (the atoms' surface)
  double angle_deg = 0;    // the lattice direction in the unrolled plane (lattice_sheet's)
  std::size_t dropped = 0;  // triangles inside that were left out where they touched the rest at one vertex only
};

// A part of a cylinder that does not go around its axis (half a tube, a curved sheet; `angles` from
// angles_along_surface): unrolled at the cylinder's own radius, each vertex to (radius * angle, height), cut from a
// flat lattice of edge `edge` as a flat sheet is (lattice_sheet: one lattice line along the longest straight side of
// the unrolled outline, turned by `turn_deg`), and rolled back onto the cylinder. No chirality constrains it: the
// radius stays the input's. Faces face the side the input's faces face.
CurvedSheet curved_sheet(const TriMesh& input, const Cylinder& cylinder, const std::vector<double>& angles,
                         double edge, double turn_deg = 0);

}  // namespace carbonmesh
