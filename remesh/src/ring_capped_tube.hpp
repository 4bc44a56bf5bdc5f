#pragma once
// Capped nanotubes of any chirality (n, m): each cap a lattice hexagon whose six corners are the cap's six pentagons
// (carbonmesh/remesh/shapes.hpp, make_capped_tube; the (5h, 5k) tubes take the icosahedral caps instead).
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

namespace ring_cap {

// The cap's rim on the unrolled tube: the steps f_0 .. f_5 from pentagon to pentagon, C = n e1 + m e2 their sum. The
// cap itself is the hexagon whose sides are f_i turned by i * 60 degrees (each pentagon takes 60 degrees out of the
// lattice around it): it closes when the sum of the turned steps is 0. Of the step sets whose hexagon is simple, whose
// steps all go forward along C and whose two caps leave a belt of lattice triangles between them, the one with the
// steps nearest C / 6 (the most regular hexagon, the pentagons farthest apart); none for tubes too thin for it.
std::optional<std::array<lattice_net::LatticePoint, 6>> ring_cap_steps(int n, int m);

// The capped tube (n, m) with ring caps; `shape` already checked. Throws InputError if no ring cap fits (n, m).
CappedTube make_ring_capped_tube(const CappedTubeShape& shape);

}  // namespace ring_cap

}  // namespace carbonmesh
