#include <cstddef>
#include <vector>

#include "carbonmesh/remesh/remesh_steps.hpp"

namespace carbonmesh {

void spring_relaxation(TriMesh& mesh, double target, int steps) {
  const int n = static_cast<int>(mesh.n_vertices());
  if (n == 0 || steps <= 0) return;
  // The neighbours in the circulator's order, gathered once; each step reads the old positions only (the same
  // result for any thread count).
  std::vector<std::size_t> first(static_cast<std::size_t>(n) + 1, 0);
  std::vector<int> neighbours;
  neighbours.reserve(2 * mesh.n_edges());
  std::vector<char> fixed(static_cast<std::size_t>(n), 0);
  for (auto v : mesh.vertices()) {
    fixed[static_cast<std::size_t>(v.idx())] = mesh.status(v).deleted() || mesh.is_boundary(v);
    for (auto w : mesh.vv_range(v)) neighbours.push_back(w.idx());
    first[static_cast<std::size_t>(v.idx()) + 1] = neighbours.size();
  }
  std::vector<Vec3> now(mesh.points(), mesh.points() + n), next(now);
  for (int step = 0; step < steps; ++step) {
#pragma omp parallel for schedule(static) if (n >= 20000)
    for (int i = 0; i < n; ++i) {
      const auto u = static_cast<std::size_t>(i);
      if (fixed[u] || first[u + 1] == first[u]) continue;
      const Vec3& p = now[u];
      Vec3 force(0, 0, 0), normal(0, 0, 0);
      for (std::size_t k = first[u]; k < first[u + 1]; ++k) {
        const Vec3 d = now[static_cast<std::size_t>(neighbours[k])] - p;
        const double l = d.norm();
        if (l > 0) force += (l - target) / l * d;
        // Fan normal: the ring's consecutive edge vectors (the ring is closed at an interior vertex).
        const std::size_t k1 = k + 1 < first[u + 1] ? k + 1 : first[u];
        normal += OpenMesh::cross(d, now[static_cast<std::size_t>(neighbours[k1])] - p);
      }
      const double nn = normal.sqrnorm();
      if (nn > 0) force -= (OpenMesh::dot(force, normal) / nn) * normal;  // tangential only
      next[u] = p + (0.5 / static_cast<double>(first[u + 1] - first[u])) * force;
    }
    now.swap(next);
  }
  for (auto v : mesh.vertices()) mesh.set_point(v, now[static_cast<std::size_t>(v.idx())]);
}

}  // namespace carbonmesh
