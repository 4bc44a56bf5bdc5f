// Section 4.6: post-processing with the nonlinear optimizer and no projection.
#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/remesh_steps.hpp"

namespace carbonmesh {

int post_process(TriMesh& mesh, int kn, double emin, double emax) {
  const EdgeInterval interval{emin, emax};
  const double m = 0.5 * (emin + emax);
  auto troubling = [&](const TriMesh& mm) {
    const EdgeStats s = edge_stats(mm, interval);
    return s.long_edges + s.short_edges;
  };
  std::size_t best = troubling(mesh);
  TriMesh saved = mesh;
  int rounds = 0;
  // While the number of long and short edges decreases (and some are left). When the optimizer alone
  // stops improving, one round with the stellar operations on [emin, emax] first is tried (kept only if
  // it improves).
  while (best > 0 && rounds < 1000) {
    nonlinear_optimizer(mesh, kn, emin, emax);
    std::size_t now = troubling(mesh);
    if (now >= best) {
      mesh = saved;
      stellar_operations(mesh, emin, emax, m);
      mesh.garbage_collection();
      correct_valence(mesh, m, &interval);
      nonlinear_optimizer(mesh, kn, emin, emax);
      now = troubling(mesh);
      if (now >= best) break;
    }
    best = now;
    saved = mesh;
    ++rounds;
  }
  mesh = saved;
  return rounds;
}

}  // namespace carbonmesh
