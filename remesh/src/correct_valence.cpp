// Section 4.2: valence optimizer with a priority list (Algorithm 2).
#include <algorithm>
#include <cmath>
#include <vector>

#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/remesh_steps.hpp"
#include "remesh_geometry.hpp"

namespace carbonmesh {
namespace {

struct FlipQuad {
  TriMesh::VertexHandle a, b, c, d;  // edge a-b, opposite vertices c (left of a->b) and d
};

FlipQuad quad(const TriMesh& mesh, TriMesh::EdgeHandle e) {
  const auto h = mesh.halfedge_handle(e, 0), o = mesh.halfedge_handle(e, 1);
  return {mesh.from_vertex_handle(h), mesh.to_vertex_handle(h),
          mesh.to_vertex_handle(mesh.next_halfedge_handle(h)), mesh.to_vertex_handle(mesh.next_halfedge_handle(o))};
}

int sq(int x) { return x * x; }

// A flip is kept only if the smallest angle does not drop below half of its value (section 3.5.3) and
// neither new triangle turns against the old ones (no fold).
bool flip_geometry_ok(const TriMesh& mesh, const FlipQuad& q) {
  const Vec3 a = mesh.point(q.a), b = mesh.point(q.b), c = mesh.point(q.c), d = mesh.point(q.d);
  const double pre = std::min(geometry::min_angle(a, b, c), geometry::min_angle(b, a, d));
  const double post = std::min(geometry::min_angle(a, d, c), geometry::min_angle(b, c, d));
  if (post < 0.5 * pre) return false;
  const Vec3 n1 = geometry::triangle_normal(a, b, c), n2 = geometry::triangle_normal(b, a, d);
  const Vec3 m1 = geometry::triangle_normal(a, d, c), m2 = geometry::triangle_normal(b, c, d);
  for (const Vec3& n : {n1, n2})
    for (const Vec3& mm : {m1, m2})
      if (OpenMesh::dot(n, mm) <= 0) return false;
  return true;
}

}  // namespace

namespace {

// Eq 4.3 from cached valences: J_mp = E_val before - E_val after over the four vertices that change.
int improvement(const FlipQuad& q, const std::vector<int>& valence, const std::vector<int>& ideal) {
  auto at = [](const std::vector<int>& a, TriMesh::VertexHandle v) { return a[static_cast<std::size_t>(v.idx())]; };
  const int va = at(valence, q.a), vb = at(valence, q.b), vc = at(valence, q.c), vd = at(valence, q.d);
  const int ia = at(ideal, q.a), ib = at(ideal, q.b), ic = at(ideal, q.c), id = at(ideal, q.d);
  const int before = sq(ia - va) + sq(ib - vb) + sq(ic - vc) + sq(id - vd);  // Eq 4.2 on the four vertices
  const int after = sq(ia - (va - 1)) + sq(ib - (vb - 1)) + sq(ic - (vc + 1)) + sq(id - (vd + 1));
  return before - after;
}

}  // namespace

int valence_improvement(const TriMesh& mesh, TriMesh::EdgeHandle e) {
  if (mesh.status(e).deleted() || mesh.is_boundary(e)) return 0;
  const FlipQuad q = quad(mesh, e);
  std::vector<int> valence(mesh.n_vertices()), ideal(mesh.n_vertices());
  for (auto v : {q.a, q.b, q.c, q.d}) {
    valence[static_cast<std::size_t>(v.idx())] = static_cast<int>(mesh.valence(v));
    ideal[static_cast<std::size_t>(v.idx())] = ideal_valence(mesh, v);
  }
  return improvement(q, valence, ideal);
}

std::size_t correct_valence(TriMesh& mesh, double m, const EdgeInterval* keep) {
  struct Entry {
    int gain;
    double distance;  // | |e| - m |: farther from the interval centre first on equal gain
    int edge;
  };
  std::vector<int> valence(mesh.n_vertices(), 0), ideal(mesh.n_vertices(), 0);
  for (auto v : mesh.vertices()) {
    valence[static_cast<std::size_t>(v.idx())] = static_cast<int>(mesh.valence(v));
    ideal[static_cast<std::size_t>(v.idx())] = ideal_valence(mesh, v);
  }
  auto gain = [&](TriMesh::EdgeHandle e) {
    if (mesh.status(e).deleted() || mesh.is_boundary(e)) return 0;
    return improvement(quad(mesh, e), valence, ideal);
  };
  std::size_t total = 0;
  for (int pass = 0; pass < 100; ++pass) {
    std::vector<Entry> list;
    for (auto e : mesh.edges()) {
      const int g = gain(e);
      if (g > 0) list.push_back({g, std::abs(geometry::edge_length(mesh, e) - m), e.idx()});
    }
    std::sort(list.begin(), list.end(), [](const Entry& x, const Entry& y) {
      if (x.gain != y.gain) return x.gain > y.gain;
      if (x.distance != y.distance) return x.distance > y.distance;
      return x.edge < y.edge;
    });
    std::size_t flips = 0;
    for (const Entry& entry : list) {
      const TriMesh::EdgeHandle e(entry.edge);
      if (gain(e) <= 0 || !mesh.is_flip_ok(e)) continue;
      const FlipQuad q = quad(mesh, e);
      if (!flip_geometry_ok(mesh, q)) continue;  // the undo of Algorithm 2, checked beforehand
      if (keep) {  // do not trade an edge inside the interval for one outside
        const double before = geometry::edge_length(mesh, e);
        const double after = (mesh.point(q.c) - mesh.point(q.d)).norm();
        const bool inside_before = before >= keep->emin && before <= keep->emax;
        if (inside_before && (after < keep->emin || after > keep->emax)) continue;
      }
      mesh.flip(e);
      --valence[static_cast<std::size_t>(q.a.idx())];
      --valence[static_cast<std::size_t>(q.b.idx())];
      ++valence[static_cast<std::size_t>(q.c.idx())];
      ++valence[static_cast<std::size_t>(q.d.idx())];
      ++flips;
    }
    total += flips;
    if (flips == 0) break;
  }
  return total;
}

}  // namespace carbonmesh
