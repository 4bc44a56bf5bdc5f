// The Goldberg-Coxeter sphere (h, k): the triangular lattice folded onto the icosahedron (carbonmesh/remesh/shapes.hpp).
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>
#include <utility>
#include <vector>

#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/shapes.hpp"
#include "icosahedral.hpp"

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

namespace {

// Every icosahedron face is the same lattice triangle O = (0, 0), P = (h, k), Q = (-k, h + k) in lattice coordinates
// (i, j) for i e1 + j e2. The weights of a point on the corners O, P, Q, times T, are integers for a lattice point
// (times 3 T for a triangle's centroid): w_P = det(x, Q), w_Q = det(P, x), w_O = T - w_P - w_Q.
struct Frame {
  long h, k, T;
  std::array<long, 3> weights(long i, long j, long scale) const {  // of the point (i, j) / scale, times scale T
    const long wp = i * (h + k) + j * k, wq = h * j - k * i;
    return {scale * T - wp - wq, wp, wq};
  }
};

class Folding {
 public:
  Folding(long h, long k) : frame_{h, k, h * h + h * k + k * k}, g_(std::gcd(h, k)) {
    std::tie(corners_, faces_) = icosahedral::icosahedron();
    for (int f = 0; f < 20; ++f)
      for (int c = 0; c < 3; ++c) {
        const auto key = std::minmax(faces_[static_cast<std::size_t>(f)][static_cast<std::size_t>(c)],
                                     faces_[static_cast<std::size_t>(f)][static_cast<std::size_t>((c + 1) % 3)]);
        const auto [it, added] = edges_.try_emplace({key.first, key.second}, Edge{static_cast<int>(edges_.size()), -1, -1});
        (added ? it->second.left : it->second.right) = f;
      }
    // The lattice points strictly inside the master triangle, ranked row by row.
    i0_ = -k, width_ = h + k + 1, height_ = h + k + 1;
    rank_.assign(static_cast<std::size_t>(width_ * height_), -1);
    for (long j = 0; j < height_; ++j)
      for (long i = i0_; i < i0_ + width_; ++i) {
        const auto w = frame_.weights(i, j, 1);
        if (w[0] > 0 && w[1] > 0 && w[2] > 0) rank_[static_cast<std::size_t>(j * width_ + (i - i0_))] = inner_++;
      }
  }

  std::size_t vertex_count() const { return static_cast<std::size_t>(12 + 30 * (g_ - 1) + 20 * inner_); }

  // The points on the unit sphere, by vertex index.
  std::vector<Vec3> points() const {
    std::vector<Vec3> out(vertex_count());
    for (std::size_t v = 0; v < 12; ++v) out[v] = corners_[v];
    for (const auto& [key, edge] : edges_)
      for (long s = 1; s < g_; ++s)
        out[static_cast<std::size_t>(12 + edge.index * (g_ - 1) + (s - 1))] = icosahedral::slerp(
            corners_[static_cast<std::size_t>(key.first)], corners_[static_cast<std::size_t>(key.second)],
            static_cast<double>(s) / static_cast<double>(g_));
    const double T = static_cast<double>(frame_.T);
    for (std::size_t f = 0; f < 20; ++f) {
      const auto& t = faces_[f];
      for (long j = 0; j < height_; ++j)
        for (long i = i0_; i < i0_ + width_; ++i) {
          const long r = rank_[static_cast<std::size_t>(j * width_ + (i - i0_))];
          if (r < 0) continue;
          const auto w = frame_.weights(i, j, 1);
          out[static_cast<std::size_t>(inner_base() + static_cast<long>(f) * inner_ + r)] = icosahedral::spherical_point(
              corners_[static_cast<std::size_t>(t[0])], corners_[static_cast<std::size_t>(t[1])],
              corners_[static_cast<std::size_t>(t[2])], static_cast<double>(w[0]) / T,
              static_cast<double>(w[1]) / T, static_cast<double>(w[2]) / T);
        }
    }
    return out;
  }

  // The lattice triangles, counter-clockwise seen from outside: those whose centroid lies inside an icosahedron face,
  // a centroid on an edge taken by the face of smaller index.
  std::vector<std::array<int, 3>> triangles() const {
    std::vector<std::array<int, 3>> out;
    out.reserve(static_cast<std::size_t>(20 * frame_.T));
    for (int f = 0; f < 20; ++f)
      for (long j = -1; j < height_; ++j)
        for (long i = i0_ - 1; i < i0_ + width_; ++i) {
          add_if_inside(out, f, {i, j, i + 1, j, i, j + 1}, frame_.weights(3 * i + 1, 3 * j + 1, 3));
          add_if_inside(out, f, {i + 1, j, i + 1, j + 1, i, j + 1}, frame_.weights(3 * i + 2, 3 * j + 2, 3));
        }
    return out;
  }

 private:
  struct Edge {
    int index, left, right;  // the faces on either side
  };

  long inner_base() const { return 12 + 30 * (g_ - 1); }

  int other_face(int u, int w, int f) const {
    const Edge& e = edges_.at(std::minmax(u, w));
    return e.left == f ? e.right : e.left;
  }

  void add_if_inside(std::vector<std::array<int, 3>>& out, int f, const std::array<long, 6>& corners,
                     const std::array<long, 3>& centroid) const {
    const auto& t = faces_[static_cast<std::size_t>(f)];
    for (std::size_t c = 0; c < 3; ++c) {
      if (centroid[c] < 0) return;
      // On the edge opposite corner c: the face of smaller index takes it.
      if (centroid[c] == 0 && other_face(t[(c + 1) % 3], t[(c + 2) % 3], f) < f) return;
    }
    out.push_back({vertex(f, corners[0], corners[1]), vertex(f, corners[2], corners[3]),
                   vertex(f, corners[4], corners[5])});
  }

  // The vertex index of lattice point (i, j) of face f's frame: inside or on face f, or across one of its edges (a
  // triangle whose centroid lies inside f reaches no farther).
  int vertex(int f, long i, long j) const {
    const auto& t = faces_[static_cast<std::size_t>(f)];
    const auto w = frame_.weights(i, j, 1);
    int face = f;
    std::array<long, 3> weights = w;
    for (std::size_t c = 0; c < 3; ++c) {
      if (w[c] >= 0) continue;
      // Across the edge (u, x) opposite corner c, in the face g on the other side, whose third corner lies at
      // u + x - c in f's frame: the weights u + c, x + c and -c.
      const int u = t[(c + 1) % 3], x = t[(c + 2) % 3];
      face = other_face(u, x, f);
      const auto& s = faces_[static_cast<std::size_t>(face)];
      for (std::size_t d = 0; d < 3; ++d)
        weights[d] = s[d] == u ? w[(c + 1) % 3] + w[c] : s[d] == x ? w[(c + 2) % 3] + w[c] : -w[c];
      break;
    }
    const auto& s = faces_[static_cast<std::size_t>(face)];
    int zeros = 0;
    for (std::size_t d = 0; d < 3; ++d) {
      if (weights[d] < 0) throw std::logic_error("Goldberg-Coxeter folding: a lattice point beyond the next face");
      zeros += weights[d] == 0 ? 1 : 0;
    }
    if (zeros == 2)
      for (std::size_t d = 0; d < 3; ++d)
        if (weights[d] == frame_.T) return s[d];
    if (zeros == 1) {
      std::size_t d = 0;
      while (weights[d] != 0) ++d;
      const int u = s[(d + 1) % 3], x = s[(d + 2) % 3];
      const long on_larger = u > x ? weights[(d + 1) % 3] : weights[(d + 2) % 3];
      const long step = on_larger * g_ / frame_.T;
      if (step * frame_.T != on_larger * g_ || step < 1 || step >= g_)
        throw std::logic_error("Goldberg-Coxeter folding: an edge point off the lattice");
      return static_cast<int>(12 + edges_.at(std::minmax(u, x)).index * (g_ - 1) + (step - 1));
    }
    // Inside face `face`: its point w_P P + w_Q Q over T in the master triangle's lattice coordinates.
    const long h = frame_.h, k = frame_.k, T = frame_.T;
    const long pi = weights[1] * h - weights[2] * k, pj = weights[1] * k + weights[2] * (h + k);
    if (pi % T != 0 || pj % T != 0) throw std::logic_error("Goldberg-Coxeter folding: a point off the lattice");
    const long li = pi / T, lj = pj / T;
    const long r = rank_[static_cast<std::size_t>(lj * width_ + (li - i0_))];
    if (r < 0) throw std::logic_error("Goldberg-Coxeter folding: an inner point not ranked");
    return static_cast<int>(inner_base() + static_cast<long>(face) * inner_ + r);
  }

  Frame frame_;
  long g_;
  std::vector<Vec3> corners_;
  std::vector<std::array<int, 3>> faces_;
  std::map<std::pair<int, int>, Edge> edges_;
  long i0_ = 0, width_ = 0, height_ = 0, inner_ = 0;
  std::vector<long> rank_;
};

}  // namespace

TriMesh make_goldberg_coxeter_sphere(const GoldbergCoxeterShape& shape) {
  if (!(shape.radius > 0) || !std::isfinite(shape.radius))
    throw InputError("shape: sphere radius must be a positive number");
  check_goldberg_coxeter(shape.h, shape.k);
  const Folding folding(shape.h, shape.k);
  const std::vector<Vec3> points = folding.points();
  const std::vector<std::array<int, 3>> triangles = folding.triangles();
  const long T = triangulation_number(shape.h, shape.k);
  if (points.size() != static_cast<std::size_t>(10 * T + 2) || triangles.size() != static_cast<std::size_t>(20 * T))
    throw std::logic_error(fmt::format("Goldberg-Coxeter folding ({}, {}): {} vertices and {} triangles, not {} and {}",
                                       shape.h, shape.k, points.size(), triangles.size(), 10 * T + 2, 20 * T));
  TriMesh mesh;
  std::vector<TriMesh::VertexHandle> handles;
  handles.reserve(points.size());
  for (const auto& p : points) handles.push_back(mesh.add_vertex(p * shape.radius));
  for (const auto& t : triangles)
    if (!mesh.add_face(handles[static_cast<std::size_t>(t[0])], handles[static_cast<std::size_t>(t[1])],
                       handles[static_cast<std::size_t>(t[2])])
             .is_valid())
      throw std::logic_error("Goldberg-Coxeter folding: a triangle that does not fit its neighbours");
  icosahedral::even_out_on_sphere(mesh, shape.radius);
  mesh.update_normals();
  return mesh;
}

}  // namespace carbonmesh
