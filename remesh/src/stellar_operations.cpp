// Section 4.1: stellar operations (edge split and edge collapse) with a priority list.
#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "carbonmesh/remesh/remesh_steps.hpp"
#include "remesh_geometry.hpp"

namespace carbonmesh {
namespace {

using VH = TriMesh::VertexHandle;
using HH = TriMesh::HalfedgeHandle;

using geometry::kMaxNormalTurnCos;
using geometry::kMinAngle;

// Number of border edges of the border loop through the boundary half-edge `h`.
std::size_t border_loop_length(const TriMesh& mesh, HH h) {
  std::size_t n = 0;
  HH g = h;
  do {
    ++n;
    g = mesh.next_halfedge_handle(g);
  } while (g != h && n < 8);  // only "<= 3" matters
  return n;
}

bool adjacent(const TriMesh& mesh, VH a, VH b) {
  for (auto w : mesh.vv_range(a))
    if (w == b) return true;
  return false;
}

// The link condition: the common neighbours of the two ends are exactly the vertices opposite the edge.
bool link_condition(const TriMesh& mesh, HH h) {
  const VH v0 = mesh.from_vertex_handle(h), v1 = mesh.to_vertex_handle(h);
  const HH o = mesh.opposite_halfedge_handle(h);
  VH vl, vr;
  if (!mesh.is_boundary(h)) vl = mesh.to_vertex_handle(mesh.next_halfedge_handle(h));
  if (!mesh.is_boundary(o)) vr = mesh.to_vertex_handle(mesh.next_halfedge_handle(o));
  if (vl.is_valid() && vl == vr) return false;
  for (auto w : mesh.vv_range(v0)) {
    if (w == v1 || w == vl || w == vr) continue;
    if (adjacent(mesh, w, v1)) return false;
  }
  // A tetrahedron passes the link condition but collapses into a doubled triangle.
  if (vl.is_valid() && vr.is_valid() && geometry::valence(mesh, v0) == 3 && geometry::valence(mesh, v1) == 3 &&
      adjacent(mesh, vl, vr))
    return false;
  return true;
}

// Whether an end of `e` is on a border.
bool touches_a_border(const TriMesh& mesh, TriMesh::EdgeHandle e) {
  const HH h = mesh.halfedge_handle(e, 0);
  return mesh.is_boundary(mesh.from_vertex_handle(h)) || mesh.is_boundary(mesh.to_vertex_handle(h));
}

// Whether a triangle of `e` has, opposite it, an interior vertex added in this pass (index >= first_new): that
// triangle was divided by a split already. A vertex added on a border edge does not count: it has valence 3 (ideal 4)
// until an edge of its triangle is split too, and a border vertex of valence 3 leaves that triangle almost no room.
bool next_to_a_split(const TriMesh& mesh, TriMesh::EdgeHandle e, int first_new) {
  for (int side = 0; side < 2; ++side) {
    const HH h = mesh.halfedge_handle(e, side);
    if (mesh.is_boundary(h)) continue;
    const VH opposite = mesh.to_vertex_handle(mesh.next_halfedge_handle(h));
    if (opposite.idx() >= first_new && !mesh.is_boundary(opposite)) return true;
  }
  return false;
}

}  // namespace

IntermediateInterval intermediate_interval(double current_mean, double emin, double emax) {
  const double m = 0.5 * (emin + emax);
  const double c = std::min(2.0 * current_mean, m);  // section 4.1, e^i_min and e^i_max
  // The half width is (emax - emin) / 2, except on a mesh whose mean edge is below that (a dense scan made into a
  // small structure): there c - (emax - emin) / 2 < m_i would collapse nothing, iteration after iteration, so the
  // lower bound is kept at m_i (c / 2) and the edges shorter than the mean are collapsed.
  const double half = std::min(0.5 * (emax - emin), 0.5 * c);
  return {c - half, c + half};
}

bool collapse_keeps_topology(TriMesh& mesh, HH h) {
  const auto e = mesh.edge_handle(h);
  if (mesh.status(e).deleted()) return false;
  const VH v0 = mesh.from_vertex_handle(h), v1 = mesh.to_vertex_handle(h);
  const bool border_edge = mesh.is_boundary(e);
  // Never collapse an interior edge between two border vertices (it would pinch the surface).
  if (!border_edge && mesh.is_boundary(v0) && mesh.is_boundary(v1)) return false;
  // Never move the border inwards by removing a border vertex into an interior one.
  if (mesh.is_boundary(v0) && !mesh.is_boundary(v1)) return false;
  if (border_edge) {
    const HH b = mesh.is_boundary(h) ? h : mesh.opposite_halfedge_handle(h);
    if (border_loop_length(mesh, b) <= 3) return false;  // would close (or degenerate) a border
  }
  if (!link_condition(mesh, h)) return false;
  return mesh.is_collapse_ok(h);
}

namespace {

// The geometric half of collapse_ok (the caller has checked the topology). The edge lengths go first: on
// stanford-bunny's second iteration they refuse 39% of the positions tried, the normals and angles 1%.
bool collapse_geometry_ok(const TriMesh& mesh, HH h, const Vec3& position, double max_edge) {
  const VH v0 = mesh.from_vertex_handle(h), v1 = mesh.to_vertex_handle(h);
  for (VH v : {v0, v1})
    for (auto w : mesh.vv_range(v))
      if (w != v0 && w != v1 && (mesh.point(w) - position).norm() > max_edge) return false;
  for (VH v : {v0, v1}) {
    for (auto f : mesh.vf_range(v)) {
      Vec3 p[3];
      bool has0 = false, has1 = false;
      int i = 0;
      for (auto w : mesh.fv_range(f)) {
        has0 |= w == v0;
        has1 |= w == v1;
        p[i++] = (w == v0 || w == v1) ? position : mesh.point(w);
      }
      if (has0 && has1) continue;  // removed by the collapse
      Vec3 a, b, c;
      geometry::face_points(mesh, f, a, b, c);
      const Vec3 before = geometry::triangle_normal(a, b, c);
      const Vec3 after = geometry::triangle_normal(p[0], p[1], p[2]);
      if (OpenMesh::dot(before, after) < kMaxNormalTurnCos) return false;
      if (geometry::min_angle(p[0], p[1], p[2]) < kMinAngle) return false;
    }
  }
  return true;
}

}  // namespace

bool collapse_ok(TriMesh& mesh, HH h, const Vec3& position, double max_edge) {
  return collapse_keeps_topology(mesh, h) && collapse_geometry_ok(mesh, h, position, max_edge);
}

Vec3 minimize_length_energy(const std::vector<Vec3>& neighbors, const Vec3& start, const Vec3& normal, double m) {
  // Eq 4.1: sum_j (|V_i - V_j| - m)^2, Gauss-Newton in the plane (start; t1, t2).
  Vec3 t1, t2;
  const double nl = normal.norm();
  geometry::tangent_basis(nl > 0 ? normal / nl : Vec3(0, 0, 1), t1, t2);
  Eigen::Vector2d uv(0, 0);
  // The differences x - p and their lengths at the current point are kept from the evaluation that accepted it
  // (the Jacobian needs the same values).
  thread_local std::vector<Vec3> d_now, d_trial;
  thread_local std::vector<double> l_now, l_trial;
  const std::size_t n = neighbors.size();
  for (auto* v : {&d_now, &d_trial}) v->resize(n);
  for (auto* v : {&l_now, &l_trial}) v->resize(n);
  auto energy = [&](const Eigen::Vector2d& q, std::vector<Vec3>& d, std::vector<double>& l) {
    const Vec3 x = start + q[0] * t1 + q[1] * t2;
    double s = 0;
    for (std::size_t i = 0; i < n; ++i) {
      d[i] = x - neighbors[i];
      l[i] = d[i].norm();
      const double r = l[i] - m;
      s += r * r;
    }
    return s;
  };
  double current = energy(uv, d_now, l_now);
  for (int it = 0; it < 10; ++it) {
    Eigen::Matrix2d jtj = Eigen::Matrix2d::Zero();
    Eigen::Vector2d jtr = Eigen::Vector2d::Zero();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3& d = d_now[i];
      const double l = l_now[i];
      if (l <= 1e-12) continue;
      const Eigen::Vector2d j(OpenMesh::dot(d, t1) / l, OpenMesh::dot(d, t2) / l);
      jtj += j * j.transpose();
      jtr += j * (l - m);
    }
    jtj.diagonal().array() += 1e-9 + 1e-3 * jtj.trace();
    const Eigen::Vector2d step = -jtj.ldlt().solve(jtr);
    if (!step.allFinite()) break;
    double scale = 1.0;
    bool improved = false;
    for (int k = 0; k < 6; ++k, scale *= 0.5) {
      const Eigen::Vector2d q = uv + scale * step;
      const double e = energy(q, d_trial, l_trial);
      if (e < current) {
        uv = q;
        current = e;
        d_now.swap(d_trial);
        l_now.swap(l_trial);
        improved = true;
        break;
      }
    }
    if (!improved || scale * step.norm() < 1e-9 * (1 + m)) break;
  }
  return start + uv[0] * t1 + uv[1] * t2;
}

namespace {

// Splits `e` at a position minimising Eq 4.1 (the midpoint for border edges or when that folds a face).
void split_edge(TriMesh& mesh, TriMesh::EdgeHandle e, double m) {
  const HH h = mesh.halfedge_handle(e, 0), o = mesh.halfedge_handle(e, 1);
  const VH a = mesh.from_vertex_handle(h), b = mesh.to_vertex_handle(h);
  const Vec3 mid = 0.5 * (mesh.point(a) + mesh.point(b));
  Vec3 position = mid;
  if (!mesh.is_boundary(e)) {
    const VH c = mesh.to_vertex_handle(mesh.next_halfedge_handle(h));
    const VH d = mesh.to_vertex_handle(mesh.next_halfedge_handle(o));
    const Vec3 n = geometry::face_normal(mesh, mesh.face_handle(h)) + geometry::face_normal(mesh, mesh.face_handle(o));
    thread_local std::vector<Vec3> nb;  // (no allocation per split)
    nb.assign({mesh.point(a), mesh.point(b), mesh.point(c), mesh.point(d)});
    const Vec3 x = minimize_length_energy(nb, mid, n, m);
    // The four new triangles (a,x,c), (x,b,c), (b,x,d), (x,a,d) must keep the orientation and shape.
    const Vec3 nn = n.norm() > 0 ? n.normalized() : n;
    bool ok = true;
    const Vec3 pa = mesh.point(a), pb = mesh.point(b), pc = mesh.point(c), pd = mesh.point(d);
    const Vec3 tris[4][3] = {{pa, x, pc}, {x, pb, pc}, {pb, x, pd}, {x, pa, pd}};
    for (const auto& t : tris) {
      if (OpenMesh::dot(geometry::triangle_normal(t[0], t[1], t[2]), nn) < kMaxNormalTurnCos ||
          geometry::min_angle(t[0], t[1], t[2]) < kMinAngle)
        ok = false;
    }
    if (ok) position = x;
  }
  const VH v = mesh.add_vertex(position);
  mesh.split(e, v);
}

// Collapses `e` if some direction is allowed; the kept vertex goes to the Eq 4.1 position (border
// vertices keep their place; a border edge collapses to its midpoint).
bool collapse_edge(TriMesh& mesh, TriMesh::EdgeHandle e, double max_edge, double m) {
  for (int side = 0; side < 2; ++side) {
    const HH h = mesh.halfedge_handle(e, side);
    const VH v0 = mesh.from_vertex_handle(h), v1 = mesh.to_vertex_handle(h);
    if (!collapse_keeps_topology(mesh, h)) continue;
    auto fits = [&](const Vec3& p) { return collapse_geometry_ok(mesh, h, p, max_edge); };
    Vec3 position;
    bool ok = false;  // each position is checked once
    if (mesh.is_boundary(e)) {
      position = 0.5 * (mesh.point(v0) + mesh.point(v1));
      ok = fits(position);
    } else if (mesh.is_boundary(v1)) {
      position = mesh.point(v1);
      ok = fits(position);
    } else {
      thread_local std::vector<Vec3> nb;  // (no allocation per collapse)
      nb.clear();
      for (VH v : {v0, v1})
        for (auto w : mesh.vv_range(v))
          if (w != v0 && w != v1) nb.push_back(mesh.point(w));
      const Vec3 mid = 0.5 * (mesh.point(v0) + mesh.point(v1));
      const Vec3 n = geometry::vertex_normal(mesh, v0) + geometry::vertex_normal(mesh, v1);
      position = minimize_length_energy(nb, mid, n, m);
      ok = fits(position);
      if (!ok) ok = fits(position = mid);
    }
    if (!ok) continue;
    mesh.collapse(h);
    mesh.set_point(v1, position);
    return true;
  }
  return false;
}

}  // namespace

StellarResult stellar_operations(TriMesh& mesh, double emin, double emax, double m) {
  struct Entry {
    double priority;
    int edge;
  };
  std::vector<Entry> list;
  for (auto e : mesh.edges()) {
    if (mesh.status(e).deleted()) continue;
    const double l = geometry::edge_length(mesh, e);
    if (l > emax) list.push_back({l / emax, e.idx()});
    else if (l < emin) list.push_back({emin / std::max(l, 1e-300), e.idx()});
  }
  // Farthest outside the interval first; ties by edge index (a total order: deterministic).
  std::sort(list.begin(), list.end(), [](const Entry& a, const Entry& b) {
    return a.priority != b.priority ? a.priority > b.priority : a.edge < b.edge;
  });
  // A collapse may leave edges up to half an interval width above emax: the low-pass filter relaxes them,
  // while refusing every collapse that creates an edge above emax stalls with too many vertices.
  const double max_collapse_edge = emax + 0.5 * (emax - emin);
  StellarResult result;
  const int first_new = static_cast<int>(mesh.n_vertices());  // splits add vertices from here on
  for (const Entry& entry : list) {
    const TriMesh::EdgeHandle e(entry.edge);
    if (mesh.status(e).deleted()) continue;
    const double l = geometry::edge_length(mesh, e);
    if (l > emax) {
      // An interior edge shorter than 2 emin splits into two short halves: next to a split of this pass it waits for
      // the next one (where every edge is long, splitting them all divided each face into four, and the next
      // iterations collapsed most of the new vertices again).
      if (l < 2.0 * emin && !touches_a_border(mesh, e) && next_to_a_split(mesh, e, first_new)) continue;
      split_edge(mesh, e, m);
      ++result.splits;
    } else if (l < emin) {
      if (collapse_edge(mesh, e, max_collapse_edge, m)) ++result.collapses;
    }
  }
  return result;
}

}  // namespace carbonmesh
