// Least-squares fit of the remeshed surface to the input (after Algorithm 1; not in the dissertation).
//
// With every vertex on the input, a flat triangle over a curved input lies wholly on one side of it, and a
// crease or corner of the input lies between the vertices: the remeshed surface cuts it. Each round moves every
// vertex by a displacement d_i in space so that the squared distance between the two surfaces, both ways, is
// least: quadrature points of the triangles to the input and quadrature points of the input to the triangles,
// each linearised along the normal of the face it is measured to. The second sum is what slides vertices along
// the surface onto the input's creases; a penalty on the length change of every edge keeps the triangles'
// shape, and a light Tikhonov term keeps unconstrained vertices put. The sparse normal equations (3x3 blocks)
// are solved by conjugate gradients. Edges the displacements take out of [emin, emax] are then moved back into
// it along themselves (Gauss-Seidel sweeps), and finally any edge still outside has its ends' displacements
// halved, then undone, so the interval guarantee of remesh() is kept. Border vertices stay where they are.
//
// Measured on the seed-protocol models remeshed into [1.2, 1.8] (Hausdorff to the input; this fit against the
// one before it, which moved each vertex along its normal, fitted one side, at three points per face): bunny RMS
// 0.0419 -> 0.0323, max 0.5211 -> 0.4181. Every model's figures are in docs/benchmarks.md, what was tried in
// docs/algorithm.md.
#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include "carbonmesh/remesh/remesh_steps.hpp"
#include "carbonmesh/remesh/triangle_tree.hpp"
#include "remesh_geometry.hpp"

namespace carbonmesh {
namespace {

using namespace triangle_tree;

// The degree-2 rule with three interior points (weights 1/3), exact for quadratics, on each of the four
// triangles of a face's midpoint subdivision: 12 points of equal weight. The distance to a piecewise flat surface
// has kinks inside a face; the finer points follow them (with 3 points the fit's own RMS read 15% under the
// measured one on bunny, with 12 they agree).
constexpr std::array<std::array<double, 3>, 12> make_quadrature() {
  constexpr double h = 0.5;
  constexpr std::array<std::array<std::array<double, 3>, 3>, 4> sub = {{
      {{{1, 0, 0}, {h, h, 0}, {h, 0, h}}},
      {{{h, h, 0}, {0, 1, 0}, {0, h, h}}},
      {{{h, 0, h}, {0, h, h}, {0, 0, 1}}},
      {{{h, h, 0}, {0, h, h}, {h, 0, h}}},
  }};
  std::array<std::array<double, 3>, 12> out{};
  for (std::size_t t = 0; t < 4; ++t)
    for (std::size_t q = 0; q < 3; ++q)
      for (std::size_t j = 0; j < 3; ++j) {
        double b = 0;
        for (std::size_t c = 0; c < 3; ++c) b += (c == q ? 2.0 / 3 : 1.0 / 6) * sub[t][c][j];
        out[3 * t + q][j] = b;
      }
  return out;
}
constexpr std::array<std::array<double, 3>, 12> kQuadrature = make_quadrature();
constexpr std::size_t kPoints = kQuadrature.size();
// The input's side: the degree-2 rule on the face itself. With 12 points there too, bunny's RMS is 0.0315 instead
// of 0.0323 (fertility 0.0211 instead of 0.0215) at four times the searches (armadillo's fit 5.0 -> 3.9 s).
constexpr std::array<std::array<double, 3>, 3> kInputQuadrature = {
    {{2.0 / 3, 1.0 / 6, 1.0 / 6}, {1.0 / 6, 2.0 / 3, 1.0 / 6}, {1.0 / 6, 1.0 / 6, 2.0 / 3}}};

// One term of the sum: the point of face `face` at barycentric coordinates `bary` is `residual` from the other
// surface along `direction`; moving the face's corner k by d_k changes the residual by bary_k (direction . d_k).
struct Sample {
  int face = -1;
  std::array<double, 3> bary{};
  Vec3 direction{0, 0, 0};
  double weight = 0;  // its face's area over the face's number of points
  double residual = 0;
};

// The faces of the mesh in a fixed order, with their corners (in fv order) and their triangles.
struct Faces {
  std::vector<std::array<int, 3>> corners;
  Triangles triangles;
};

Faces faces_of(const TriMesh& mesh) {
  Faces out;
  out.corners.reserve(mesh.n_faces());
  for (auto f : mesh.faces()) {  // the order of triangles_of
    std::array<int, 3> v{};
    int k = 0;
    for (auto w : mesh.fv_range(f)) v[static_cast<std::size_t>(k++)] = w.idx();
    out.corners.push_back(v);
  }
  out.triangles = triangles_of(mesh);
  return out;
}

// The closest input point of each sample of the previous evaluation: the hint of the next search.
using Hints = std::vector<Tree::Point_and_primitive_id>;

// The mesh's side of face i: its quadrature points to the input, along the normal of the closest input face.
// hints[kPoints i + q] holds point q's closest input point of the last evaluation, the start of the next search;
// without one (hinted false), the face's previous point gives one (it is near).
std::array<Sample, kPoints> face_samples(const Faces& faces, std::size_t i, const Tree& input, Hints& hints,
                                         bool hinted) {
  const Triangle& t = faces.triangles[i];
  const Vec3 p0 = to_vec(t[0]), p1 = to_vec(t[1]), p2 = to_vec(t[2]);
  const Vec3 face_normal = geometry::triangle_normal(p0, p1, p2);
  const double weight = geometry::triangle_area(p0, p1, p2) / static_cast<double>(kPoints);
  std::array<Sample, kPoints> samples;
  std::array<Point, kPoints> points;
  for (std::size_t q = 0; q < kPoints; ++q) {
    const auto& b = kQuadrature[q];
    points[q] = to_point(b[0] * p0 + b[1] * p1 + b[2] * p2);
  }
  if (hinted) {  // the face's points from their last closest points, with one box search (the tree's results)
    thread_local std::vector<Tree::Primitive_id> listed;
    closest_points_from_hints(input, points.data(), hints.data() + kPoints * i, kPoints, listed);
  }
  for (std::size_t q = 0; q < kPoints; ++q) {
    const auto& b = kQuadrature[q];
    const Vec3 x = to_vec(points[q]);
    const std::size_t slot = kPoints * i + q;
    auto& hint = hints[slot];
    if (!hinted) {
      if (q > 0) hint = input.closest_point_and_primitive(points[q], hints[slot - 1]);
      else hint = input.closest_point_and_primitive(points[q]);
    }
    const auto& [closest, primitive] = hint;
    const Triangle& s = *primitive;
    Vec3 ns = to_vec(CGAL::ORIGIN + CGAL::cross_product(s[1] - s[0], s[2] - s[0]));
    const double l = ns.norm();
    ns = l > 0 ? ns / l : face_normal;
    if (OpenMesh::dot(ns, face_normal) < 0) ns = -ns;
    samples[q] = {static_cast<int>(i), b, ns, weight, OpenMesh::dot(x - to_vec(closest), ns)};
  }
  return samples;
}

// Sizes the hints for the faces; true if they hold the last evaluation's points.
bool prepare_hints(const Faces& faces, Hints& hints) {
  const std::size_t size = kPoints * faces.triangles.size();
  if (hints.size() == size) return true;
  hints.resize(size);
  return false;
}

// The sum of w r^2 and of w over a set of samples.
struct Sums {
  double squared = 0, weight = 0;
  void add(const Sample& s) {
    squared += s.weight * s.residual * s.residual;
    weight += s.weight;
  }
  void add(const Sums& o) {
    squared += o.squared;
    weight += o.weight;
  }
  double rms() const { return weight > 0 ? std::sqrt(squared / weight) : 0.0; }
};

// The area-weighted RMS distance of the mesh's quadrature points to the input (parallel over faces, summed in face
// order: the result does not depend on the thread count).
double mesh_rms(const Faces& faces, const Tree& input, Hints& hints) {
  const bool hinted = prepare_hints(faces, hints);
  std::vector<Sums> sums(faces.triangles.size());
  const int n = static_cast<int>(sums.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (int i = 0; i < n; ++i)
    for (const Sample& s : face_samples(faces, static_cast<std::size_t>(i), input, hints, hinted))
      sums[static_cast<std::size_t>(i)].add(s);
  Sums total;
  for (const Sums& face : sums) total.add(face);
  return total.rms();
}

// The input's side: its quadrature points (fixed: the input does not move).
struct InputPoint {
  Vec3 position;
  double weight = 0;
};

std::vector<InputPoint> input_points(const Triangles& triangles) {
  std::vector<InputPoint> points;
  points.reserve(kInputQuadrature.size() * triangles.size());
  for (const Triangle& t : triangles) {
    const Vec3 a = to_vec(t[0]), b = to_vec(t[1]), c = to_vec(t[2]);
    const double weight = geometry::triangle_area(a, b, c) / static_cast<double>(kInputQuadrature.size());
    for (const auto& q : kInputQuadrature) points.push_back({q[0] * a + q[1] * b + q[2] * c, weight});
  }
  return points;
}

// ... to the mesh, along the normal of the closest face (a tree of the mesh as it is now; parallel over points).
// `previous`, the samples of the last evaluation on the same faces, gives each search its start: the point of
// the face it found then, at the same barycentric coordinates.
std::vector<Sample> input_samples(const Faces& faces, const std::vector<InputPoint>& points,
                                  const std::vector<Sample>& previous) {
  std::vector<Sample> samples(points.size());
  if (faces.triangles.empty()) return samples;
  Tree tree(faces.triangles.begin(), faces.triangles.end());
  tree.build();
  const bool hinted = previous.size() == points.size();
  if (!hinted) tree.accelerate_distance_queries();
  const int n = static_cast<int>(points.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (int i = 0; i < n; ++i) {
    const InputPoint& y = points[static_cast<std::size_t>(i)];
    Tree::Point_and_primitive_id found;
    if (hinted) {
      const Sample& last = previous[static_cast<std::size_t>(i)];
      const auto face = faces.triangles.begin() + last.face;
      const Vec3 start = last.bary[0] * to_vec((*face)[0]) + last.bary[1] * to_vec((*face)[1]) +
                         last.bary[2] * to_vec((*face)[2]);
      found = tree.closest_point_and_primitive(to_point(y.position), {to_point(start), face});
    } else {
      found = tree.closest_point_and_primitive(to_point(y.position));
    }
    const auto& [closest, primitive] = found;
    const Triangle& t = *primitive;
    const Vec3 a = to_vec(t[0]), b = to_vec(t[1]), c = to_vec(t[2]), x = to_vec(closest);
    const Vec3 nf = geometry::triangle_normal(a, b, c);
    samples[static_cast<std::size_t>(i)] = {static_cast<int>(primitive - faces.triangles.begin()),
                                            geometry::barycentric(x, a, b, c), nf, y.weight,
                                            OpenMesh::dot(x - y.position, nf)};
  }
  return samples;
}

double weighted_rms(const std::vector<Sample>& samples) {
  Sums sums;
  for (const Sample& s : samples) sums.add(s);
  return sums.rms();
}

using Block = std::array<double, 9>;  // row-major 3x3

// The normal equations in 3x3 blocks: row i holds vertex i and its neighbours, in increasing index order.
class BlockSystem {
 public:
  explicit BlockSystem(const TriMesh& mesh) : start_(mesh.n_vertices() + 1, 0) {
    for (auto v : mesh.all_vertices()) {
      std::vector<int> row{v.idx()};
      if (!mesh.status(v).deleted())
        for (auto w : mesh.vv_range(v)) row.push_back(w.idx());
      std::sort(row.begin(), row.end());
      column_.insert(column_.end(), row.begin(), row.end());
      start_[static_cast<std::size_t>(v.idx()) + 1] = column_.size();
    }
    clear();
  }

  // Every block and right side zero again (the pattern stays: the fit changes no connectivity).
  void clear() {
    blocks_.assign(column_.size(), Block{});
    rhs_ = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(start_.size() - 1));
  }

  Block& block(int i, int j) {
    const auto first = column_.begin() + static_cast<std::ptrdiff_t>(start_[static_cast<std::size_t>(i)]);
    const auto last = column_.begin() + static_cast<std::ptrdiff_t>(start_[static_cast<std::size_t>(i) + 1]);
    return blocks_[static_cast<std::size_t>(std::lower_bound(first, last, j) - column_.begin())];
  }
  double& rhs(int i, int c) { return rhs_[3 * i + c]; }

  // The assembled matrix, compressed row-major (3 rows per vertex), written in place: the rows' columns are
  // already in order.
  Eigen::SparseMatrix<double, Eigen::RowMajor> matrix() const {
    const std::size_t vertices = start_.size() - 1;
    const auto rows = static_cast<Eigen::Index>(3 * vertices);
    Eigen::SparseMatrix<double, Eigen::RowMajor> a(rows, rows);
    a.resizeNonZeros(static_cast<Eigen::Index>(9 * column_.size()));
    int* outer = a.outerIndexPtr();
    int* inner = a.innerIndexPtr();
    double* value = a.valuePtr();
    std::size_t k = 0;
    for (std::size_t i = 0; i < vertices; ++i)
      for (int r = 0; r < 3; ++r) {
        outer[3 * i + static_cast<std::size_t>(r)] = static_cast<int>(k);
        for (std::size_t p = start_[i]; p < start_[i + 1]; ++p)
          for (int c = 0; c < 3; ++c, ++k) {
            inner[k] = 3 * column_[p] + c;
            value[k] = blocks_[p][static_cast<std::size_t>(3 * r + c)];
          }
      }
    outer[3 * vertices] = static_cast<int>(k);
    return a;
  }
  const Eigen::VectorXd& rhs() const { return rhs_; }

  // Block-Jacobi scaling: with L_i the Cholesky factor of vertex i's diagonal block, the system becomes
  // L_i^-1 A_ij L_j^-T y_j = L_i^-1 b_i, whose diagonal blocks are the identity (conjugate gradients then need
  // fewer iterations); unscale() maps y back to d_i = L_i^-T y_i.
  void scale() {
    const std::size_t vertices = start_.size() - 1;
    factor_.resize(vertices);
    for (std::size_t i = 0; i < vertices; ++i)
      factor_[i] = Eigen::Map<const Eigen::Matrix3d>(block(static_cast<int>(i), static_cast<int>(i)).data())
                       .llt()
                       .matrixL();
    for (std::size_t i = 0; i < vertices; ++i) {
      const auto li = factor_[i].triangularView<Eigen::Lower>();
      for (std::size_t p = start_[i]; p < start_[i + 1]; ++p) {
        Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> a(blocks_[p].data());
        const Eigen::Matrix3d left = li.solve(Eigen::Matrix3d(a));
        const auto lj = factor_[static_cast<std::size_t>(column_[p])].triangularView<Eigen::Lower>();
        a = lj.solve(left.transpose()).transpose();
      }
      rhs_.segment<3>(3 * static_cast<Eigen::Index>(i)) = li.solve(rhs_.segment<3>(3 * static_cast<Eigen::Index>(i)));
    }
  }
  Eigen::VectorXd unscale(const Eigen::VectorXd& y) const {
    Eigen::VectorXd d(y.size());
    for (std::size_t i = 0; i < factor_.size(); ++i)
      d.segment<3>(3 * static_cast<Eigen::Index>(i)) =
          factor_[i].transpose().triangularView<Eigen::Upper>().solve(y.segment<3>(3 * static_cast<Eigen::Index>(i)));
    return d;
  }

 private:
  std::vector<std::size_t> start_;
  std::vector<int> column_;
  std::vector<Block> blocks_;
  Eigen::VectorXd rhs_;
  std::vector<Eigen::Matrix3d> factor_;
};

// One face's share of the normal equations: the blocks (a, b) of its corners and their right sides.
struct FaceTerms {
  std::array<Block, 9> block{};  // corner a, corner b: block[3 a + b]
  std::array<double, 9> rhs{};   // corner a, coordinate c: rhs[3 a + c]
};

// Adds w g g^T and -w r g, g_(k,c) = bary_k direction_c, to a face's terms.
void add_sample(FaceTerms& terms, const Sample& s) {
  Block dd;
  for (std::size_t r = 0; r < 3; ++r)
    for (std::size_t c = 0; c < 3; ++c) dd[3 * r + c] = s.weight * s.direction[r] * s.direction[c];
  for (std::size_t a = 0; a < 3; ++a) {
    for (std::size_t c = 0; c < 3; ++c) terms.rhs[3 * a + c] -= s.weight * s.residual * s.bary[a] * s.direction[c];
    for (std::size_t b = 0; b < 3; ++b) {
      const double ab = s.bary[a] * s.bary[b];
      for (std::size_t k = 0; k < 9; ++k) terms.block[3 * a + b][k] += ab * dd[k];
    }
  }
}

// The terms of both sides added to the system: computed per face in parallel (the face's own quadrature points,
// evaluated here, and the input's points closest to it), a chunk of faces at a time, and added in face order (the
// sums do not depend on the thread count); the corners that stay get none. Returns the mesh side's sums.
Sums add_samples(BlockSystem& system, const Faces& faces, const Tree& input, Hints& hints,
                 const std::vector<Sample>& backward, const std::vector<char>& moves) {
  const std::size_t count = faces.corners.size();
  std::vector<std::size_t> first(count + 1, 0), order(backward.size());  // the input samples by face
  for (const Sample& s : backward) ++first[static_cast<std::size_t>(s.face) + 1];
  for (std::size_t f = 0; f < count; ++f) first[f + 1] += first[f];
  {
    std::vector<std::size_t> next(first.begin(), first.end() - 1);
    for (std::size_t i = 0; i < backward.size(); ++i) order[next[static_cast<std::size_t>(backward[i].face)]++] = i;
  }
  const bool hinted = prepare_hints(faces, hints);
  constexpr std::size_t kChunk = 4096;
  std::vector<FaceTerms> terms(std::min(kChunk, count));
  std::vector<Sums> sums(terms.size());
  Sums total;
  for (std::size_t begin = 0; begin < count; begin += kChunk) {
    const int size = static_cast<int>(std::min(kChunk, count - begin));
#pragma omp parallel for schedule(dynamic, 64)
    for (int j = 0; j < size; ++j) {
      const std::size_t f = begin + static_cast<std::size_t>(j);
      FaceTerms& t = terms[static_cast<std::size_t>(j)];
      t = FaceTerms{};
      sums[static_cast<std::size_t>(j)] = Sums{};
      for (const Sample& s : face_samples(faces, f, input, hints, hinted)) {
        add_sample(t, s);
        sums[static_cast<std::size_t>(j)].add(s);
      }
      for (std::size_t k = first[f]; k < first[f + 1]; ++k) add_sample(t, backward[order[k]]);
    }
    for (std::size_t j = 0; j < static_cast<std::size_t>(size); ++j) {
      total.add(sums[j]);
      const auto& corner = faces.corners[begin + j];
      const FaceTerms& t = terms[j];
      for (std::size_t a = 0; a < 3; ++a) {
        if (!moves[static_cast<std::size_t>(corner[a])]) continue;
        for (std::size_t c = 0; c < 3; ++c) system.rhs(corner[a], static_cast<int>(c)) += t.rhs[3 * a + c];
        for (std::size_t b = 0; b < 3; ++b) {
          if (!moves[static_cast<std::size_t>(corner[b])]) continue;
          Block& block = system.block(corner[a], corner[b]);
          for (std::size_t k = 0; k < 9; ++k) block[k] += t.block[3 * a + b][k];
        }
      }
    }
  }
  return total;
}

// The edge terms: stiffness (|e| - |e_start| + u_e . (d_j - d_i))^2 for every edge (i, j), u_e its direction,
// keeps its length near its length at the start (and the triangles' shape).
void add_edge_terms(BlockSystem& system, const TriMesh& mesh, const std::vector<Vec3>& start,
                    const std::vector<char>& moves, double stiffness) {
  for (auto e : mesh.edges()) {
    if (mesh.status(e).deleted()) continue;
    const auto h = mesh.halfedge_handle(e, 0);
    const int i = mesh.from_vertex_handle(h).idx(), j = mesh.to_vertex_handle(h).idx();
    const std::size_t ui = static_cast<std::size_t>(i), uj = static_cast<std::size_t>(j);
    Vec3 u = mesh.point(TriMesh::VertexHandle(j)) - mesh.point(TriMesh::VertexHandle(i));
    const double length = u.norm();
    if (length <= 0) continue;
    u /= length;
    const double residual = length - (start[uj] - start[ui]).norm();
    const std::array<int, 2> ends = {j, i};
    const std::array<double, 2> sign = {1.0, -1.0};  // d(residual)/d(d_j) = u, d/d(d_i) = -u
    const std::array<bool, 2> end_moves = {moves[uj] != 0, moves[ui] != 0};
    for (std::size_t a = 0; a < 2; ++a) {
      if (!end_moves[a]) continue;
      for (int c = 0; c < 3; ++c) system.rhs(ends[a], c) -= stiffness * residual * sign[a] * u[c];
      for (std::size_t b = 0; b < 2; ++b) {
        if (!end_moves[b]) continue;
        Block& block = system.block(ends[a], ends[b]);
        const double w = stiffness * sign[a] * sign[b];
        for (std::size_t r = 0; r < 3; ++r)
          for (std::size_t c = 0; c < 3; ++c) block[3 * r + c] += w * u[static_cast<int>(r)] * u[static_cast<int>(c)];
      }
    }
  }
}

// True if the fit took the edge of halfedge h out of [emin, emax]: outside now, inside at `start` (an edge that was
// outside already is not the fit's doing).
bool left_interval(const TriMesh& mesh, TriMesh::HalfedgeHandle h, const std::vector<Vec3>& start, double emin,
                   double emax) {
  const auto v0 = mesh.from_vertex_handle(h), v1 = mesh.to_vertex_handle(h);
  const double now = (mesh.point(v1) - mesh.point(v0)).norm();
  if (now >= emin && now <= emax) return false;
  const double before =
      (start[static_cast<std::size_t>(v0.idx())] - start[static_cast<std::size_t>(v1.idx())]).norm();
  return before >= emin && before <= emax;
}

// Moves the ends of every edge that was inside [emin, emax] at `start` and is not now back inside it, along the
// edge, in edge order (Gauss-Seidel); a fixed end stays. Returns the sweeps made. After the first sweep an edge is
// looked at again only if an end of it moved since it was last looked at (else nothing it depends on changed, and it
// would be left as it was): the same moves in the same order as sweeping every edge, without reading every edge of
// the mesh again on each of bunny's 35 sweeps.
int settle_edges(TriMesh& mesh, const std::vector<Vec3>& start, double emin, double emax,
                 const std::vector<char>& moves, int sweeps) {
  const double margin = (emax - emin) / 60;  // 0.01 inside the bounds of [1.2, 1.8]
  // Edges to look at in this sweep (a min-heap of indices: ends moved by an earlier edge of this sweep add later
  // ones) and in the next (ends moved at or after their place in this sweep).
  std::vector<int> now, next;
  std::vector<char> in_now(mesh.n_edges(), 1), in_next(mesh.n_edges(), 0);  // (deleted edges are never listed)
  for (auto e : mesh.edges())
    if (!mesh.status(e).deleted()) now.push_back(e.idx());  // (in order: a heap already)
  auto moved = [&](TriMesh::VertexHandle v, int position) {
    geometry::for_each_outgoing(mesh, v, [&](TriMesh::HalfedgeHandle h) {
      const int f = mesh.edge_handle(h).idx();
      const auto uf = static_cast<std::size_t>(f);
      if (f > position) {
        if (!in_now[uf]) in_now[uf] = 1, now.push_back(f), std::push_heap(now.begin(), now.end(), std::greater<>());
      } else if (!in_next[uf]) {
        in_next[uf] = 1, next.push_back(f);
      }
    });
  };
  int sweep = 0;
  for (; sweep < sweeps; ++sweep) {
    bool any = false;
    while (!now.empty()) {
      std::pop_heap(now.begin(), now.end(), std::greater<>());
      const int index = now.back();
      now.pop_back();
      in_now[static_cast<std::size_t>(index)] = 0;
      const TriMesh::EdgeHandle e(index);
      const auto h = mesh.halfedge_handle(e, 0);
      if (!left_interval(mesh, h, start, emin, emax)) continue;
      const auto v0 = mesh.from_vertex_handle(h), v1 = mesh.to_vertex_handle(h);
      Vec3 u = mesh.point(v1) - mesh.point(v0);
      const double length = u.norm();
      if (length <= 0) continue;
      const std::size_t i0 = static_cast<std::size_t>(v0.idx()), i1 = static_cast<std::size_t>(v1.idx());
      const bool m0 = moves[i0] != 0, m1 = moves[i1] != 0;
      if (!m0 && !m1) continue;
      u /= length;
      const double excess = length - std::clamp(length, emin + margin, emax - margin);
      if (m0 && m1) {
        mesh.set_point(v0, mesh.point(v0) + 0.5 * excess * u);
        mesh.set_point(v1, mesh.point(v1) - 0.5 * excess * u);
      } else if (m0) {
        mesh.set_point(v0, mesh.point(v0) + excess * u);
      } else {
        mesh.set_point(v1, mesh.point(v1) - excess * u);
      }
      if (m0) moved(v0, index);
      if (m1) moved(v1, index);
      any = true;
    }
    if (!any) break;
    std::sort(next.begin(), next.end());  // (a heap)
    now.swap(next);
    next.clear();
    for (const int f : now) in_next[static_cast<std::size_t>(f)] = 0, in_now[static_cast<std::size_t>(f)] = 1;
  }
  return sweep;
}

// Keeps every edge that was inside [emin, emax] at `start` inside: halves the displacements of the ends of an
// edge outside, and after a few rounds undoes them. Undoing one end can take its other edges out: it repeats
// until none is. Each such round undoes at least one moved vertex (an edge with both ends at their start is as
// long as it was), so it ends. Returns the halvings and undoings.
std::size_t keep_interval(TriMesh& mesh, const std::vector<Vec3>& start, const std::vector<char>& moves,
                          double emin, double emax) {
  constexpr int kHalvings = 8;
  std::size_t limited = 0;
  for (int round = 0;; ++round) {
    std::vector<char> shrink(start.size(), 0);
    bool any = false;
    for (auto e : mesh.edges()) {
      if (mesh.status(e).deleted()) continue;
      const auto h = mesh.halfedge_handle(e, 0);
      if (!left_interval(mesh, h, start, emin, emax)) continue;
      shrink[static_cast<std::size_t>(mesh.from_vertex_handle(h).idx())] = 1;
      shrink[static_cast<std::size_t>(mesh.to_vertex_handle(h).idx())] = 1;
      any = true;
    }
    if (!any) return limited;
    for (auto v : mesh.vertices()) {
      const std::size_t i = static_cast<std::size_t>(v.idx());
      if (!shrink[i] || !moves[i]) continue;
      ++limited;
      mesh.set_point(v, round >= kHalvings ? start[i] : start[i] + 0.5 * (mesh.point(v) - start[i]));
    }
  }
}

}  // namespace

SurfaceFitResult fit_to_surface(TriMesh& mesh, const TriMesh& surface, double emin, double emax,
                                const SurfaceFitSettings& settings, const std::vector<char>* fixed,
                                const SurfaceTree* surface_tree) {
  SurfaceFitResult result;
  if (surface.n_faces() == 0 || mesh.n_faces() == 0) return result;
  std::optional<SurfaceTree> own;
  const SurfaceTree& input = surface_tree ? *surface_tree : own.emplace(surface);
  const std::vector<InputPoint> points = input_points(input.triangles());
  const std::size_t n = mesh.n_vertices();
  std::vector<Vec3> start(n);
  std::vector<char> moves(n, 0);  // border, isolated, deleted and fixed vertices stay
  for (auto v : mesh.all_vertices()) {
    const std::size_t i = static_cast<std::size_t>(v.idx());
    start[i] = mesh.point(v);
    moves[i] = !mesh.status(v).deleted() && !mesh.is_isolated(v) && !mesh.is_boundary(v) &&
               !(fixed != nullptr && (*fixed)[i] != 0);
  }
  const double max_offset = settings.max_offset * emin;

  Hints hints;
  std::vector<Sample> backward;
  BlockSystem system(mesh);
  for (int round = 0; round < settings.rounds; ++round) {
    const Faces faces = faces_of(mesh);
    backward = input_samples(faces, points, backward);
    // Normal equations of min sum_s w_s (r_s + g_s . d)^2 + sum_edges mu w (|e| - |e_start| + u_e . d)^2
    // + lambda w |d|^2, w the mean weight of the mesh's samples.
    system.clear();
    const Sums forward = add_samples(system, faces, input.tree(), hints, backward, moves);
    if (round == 0) {
      result.rms_before = forward.rms();
      result.input_rms_before = weighted_rms(backward);
    }
    const double mean_weight =
        forward.weight / static_cast<double>(std::max<std::size_t>(1, kPoints * faces.corners.size()));
    add_edge_terms(system, mesh, start, moves, settings.edge_stiffness * mean_weight);
    for (std::size_t i = 0; i < n; ++i) {  // Tikhonov term; a vertex that stays has only it (and no right side)
      Block& block = system.block(static_cast<int>(i), static_cast<int>(i));
      for (int c = 0; c < 3; ++c) block[static_cast<std::size_t>(4 * c)] += 1e-3 * mean_weight;
    }
    system.scale();
    const Eigen::SparseMatrix<double, Eigen::RowMajor> a = system.matrix();
    Eigen::ConjugateGradient<Eigen::SparseMatrix<double, Eigen::RowMajor>, Eigen::Lower | Eigen::Upper> solver;
    solver.setTolerance(1e-6);
    solver.setMaxIterations(1000);
    solver.compute(a);
    const Eigen::VectorXd d = system.unscale(solver.solve(system.rhs()));
    result.solver_iterations += static_cast<std::size_t>(solver.iterations());
    if (!d.allFinite()) break;
    for (auto v : mesh.vertices()) {
      const std::size_t i = static_cast<std::size_t>(v.idx());
      if (!moves[i]) continue;
      const auto k = static_cast<Eigen::Index>(3 * i);
      Vec3 offset = mesh.point(v) + Vec3(d[k], d[k + 1], d[k + 2]) - start[i];
      const double length = offset.norm();
      if (length > max_offset) offset *= max_offset / length;
      mesh.set_point(v, start[i] + offset);
    }
    const int sweeps = settle_edges(mesh, start, emin, emax, moves, settings.settle_sweeps);
    result.settle_sweeps += static_cast<std::size_t>(sweeps);
  }

  result.limited = keep_interval(mesh, start, moves, emin, emax);
  const Faces faces = faces_of(mesh);
  result.rms_after = mesh_rms(faces, input.tree(), hints);
  if (settings.measure_input_after) result.input_rms_after = weighted_rms(input_samples(faces, points, backward));
  return result;
}

}  // namespace carbonmesh
