// Removal of interior vertices of valence 4 or less after the remeshing loop (not in the dissertation).
//
// A split in the nonlinear phase leaves a valence-4 vertex among regular ones. Flips cannot repair it: a
// flip moves valence charge in pairs (a 5-7 pair glides, it does not vanish), so without a 7 nearby every
// flip sequence keeps E_val, and regularize() leaves it. Collapsing the vertex into a neighbour removes its
// charge (two neighbours drop to valence 5); the region around the kept vertex is then relaxed as in
// regularize(), and the collapse is undone by a vertex split when the region ends with more edges outside
// [emin, emax] (or faces under 3 degrees) than before. On a mesh with every edge inside they all stay inside.
#include <limits>
#include <vector>

#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/remesh_steps.hpp"
#include "local_region.hpp"
#include "remesh_geometry.hpp"

namespace carbonmesh {

std::size_t remove_valence_defects(TriMesh& mesh, const ProjectionTarget& target, int kn, double emin,
                                   double emax) {
  std::vector<TriMesh::VertexHandle> defects;
  for (auto v : mesh.vertices())
    if (!mesh.is_boundary(v) && ideal_valence(mesh, v) - geometry::valence(mesh, v) >= 2) defects.push_back(v);
  std::size_t removed = 0;
  std::vector<std::pair<TriMesh::VertexHandle, Vec3>> moved, saved;
  std::vector<Vec3> neighbors;
  auto project = [&](TriMesh::VertexHandle v) { project_with_ring(mesh, target, v, neighbors); };
  LocalRegion local(emin, emax);
  std::vector<TriMesh::VertexHandle> region;
  for (auto v : defects) {
    if (mesh.status(v).deleted()) continue;
    std::vector<TriMesh::VertexHandle> ring;
    for (auto w : mesh.vv_range(v)) ring.push_back(w);
    for (const auto u : ring) {  // collapse into each neighbour in turn until one relaxes into the interval
      if (mesh.is_boundary(u)) continue;  // the border stays where it is
      const auto h = mesh.find_halfedge(v, u);
      const Vec3 pv = mesh.point(v), pu = mesh.point(u);
      const Vec3 mid = 0.5 * (pv + pu);
      if (!h.is_valid() || !collapse_ok(mesh, h, mid, std::numeric_limits<double>::infinity())) continue;
      // Every vertex the relaxation below can move, with the stars of those: kn + 3 rings around v.
      local.collect(mesh, v, kn + 3, region);
      const std::size_t flaws_before = local.flaws(mesh, region);
      const auto vl = mesh.to_vertex_handle(mesh.next_halfedge_handle(h));
      const auto vr = mesh.to_vertex_handle(mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(h)));
      mesh.collapse(h);
      mesh.set_point(u, mid);
      project(u);
      saved.assign(1, {u, pu});
      std::vector<TriMesh::EdgeHandle> around;
      for (auto g : mesh.voh_range(u)) around.push_back(mesh.edge_handle(g));
      for (const auto e : around) {
        const auto a = mesh.from_vertex_handle(mesh.halfedge_handle(e, 0));
        const auto b = mesh.to_vertex_handle(mesh.halfedge_handle(e, 0));
        if (geometry::star_inside(mesh, a, emin, emax) && geometry::star_inside(mesh, b, emin, emax)) continue;
        optimize_edge_region(mesh, e, kn, emin, emax, moved);
        saved.insert(saved.end(), moved.begin(), moved.end());
        for (const auto& [w, before] : moved) project(w);
      }
      if (local.flaws(mesh, region) <= flaws_before) {
        ++removed;
        break;
      }
      for (auto it = saved.rbegin(); it != saved.rend(); ++it) mesh.set_point(it->first, it->second);
      mesh.vertex_split(pv, u, vl, vr);  // the inverse of the collapse; the vertex comes back as the last one
      v = TriMesh::VertexHandle(static_cast<int>(mesh.n_vertices()) - 1);
    }
  }
  if (!defects.empty()) mesh.garbage_collection();
  return removed;
}

}  // namespace carbonmesh
