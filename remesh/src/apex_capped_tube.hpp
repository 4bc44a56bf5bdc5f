#pragma once
// Capped nanotubes of any chirality (n, m) with apex caps: each cap five lattice triangles around a pentagon, the apex,
// with the other five pentagons on their rim (carbonmesh/remesh/shapes.hpp, make_capped_tube; the (5h, 5k) tubes take
// the icosahedral caps, the case of five equal steps, instead).
#include <array>
#include <optional>
#include <vector>

#include "carbonmesh/remesh/shapes.hpp"
#include "lattice_net.hpp"

namespace carbonmesh {

// The mesh of the folded lattice's `points` and `triangles` (capped_tube.cpp), checked for `expected` triangles and
// F / 2 + 2 vertices, evened out by the sphere's springs on the capsule of `radius` whose straight part runs from
// -half to half along z.
TriMesh capsule_mesh(const std::vector<Vec3>& points, const std::vector<std::array<int, 3>>& triangles, long expected,
                     int n, int m, double radius, double half);

// The tube (n, m)'s translation vector, square to C = n e1 + m e2, pointing from the upper rim to the lower (toward
// -det(C, .)): ((2m + n) / d, -(2n + m) / d), d = gcd(2m + n, 2n + m).
lattice_net::LatticePoint translation_vector(long n, long m);

namespace apex_cap {

// The cap's rim on the unrolled tube: the steps f_0 .. f_4 from pentagon to pentagon, C = n e1 + m e2 their sum. The
// cap's sides are f_i turned by i * 60 degrees (each pentagon takes 60 degrees out of the lattice around it), the far
// sides of five triangles around the apex. Of the step sets whose steps all go forward along C, whose triangles are
// counter-clockwise with 300 degrees around the apex and each ring corner, and whose two caps leave a belt of lattice
// triangles between them, the one with the steps nearest C / 5 (the pentagons farthest apart); none for tubes too
// thin for it (n^2 + nm + m^2 < 25).
std::optional<std::array<lattice_net::LatticePoint, 5>> apex_cap_steps(int n, int m);

// The capped tube (n, m) with apex caps; `shape` already checked. Throws InputError if no cap fits (n, m).
CappedTube make_apex_capped_tube(const CappedTubeShape& shape);

}  // namespace apex_cap

}  // namespace carbonmesh
