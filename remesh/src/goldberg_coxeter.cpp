// The Goldberg-Coxeter sphere (h, k): the triangular lattice folded onto the icosahedron (carbonmesh/remesh/shapes.hpp).
#include <fmt/format.h>

#include <cmath>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/shapes.hpp"
#include "add_faces.hpp"
#include "icosahedral.hpp"
#include "lattice_net.hpp"

namespace carbonmesh {

long triangulation_number(int h, int k) {
  const long hl = h, kl = k;
  return hl * hl + hl * kl + kl * kl;
}

void check_goldberg_coxeter(int h, int k) {
  if (h < 0 || k < 0 || (h == 0 && k == 0))
    throw InputError(fmt::format("Goldberg-Coxeter indices ({}, {}): both must be >= 0 and one > 0", h, k));
  if (triangulation_number(h, k) > kMaxTriangulationNumber)
    throw InputError(fmt::format("Goldberg-Coxeter indices ({}, {}): T = {} is more than {} ({:.0e} triangles)", h, k,
                                 triangulation_number(h, k), kMaxTriangulationNumber,
                                 20.0 * static_cast<double>(kMaxTriangulationNumber)));
}

TriMesh make_goldberg_coxeter_sphere(const GoldbergCoxeterShape& shape) {
  if (!(shape.radius > 0) || !std::isfinite(shape.radius))
    throw InputError("shape: sphere radius must be a positive number");
  check_goldberg_coxeter(shape.h, shape.k);
  // Every icosahedron face is the same lattice triangle 0, w = (h, k) and w turned by 60 degrees (lattice_net.hpp).
  const auto [corners, faces] = icosahedral::icosahedron();
  const lattice_net::LatticePoint w{shape.h, shape.k}, zero{0, 0};
  std::vector<lattice_net::NetFace> net;
  for (const auto& f : faces) net.push_back({f, {zero, w, lattice_net::turned(w, 1)}});
  const lattice_net::Folded folded = lattice_net::fold_lattice(12, net);
  const long T = triangulation_number(shape.h, shape.k);
  if (folded.places.size() != static_cast<std::size_t>(10 * T + 2) ||
      folded.triangles.size() != static_cast<std::size_t>(20 * T))
    throw std::logic_error(fmt::format("Goldberg-Coxeter folding ({}, {}): {} vertices and {} triangles, not {} and {}",
                                       shape.h, shape.k, folded.places.size(), folded.triangles.size(), 10 * T + 2,
                                       20 * T));
  // The points on the sphere: an edge's divide it into equal arcs from its smaller corner (g = gcd(h, k) steps), an
  // inner point is where the great circles of its three weights cross (icosahedral::spherical_point).
  const long g = std::gcd(shape.h, shape.k);
  TriMesh mesh;
  for (const auto& place : folded.places) {
    const auto& t = faces[static_cast<std::size_t>(place.face)];
    const auto& b = place.weights;
    int zeros = 0;
    for (double x : b) zeros += x == 0 ? 1 : 0;
    Vec3 p;
    if (zeros == 2) {  // a corner
      std::size_t c = 0;
      while (b[c] == 0) ++c;
      p = corners[static_cast<std::size_t>(t[c])];
    } else if (zeros == 1) {
      std::size_t d = 0;
      while (b[d] != 0) ++d;
      const std::size_t u = (d + 1) % 3, x = (d + 2) % 3, small = t[u] < t[x] ? u : x, large = small == u ? x : u;
      const long step = std::lround(b[large] * static_cast<double>(g));
      p = icosahedral::slerp(corners[static_cast<std::size_t>(t[small])], corners[static_cast<std::size_t>(t[large])],
                             static_cast<double>(step) / static_cast<double>(g));
    } else {
      p = icosahedral::spherical_point(corners[static_cast<std::size_t>(t[0])], corners[static_cast<std::size_t>(t[1])],
                                       corners[static_cast<std::size_t>(t[2])], b[0], b[1], b[2]);
    }
    mesh.add_vertex(p * shape.radius);
  }
  if (!add_faces(mesh, folded.triangles))
    throw std::logic_error("Goldberg-Coxeter folding: a triangle that does not fit its neighbours");
  icosahedral::even_out_on_sphere(mesh, shape.radius);
  mesh.update_normals();
  return mesh;
}

}  // namespace carbonmesh
