// Section 4.6: post-processing with the nonlinear optimizer and no projection.
#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/remesh_steps.hpp"

namespace carbonmesh {

int post_process(TriMesh& mesh, int kn, double emin, double emax) {
  const EdgeInterval interval{emin, emax};
  auto troubling = [&](const TriMesh& m) {
    const EdgeStats s = edge_stats(m, interval);
    return s.long_edges + s.short_edges;
  };
  std::size_t best = troubling(mesh);
  TriMesh saved = mesh;
  int rounds = 0;
  // While the number of long and short edges decreases (and some are left).
  while (best > 0 && rounds < 1000) {
    nonlinear_optimizer(mesh, kn, emin, emax);
    const std::size_t now = troubling(mesh);
    if (now >= best) break;
    best = now;
    saved = mesh;
    ++rounds;
  }
  mesh = saved;
  return rounds;
}

}  // namespace carbonmesh
