#pragma once
// Built-in shapes: well-shaped triangle meshes generated in code, closed but for the open tube. They are the default
// input of `make run` and the fixtures of the tests; the repository ships no other models.
#include <string>
#include <vector>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

// Icosahedron subdivided `subdivisions` times (each edge split in two), projected onto the sphere.
// Every vertex has valence 6 except the 12 of the icosahedron (valence 5).
struct SphereShape {
  double radius = 10.0;
  int subdivisions = 3;
};
TriMesh make_icosphere(const SphereShape& shape);

// Geodesic sphere: each icosahedron face divided into frequency^2 triangles (T = frequency^2, class I) and,
// with `sqrt3`, one sqrt(3) subdivision step after (T = 3 frequency^2, class II), projected onto the sphere:
// 20 T faces, every vertex of valence 6 except the 12 of the icosahedron (valence 5). Its dual is the
// icosahedral fullerene C_20T (frequency 1 with sqrt3: C60; 2: C240; 3: C540; 4: C960).
struct GeodesicSphereShape {
  double radius = 10.0;
  int frequency = 1;  // 1 to 1000
  bool sqrt3 = false;
};
TriMesh make_geodesic_sphere(const GeodesicSphereShape& shape);
// The geodesic sphere of `radius` whose face count 20 T is nearest to `faces` (ties to the smaller).
GeodesicSphereShape geodesic_sphere_for_faces(double faces, double radius);

// Goldberg-Coxeter sphere (h, k): the triangular lattice folded onto the icosahedron, each face the lattice triangle
// with corners 0, h e1 + k e2 and that vector turned by 60 degrees (e1, e2 lattice edges 60 degrees apart): T = h^2 +
// hk + k^2, 20 T faces, 10 T + 2 vertices, every vertex of valence 6 but the icosahedron's 12 (valence 5). Its
// points go onto the sphere as the geodesic sphere's do, and the same springs even them out. Its dual is the
// icosahedral fullerene C_20T: (h, 0) and (h, h) have the full symmetry Ih ((h, 0) is the geodesic sphere of
// frequency h), 0 < k < h gives a chiral cage (symmetry I; (k, h) is its mirror image). (1, 1) gives C60.
struct GoldbergCoxeterShape {
  double radius = 10.0;
  int h = 1, k = 0;
};
// The largest T built: 10^8 faces (`carbonmesh build`'s largest structure).
constexpr long kMaxTriangulationNumber = 5'000'000;
long triangulation_number(int h, int k);  // h^2 + hk + k^2
// Throws InputError unless h, k >= 0, not both 0, and T <= kMaxTriangulationNumber.
void check_goldberg_coxeter(int h, int k);
TriMesh make_goldberg_coxeter_sphere(const GoldbergCoxeterShape& shape);

// Capped nanotube (n, m). For (n, m) = (5h, 5k): the icosahedral fullerene C_20T, (h, k) its Goldberg-Coxeter
// indices, opened along a five-fold axis and lengthened by whole periods of the tube (n, m) (C60 gives the capped
// (5, 5) tube, C80's (2, 0) cage the capped (10, 0) tube). Its triangles are the lattice's folded onto that elongated
// icosahedron: 12 vertices of valence 5 (the dual's pentagons, six in each cap), every other of valence 6, 20 T + j P
// faces for j periods of P faces. The points lie on the capsule of the tube's radius whose straight part is the j
// periods: the caps are the Goldberg-Coxeter sphere's halves at that radius (with no period added, the whole sphere),
// the periods the lattice rolled onto the cylinder, evened out by springs as on the sphere. Its dual is the capped
// nanotube. Any other (n, m) but the thinnest (n^2 + nm + m^2 >= 25) gets apex caps (apex_capped_tube.cpp): each cap
// five lattice triangles around a pentagon, the apex, with the other five pentagons on their rim, as the icosahedral
// caps have them; the tube is as many lattice rows long as give the capsule of the length asked its area (the
// straight part within half a row of it), and the points lie on that capsule.
enum class CapKind {
  icosahedral,  // the halves of C_20T ((5h, 5k))
  apex,         // any other (n, m): a pentagon at the apex of five lattice triangles, five on their rim
};
const char* cap_kind_name(CapKind kind);         // "icosahedral", "apex"
const char* cap_kind_description(CapKind kind);  // e.g. "the halves of C_20T"
struct CappedTubeShape {
  int n = 5, m = 5;      // chiral indices
  double length = 0;     // wanted length of the straight part (mesh units): the nearest whole number of periods
                         // (icosahedral caps) or lattice rows (apex caps)
  double edge = 2.4595121467478056;  // lattice edge (mesh units): sqrt(3) times a C-C bond of 1.42 A
};
struct CappedTube {
  TriMesh mesh;
  int periods = 0;             // tube periods added to C_20T (0 with apex caps)
  CapKind caps = CapKind::icosahedral;
  double radius = 0;           // the tube's: edge |n e1 + m e2| / (2 pi)
  double straight_length = 0;  // of the capsule the points lie on (mesh units; icosahedral caps: periods * period)
  double period = 0;           // the tube's translation period (mesh units)
};
// Throws InputError unless n, m >= 0, not both 0, and for multiples of 5 T = (n^2 + nm + m^2) / 25 is at most
// kMaxTriangulationNumber (for others n^2 + nm + m^2 at most 25 times that).
void check_capped_tube(int n, int m);
// Whether the tube (n, m) gets the icosahedral caps (n and m multiples of 5) rather than apex caps.
bool icosahedral_caps(int n, int m);
double capped_tube_radius(int n, int m, double edge);
double capped_tube_period(int n, int m, double edge);
// Throws InputError for bad indices (check_capped_tube), a tube too thin for a cap, an edge that is not
// positive, a negative length or one that needs more than 20 kMaxTriangulationNumber faces.
CappedTube make_capped_tube(const CappedTubeShape& shape);

// A tube of radius `minor_radius` around a circle of radius `major_radius` (genus 1).
// `edge` is the target edge length (0: chosen so the tube has 24 segments around).
struct TorusShape {
  double major_radius = 10.0;
  double minor_radius = 4.0;
  double edge = 0.0;
};
TriMesh make_torus(const TorusShape& shape);

// A closed helical tube (a "nanospring"): a tube of radius `tube_radius` around a helix of radius `radius`,
// rising `pitch` per turn over `turns` turns, closed by hemispherical caps (genus 0).
struct HelixShape {
  double radius = 10.0;
  double pitch = 12.0;
  double turns = 2.0;
  double tube_radius = 3.0;
  double edge = 0.0;  // target edge length (0: 16 segments around the tube)
};
TriMesh make_helix(const HelixShape& shape);

// A cylinder of radius `radius` and straight length `length` closed by hemispheres (genus 0).
struct CapsuleShape {
  double radius = 5.0;
  double length = 20.0;
  double edge = 0.0;  // target edge length (0: 24 segments around)
};
TriMesh make_capsule(const CapsuleShape& shape);

// An open cylinder (no caps: two borders, the rims) of radius `radius` and length `length` (genus 0); neighbouring
// rings offset by half a step, so most triangles are not parallel to the axis.
struct TubeShape {
  double radius = 5.0;
  double length = 20.0;
  double edge = 0.0;  // target edge length (0: 24 segments around)
};
TriMesh make_open_tube(const TubeShape& shape);

// The names of the built-in shapes of `carbonmesh shape`.
const std::vector<std::string>& shape_names();

}  // namespace carbonmesh
