// Section 4.4: nonlinear optimizer of Error_b (Eq 4.7) around troubling edges, by priority.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "carbonmesh/remesh/remesh_steps.hpp"
#include "dense_llt.hpp"
#include "permuted_ldlt.hpp"
#include "remesh_geometry.hpp"

namespace carbonmesh {
namespace {

using VH = TriMesh::VertexHandle;

using geometry::kMaxNormalTurnCos;
constexpr double kFoldCos = -0.5;  // neighbouring faces more than 120 degrees apart are folded
using geometry::kMinAngle;
constexpr double kHingeWeight = 1000.0;  // weight of the interval hinge relative to Eq 4.7
constexpr double kHingeMargin = 0.05;    // the hinge starts this share of the interval width inside it
constexpr int kDenseUnknowns = 48;       // regions with at most this many unknowns are solved with a dense LLT

bool troubling(const TriMesh& mesh, TriMesh::EdgeHandle e, double emin, double emax) {
  const double l = geometry::edge_length(mesh, e);
  return l < emin || l > emax;
}

// The border curve of `v`; false when `v` is not on exactly one border or its border neighbours coincide.
bool border_curve(const TriMesh& mesh, VH v, geometry::BorderCurve& c) {
  TriMesh::HalfedgeHandle out;
  int count = 0;
  for (auto h : mesh.voh_range(v))
    if (mesh.is_boundary(h)) out = h, ++count;
  if (count != 1) return false;
  const auto in = mesh.prev_halfedge_handle(out);
  const VH va = mesh.from_vertex_handle(in), vb = mesh.to_vertex_handle(out);
  if (va == vb) return false;
  c.a = mesh.point(va), c.p = mesh.point(v), c.b = mesh.point(vb);
  c.ta = -(c.p - c.a).norm(), c.tb = (c.b - c.p).norm();
  return c.ta < 0 && c.tb > 0;
}

// Vertices within `k` rings of the two ends of an edge (ring 0: the ends), in BFS order.
struct EdgeStar {
  std::vector<VH> vertices;
  std::vector<int> ring;
};

struct Marks {
  std::vector<int> vertex, edge, local;
  int stamp = 0;
  // optimize_region's fold check: per attempt (face_stamp), the faces checked and those whose normal at the trial
  // displacement is held in face_normal; per region (stamp), those whose normal before the move is in face_before.
  std::vector<int> face_checked, face_normal_stamp, face_before_stamp;
  std::vector<Vec3> face_normal, face_before;
  int face_stamp = 0;
  explicit Marks(const TriMesh& mesh)
      : vertex(mesh.n_vertices(), 0), edge(mesh.n_edges(), 0), local(mesh.n_vertices(), -1),
        face_checked(mesh.n_faces(), 0), face_normal_stamp(mesh.n_faces(), 0), face_before_stamp(mesh.n_faces(), 0),
        face_normal(mesh.n_faces()), face_before(mesh.n_faces()) {}
  bool fits(const TriMesh& mesh) const {
    return vertex.size() == mesh.n_vertices() && edge.size() == mesh.n_edges() && face_checked.size() == mesh.n_faces();
  }
};

void collect_edge_star(const TriMesh& mesh, TriMesh::EdgeHandle e, int k, EdgeStar& star, Marks& marks) {
  ++marks.stamp;
  star.vertices.clear();
  star.ring.clear();
  auto visit = [&](VH w, int r) {
    marks.vertex[static_cast<std::size_t>(w.idx())] = marks.stamp;
    marks.local[static_cast<std::size_t>(w.idx())] = static_cast<int>(star.vertices.size());
    star.vertices.push_back(w);
    star.ring.push_back(r);
  };
  const auto h = mesh.halfedge_handle(e, 0);
  visit(mesh.from_vertex_handle(h), 0);
  visit(mesh.to_vertex_handle(h), 0);
  std::size_t begin = 0;
  for (int r = 1; r <= k; ++r) {
    const std::size_t end = star.vertices.size();
    for (std::size_t i = begin; i < end; ++i)
      for (auto w : mesh.vv_range(star.vertices[i]))
        if (marks.vertex[static_cast<std::size_t>(w.idx())] != marks.stamp) visit(w, r);
    begin = end;
  }
}

// p_j = n_l + n_s: troubling edges of the kn-star of the edge (edges at a vertex of star number < kn).
int priority(const TriMesh& mesh, const EdgeStar& star, int kn, const std::vector<char>& is_troubling, Marks& marks) {
  int count = 0;
  for (std::size_t i = 0; i < star.vertices.size() && star.ring[i] < kn; ++i) {
    for (auto he : mesh.voh_range(star.vertices[i])) {
      const auto e = mesh.edge_handle(he);
      auto& mark = marks.edge[static_cast<std::size_t>(e.idx())];
      if (mark == marks.stamp) continue;
      mark = marks.stamp;
      count += is_troubling[static_cast<std::size_t>(e.idx())];
    }
  }
  return count;
}

// Minimises Error_b (Eq 4.7) over the tangent displacements (alpha_i, beta_i) of `variables` with
// Levenberg-Marquardt; the other vertices stay fixed. Applies the result if no face folds.
void optimize_region(TriMesh& mesh, const std::vector<VH>& variables, double emin, double emax, double outside_weight,
                     Marks& marks) {
  const double m = 0.5 * (emin + emax);
  const int nv = static_cast<int>(variables.size());
  ++marks.stamp;
  for (int i = 0; i < nv; ++i) {
    marks.vertex[static_cast<std::size_t>(variables[static_cast<std::size_t>(i)].idx())] = marks.stamp;
    marks.local[static_cast<std::size_t>(variables[static_cast<std::size_t>(i)].idx())] = i;
  }
  auto var_index = [&](VH w) {
    return marks.vertex[static_cast<std::size_t>(w.idx())] == marks.stamp ? marks.local[static_cast<std::size_t>(w.idx())] : -1;
  };
  // Residual edges: every edge at a variable vertex, once.
  struct Term {
    int a, b;     // variable indices (b: -1 for a fixed end)
    Vec3 fixed;   // the fixed end's position (b = -1)
    double weight;  // outside_weight for an edge outside [emin, emax] at the start, else 1
  };
  std::vector<Term> terms;
  for (int i = 0; i < nv; ++i) {
    const VH v = variables[static_cast<std::size_t>(i)];
    for (auto w : mesh.vv_range(v)) {
      const int j = var_index(w);
      if (j >= 0 && j < i) continue;  // counted from the other end
      const double l = (mesh.point(v) - mesh.point(w)).norm();
      terms.push_back({i, j, mesh.point(w), l < emin || l > emax ? outside_weight : 1.0});
    }
  }
  std::vector<Vec3> base(static_cast<std::size_t>(nv)), t1(static_cast<std::size_t>(nv)), t2(static_cast<std::size_t>(nv));
  // Border vertices have one degree of freedom, the parameter on their border curve (x[2i]; x[2i+1] has
  // no effect and stays 0 under the damping).
  std::vector<int> curve_of(static_cast<std::size_t>(nv), -1);
  std::vector<geometry::BorderCurve> curves;
  for (int i = 0; i < nv; ++i) {
    const VH v = variables[static_cast<std::size_t>(i)];
    base[static_cast<std::size_t>(i)] = mesh.point(v);
    if (mesh.is_boundary(v)) {
      geometry::BorderCurve c;
      border_curve(mesh, v, c);  // the caller checked that it exists
      curve_of[static_cast<std::size_t>(i)] = static_cast<int>(curves.size());
      curves.push_back(c);
      t1[static_cast<std::size_t>(i)] = c.derivative(0);
      t2[static_cast<std::size_t>(i)] = Vec3(0, 0, 0);
      continue;
    }
    geometry::tangent_basis(geometry::vertex_normal(mesh, v), t1[static_cast<std::size_t>(i)], t2[static_cast<std::size_t>(i)]);
  }
  const double m2 = m * m;
  auto position = [&](const Eigen::VectorXd& x, int i) {
    const auto s = static_cast<std::size_t>(i);
    if (curve_of[s] >= 0) return curves[static_cast<std::size_t>(curve_of[s])].at(x[2 * i]);
    return base[s] + x[2 * i] * t1[s] + x[2 * i + 1] * t2[s];
  };
  // The positions of every variable at x, once per evaluation (each is an end of about six terms).
  auto positions = [&](const Eigen::VectorXd& x, std::vector<Vec3>& out) {
    out.resize(static_cast<std::size_t>(nv));
    for (int i = 0; i < nv; ++i) out[static_cast<std::size_t>(i)] = position(x, i);
  };
  auto end_b = [&](const std::vector<Vec3>& at, const Term& t) {
    return t.b >= 0 ? at[static_cast<std::size_t>(t.b)] : t.fixed;
  };
  // A border parameter outside the middle halves of its border edges is not allowed.
  auto admissible = [&](const Eigen::VectorXd& x) {
    for (int i = 0; i < nv; ++i) {
      const int c = curve_of[static_cast<std::size_t>(i)];
      if (c >= 0 && !curves[static_cast<std::size_t>(c)].contains(x[2 * i])) return false;
    }
    return true;
  };
  auto point_of = [&](const Eigen::VectorXd& x, int index, VH v) { return index >= 0 ? position(x, index) : mesh.point(v); };
  // Error_b (Eq 4.7) plus a hinge on the interval: squared lengths outside [lo^2, hi^2] (the interval
  // shrunk by a small margin) cost kHingeWeight more. Least squares alone may trade a short edge for
  // another one around a valence defect; the hinge prefers every edge inside.
  const double margin = kHingeMargin * (emax - emin);
  const double lo2 = (emin + margin) * (emin + margin), hi2 = (emax - margin) * (emax - margin);
  auto hinge = [&](double l2) { return l2 < lo2 ? l2 - lo2 : (l2 > hi2 ? l2 - hi2 : 0.0); };
  auto energy = [&](const std::vector<Vec3>& at) {
    double e = 0;
    for (const Term& t : terms) {
      const double l2 = (at[static_cast<std::size_t>(t.a)] - end_b(at, t)).sqrnorm();
      const double r = l2 - m2, h = hinge(l2);
      e += t.weight * r * r + kHingeWeight * h * h;
    }
    return e;
  };
  const int dim = 2 * nv;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(dim);
  std::vector<Vec3> at, trial_at;
  positions(x, at);
  double current = energy(at);
  double mu = 1e-3, nu = 2;  // the damping, and its factor after a failed try (doubled on each)
  const double diag_floor = 1e-12 * (1 + m2);  // added to each diagonal entry the damping scales (keeps it positive)
  std::vector<double> diag(static_cast<std::size_t>(2 * nv));  // diag(J^T J) of the iteration
  auto term_indices = [&](const Term& t, int idx[4]) {
    int c = 0;
    idx[c++] = 2 * t.a, idx[c++] = 2 * t.a + 1;
    if (t.b >= 0) idx[c++] = 2 * t.b, idx[c++] = 2 * t.b + 1;
    return c;
  };
  // J^T J is sparse (2x2 blocks of the variables an edge joins). A small region (the usual kn-star: about 24
  // unknowns) is solved dense; a large one keeps its pattern once, each term with pointers to its entries,
  // and a sparse LDL^T analysed once (PermutedLDLT: Eigen's fill-reducing permutation applied once per region).
  // Both keep the lower triangle only, the part their factorizations read.
  auto lower = [](int row, int column) { return column <= row; };
  const bool dense = dim <= kDenseUnknowns;
  Eigen::MatrixXd jtj_dense, h_dense;
  Eigen::SparseMatrix<double> jtj;
  PermutedLDLT ldlt;
  std::vector<double*> entry, diag_entry;
  if (dense) {
    jtj_dense.resize(dim, dim);
    h_dense.resize(dim, dim);
  } else {
    std::vector<Eigen::Triplet<double>> pattern;
    for (int i = 0; i < dim; ++i) pattern.emplace_back(i, i, 0.0);
    for (const Term& t : terms) {
      int idx[4];
      const int c = term_indices(t, idx);
      for (int p = 0; p < c; ++p)
        for (int q = 0; q < c; ++q)
          if (lower(idx[p], idx[q])) pattern.emplace_back(idx[p], idx[q], 0.0);
    }
    jtj.resize(dim, dim);
    jtj.setFromTriplets(pattern.begin(), pattern.end());
    jtj.makeCompressed();
    entry.assign(16 * terms.size(), nullptr);
    for (std::size_t k = 0; k < terms.size(); ++k) {
      int idx[4];
      const int c = term_indices(terms[k], idx);
      for (int p = 0; p < c; ++p)
        for (int q = 0; q < c; ++q)
          if (lower(idx[p], idx[q]))
            entry[16 * k + static_cast<std::size_t>(4 * p + q)] = &jtj.coeffRef(idx[p], idx[q]);
    }
    diag_entry.resize(static_cast<std::size_t>(dim));
    for (int i = 0; i < dim; ++i) diag_entry[static_cast<std::size_t>(i)] = &jtj.coeffRef(i, i);
    ldlt.analyze(jtj);
  }
  Eigen::VectorXd jtr(dim), step(dim);
  for (int it = 0; it < 20 && current > 0; ++it) {
    if (dense)
      for (int j = 0; j < dim; ++j) jtj_dense.col(j).tail(dim - j).setZero();
    else std::fill(jtj.valuePtr(), jtj.valuePtr() + jtj.nonZeros(), 0.0);
    jtr.setZero();
    for (int i = 0; i < nv; ++i)
      if (const int c = curve_of[static_cast<std::size_t>(i)]; c >= 0)
        t1[static_cast<std::size_t>(i)] = curves[static_cast<std::size_t>(c)].derivative(x[2 * i]);
    for (std::size_t k = 0; k < terms.size(); ++k) {
      const Term& t = terms[k];
      const Vec3 d = at[static_cast<std::size_t>(t.a)] - end_b(at, t);
      const double l2 = d.sqrnorm();
      const double r = l2 - m2, hr = hinge(l2);
      const double wj = t.weight + (hr != 0 ? kHingeWeight : 0.0);  // J^T J weight of this edge
      const double wr = t.weight * r + kHingeWeight * hr;           // J^T r weight
      double g[4];
      int idx[4];
      const int c = term_indices(t, idx);
      const auto sa = static_cast<std::size_t>(t.a);
      g[0] = 2 * OpenMesh::dot(d, t1[sa]);
      g[1] = 2 * OpenMesh::dot(d, t2[sa]);
      if (t.b >= 0) {
        const auto sb = static_cast<std::size_t>(t.b);
        g[2] = -2 * OpenMesh::dot(d, t1[sb]);
        g[3] = -2 * OpenMesh::dot(d, t2[sb]);
      }
      for (int p = 0; p < c; ++p) {
        jtr[idx[p]] += wr * g[p];
        if (dense)
          for (int q = 0; q < c; ++q) {
            if (lower(idx[p], idx[q])) jtj_dense(idx[p], idx[q]) += wj * g[p] * g[q];
          }
        else
          for (int q = 0; q < c; ++q) {
            if (lower(idx[p], idx[q])) *entry[16 * k + static_cast<std::size_t>(4 * p + q)] += wj * g[p] * g[q];
          }
      }
    }
    bool improved = false;
    for (int i = 0; i < dim; ++i) diag[i] = dense ? jtj_dense(i, i) : *diag_entry[static_cast<std::size_t>(i)];
    for (int tries = 0; tries < 8 && !improved; ++tries) {
      // The damped system: J^T J + mu (diag(J^T J) + a tiny floor).
      if (dense) {
        h_dense.triangularView<Eigen::Lower>() = jtj_dense;
        for (int i = 0; i < dim; ++i) h_dense(i, i) += mu * (diag[i] + diag_floor);
        // (positive definite: the damping adds mu times a positive floor; Eigen's LLT arithmetic, dense_llt.hpp)
        if (!llt_in_place(h_dense)) break;
        llt_solve(h_dense, jtr, step);
        step = -step;
      } else {
        if (!ldlt.factorize(jtj, mu, diag_floor)) break;
        ldlt.solve(jtr, step);
        step = -step;
      }
      if (!step.allFinite()) break;
      const Eigen::VectorXd trial = x + step;
      double e = std::numeric_limits<double>::infinity();
      if (admissible(trial)) {
        positions(trial, trial_at);
        e = energy(trial_at);
      }
      if (e < current) {
        const double gain = current - e;
        // Nielsen's update (1999): the damping falls by up to 3 as the gain nears what the linearisation predicted,
        // and rises after a poor one (with the old mu / 3, x 4, half the tries failed: bunny's snap 0.36 -> 0.28 s).
        double predicted = -step.dot(jtr);
        for (int i = 0; i < dim; ++i) predicted += mu * (diag[i] + diag_floor) * step[i] * step[i];
        const double rho = predicted > 0 ? gain / predicted : 0.0;
        x = trial;
        at.swap(trial_at);
        current = e;
        mu = std::max(mu * std::max(1.0 / 3, 1 - std::pow(2 * rho - 1, 3)), 1e-9);
        nu = 2;
        improved = true;
        if (gain < 1e-10 * (1 + current)) it = 1000;
      } else {
        mu *= nu;
        nu *= 2;
      }
    }
    if (!improved) break;
  }
  // Apply, halving the displacement while some face folds or degenerates: a face turns by more than
  // acos(kMaxNormalTurnCos), or two neighbouring faces fold (their normals end more than 120 degrees apart).
  // Each face may turn within the limit and two neighbours still fold when they turn opposite ways (fertility at
  // 250000 atoms with two coarse levels: 4 edges folded by 170-178 degrees). Edges folded already (camelhead's
  // mouth) are left to the other checks.
  auto moved_corners = [&](TriMesh::FaceHandle f, Vec3 (&q)[3]) {
    int c = 0;
    for (auto w : mesh.fv_range(f)) q[c++] = point_of(x, var_index(w), w);
  };
  // Within an attempt a face is checked once (it is reached from each of its moving corners, and the check depends
  // on x only), and each face's normal at x is computed once (it is also read by its neighbours' checks); each face's
  // normal before the move is computed once for all the attempts (the mesh does not change until one is applied).
  auto normal_before = [&](TriMesh::FaceHandle f) {
    const auto i = static_cast<std::size_t>(f.idx());
    if (marks.face_before_stamp[i] != marks.stamp) {
      marks.face_before[i] = geometry::face_normal(mesh, f);
      marks.face_before_stamp[i] = marks.stamp;
    }
    return marks.face_before[i];
  };
  auto moved_face = [&](TriMesh::FaceHandle f, Vec3 (&q)[3]) {  // q: f's corners at x; returns its normal at x
    moved_corners(f, q);
    const auto i = static_cast<std::size_t>(f.idx());
    marks.face_normal[i] = geometry::triangle_normal(q[0], q[1], q[2]);
    marks.face_normal_stamp[i] = marks.face_stamp;
    return marks.face_normal[i];
  };
  auto moved_normal = [&](TriMesh::FaceHandle f) {
    const auto i = static_cast<std::size_t>(f.idx());
    if (marks.face_normal_stamp[i] == marks.face_stamp) return marks.face_normal[i];
    Vec3 q[3];
    return moved_face(f, q);
  };
  for (int attempt = 0; attempt < 5; ++attempt, x *= 0.5) {
    bool ok = true;
    ++marks.face_stamp;
    for (int i = 0; i < nv && ok; ++i) {
      for (auto f : mesh.vf_range(variables[static_cast<std::size_t>(i)])) {
        const auto fi = static_cast<std::size_t>(f.idx());
        if (marks.face_checked[fi] == marks.face_stamp) continue;
        marks.face_checked[fi] = marks.face_stamp;
        Vec3 q[3];
        const Vec3 before = normal_before(f), after = moved_face(f, q);
        ok = OpenMesh::dot(before, after) >= kMaxNormalTurnCos && geometry::min_angle(q[0], q[1], q[2]) >= kMinAngle;
        for (auto h : mesh.fh_range(f)) {
          const auto g = mesh.opposite_face_handle(h);
          if (!ok || !g.is_valid()) continue;
          const double fold_before = OpenMesh::dot(before, normal_before(g));
          ok = fold_before < kFoldCos || OpenMesh::dot(after, moved_normal(g)) >= kFoldCos;
        }
        if (!ok) break;
      }
    }
    if (ok) {
      for (int i = 0; i < nv; ++i) mesh.set_point(variables[static_cast<std::size_t>(i)], position(x, i));
      return;
    }
  }
}

}  // namespace

std::size_t optimize_edge_region(TriMesh& mesh, TriMesh::EdgeHandle e, int k, double emin, double emax,
                                 std::vector<std::pair<TriMesh::VertexHandle, Vec3>>& moved) {
  thread_local std::unique_ptr<Marks> marks;
  if (!marks || !marks->fits(mesh)) marks = std::make_unique<Marks>(mesh);
  thread_local EdgeStar star;
  thread_local std::vector<VH> variables;
  collect_edge_star(mesh, e, k, star, *marks);
  variables.clear();
  moved.clear();
  for (std::size_t i = 0; i < star.vertices.size() && star.ring[i] < k; ++i)
    if (!mesh.is_boundary(star.vertices[i])) {
      variables.push_back(star.vertices[i]);
      moved.emplace_back(star.vertices[i], mesh.point(star.vertices[i]));
    }
  if (!variables.empty()) optimize_region(mesh, variables, emin, emax, 1.0, *marks);
  return variables.size();
}

bool slides_on_border(const TriMesh& mesh, TriMesh::VertexHandle v) {
  geometry::BorderCurve c;
  return border_curve(mesh, v, c);
}

void optimize_vertices(TriMesh& mesh, const std::vector<TriMesh::VertexHandle>& variables, double emin, double emax) {
  thread_local std::unique_ptr<Marks> marks;
  if (!marks || !marks->fits(mesh)) marks = std::make_unique<Marks>(mesh);
  if (!variables.empty()) optimize_region(mesh, variables, emin, emax, 1.0, *marks);
}

NonlinearResult nonlinear_optimizer(TriMesh& mesh, int kn, double emin, double emax) {
  const double m = 0.5 * (emin + emax);
  NonlinearResult result;
  std::vector<char> is_troubling(mesh.n_edges(), 0);
  std::vector<int> list;
  for (auto e : mesh.edges()) {
    if (mesh.status(e).deleted() || !troubling(mesh, e, emin, emax)) continue;
    is_troubling[static_cast<std::size_t>(e.idx())] = 1;
    list.push_back(e.idx());
  }
  result.troubling = list.size();
  if (list.empty()) return result;
  Marks marks(mesh);
  EdgeStar star;
  std::vector<std::pair<int, int>> ordered;  // (priority, edge)
  for (int e : list) {
    collect_edge_star(mesh, TriMesh::EdgeHandle(e), kn, star, marks);
    ordered.emplace_back(priority(mesh, star, kn, is_troubling, marks), e);
  }
  std::sort(ordered.begin(), ordered.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  });
  std::vector<VH> variables;
  for (const auto& [p, index] : ordered) {
    const TriMesh::EdgeHandle e(index);
    if (!troubling(mesh, e, emin, emax)) continue;
    // Border ends first go through the border optimizer of section 4.3.2 (Eq 4.1 along their border curve).
    const auto h = mesh.halfedge_handle(e, 0);
    for (VH v : {mesh.from_vertex_handle(h), mesh.to_vertex_handle(h)})
      if (mesh.is_boundary(v)) border_optimizer(mesh, v, m);
    // Eq 4.7 on the kn-star; if the edge is still outside, again on a star one larger with the edges
    // outside the interval weighted up.
    for (int attempt = 0; attempt < 2 && troubling(mesh, e, emin, emax); ++attempt) {
      const int k = kn + attempt;
      collect_edge_star(mesh, e, k, star, marks);
      variables.clear();
      geometry::BorderCurve curve;
      for (std::size_t i = 0; i < star.vertices.size() && star.ring[i] < k; ++i)
        if (!mesh.is_boundary(star.vertices[i]) || border_curve(mesh, star.vertices[i], curve))
          variables.push_back(star.vertices[i]);
      if (variables.empty()) break;
      optimize_region(mesh, variables, emin, emax, attempt == 0 ? 1.0 : 10.0, marks);
      ++result.regions;
    }
  }
  return result;
}

}  // namespace carbonmesh
