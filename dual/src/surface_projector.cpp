#include "surface_projector.hpp"

#include "carbonmesh/remesh/triangle_tree.hpp"

#include <algorithm>

namespace carbonmesh::detail {
namespace {
using namespace triangle_tree;

// Where on a triangle (a, b, c) the closest point lies: its interior, a corner, or an edge (ab, bc, ca).
enum Region : int { Inside = 0, CornerA, CornerB, CornerC, EdgeAB, EdgeBC, EdgeCA };

// Closest point of triangle (a, b, c) to p (Ericson, Real-Time Collision Detection 5.1.5) and its region.
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, int& region) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = OpenMesh::dot(ab, ap), d2 = OpenMesh::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return region = CornerA, a;
  const Vec3 bp = p - b;
  const double d3 = OpenMesh::dot(ab, bp), d4 = OpenMesh::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return region = CornerB, b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return region = EdgeAB, a + ab * (d1 / (d1 - d3));
  const Vec3 cp = p - c;
  const double d5 = OpenMesh::dot(ab, cp), d6 = OpenMesh::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return region = CornerC, c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return region = EdgeCA, a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return region = EdgeBC, b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = 1.0 / (va + vb + vc);
  region = Inside;
  return a + ab * (vb * denom) + ac * (vc * denom);
}
}  // namespace

// The plane of a triangle and the three planes through its edges perpendicular to it: q projects into the
// triangle's interior when it lies strictly on the inner side of all three edge planes, and then its closest point
// is its projection onto the plane (four dot products instead of the general test; nearly every query of the
// optimiser ends there).
struct FacePlanes {
  Vec3 normal;    // unit normal (zero for a degenerate triangle)
  double offset;  // normal . a
  std::array<Vec3, 3> edge_normal;  // normal x (edge ab, bc, ca), pointing into the triangle
  std::array<double, 3> edge_offset;  // edge_normal[k] . (start of edge k)
};

FacePlanes face_planes(const std::array<Vec3, 3>& t) {
  FacePlanes f;
  const Vec3 n = OpenMesh::cross(t[1] - t[0], t[2] - t[0]);
  const double length = n.norm();
  f.normal = length > 0 ? n / length : Vec3(0, 0, 0);
  f.offset = OpenMesh::dot(f.normal, t[0]);
  for (int k = 0; k < 3; ++k) {
    f.edge_normal[k] = OpenMesh::cross(f.normal, t[(k + 1) % 3] - t[k]);
    f.edge_offset[k] = OpenMesh::dot(f.edge_normal[k], t[k]);
  }
  return f;
}

struct SurfaceProjector::Impl {
  Triangles triangles;
  Tree tree;
  std::vector<FacePlanes> planes;            // per face
  std::vector<std::array<Vec3, 3>> corners;  // per face
  std::vector<std::array<int, 3>> across;    // per face: the face across edge ab, bc, ca (-1 at a border)
  std::vector<std::array<int, 3>> vertex;    // per face: its corner vertices
  std::vector<int> star_start, star;         // CSR: the faces around each vertex
};

SurfaceProjector::SurfaceProjector(const TriMesh& surface) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  // Faces in index order, deleted ones skipped; `index` maps mesh face -> compact index.
  std::vector<int> index(surface.n_faces(), -1);
  std::vector<TriMesh::FaceHandle> handles;
  for (auto f : surface.faces()) {
    index[static_cast<std::size_t>(f.idx())] = static_cast<int>(handles.size());
    handles.push_back(f);
  }
  m.triangles.reserve(handles.size());
  m.corners.reserve(handles.size());
  m.planes.reserve(handles.size());
  m.across.reserve(handles.size());
  m.vertex.reserve(handles.size());
  for (auto f : handles) {
    std::array<Vec3, 3> p;
    std::array<int, 3> across{-1, -1, -1}, vertex{};
    int k = 0;
    for (auto h : surface.fh_range(f)) {
      if (k == 3) break;
      const auto v = surface.from_vertex_handle(h);
      p[k] = surface.point(v);
      vertex[k] = v.idx();
      const auto g = surface.opposite_face_handle(h);
      if (g.is_valid()) across[k] = index[static_cast<std::size_t>(g.idx())];
      ++k;
    }
    m.corners.push_back(p);
    m.planes.push_back(face_planes(p));
    m.across.push_back(across);
    m.vertex.push_back(vertex);
    m.triangles.emplace_back(to_point(p[0]), to_point(p[1]), to_point(p[2]));
  }
  m.star_start.assign(surface.n_vertices() + 1, 0);
  for (const auto& v : m.vertex)
    for (int u : v) ++m.star_start[static_cast<std::size_t>(u) + 1];
  for (std::size_t v = 0; v < surface.n_vertices(); ++v) m.star_start[v + 1] += m.star_start[v];
  m.star.resize(static_cast<std::size_t>(m.star_start.back()));
  std::vector<int> fill(m.star_start.begin(), m.star_start.end() - 1);
  for (std::size_t f = 0; f < m.vertex.size(); ++f)
    for (int u : m.vertex[f]) m.star[static_cast<std::size_t>(fill[static_cast<std::size_t>(u)]++)] = static_cast<int>(f);
  m.tree.insert(m.triangles.begin(), m.triangles.end());
  m.tree.build();
  m.tree.accelerate_distance_queries();
}

SurfaceProjector::~SurfaceProjector() = default;

std::size_t SurfaceProjector::faces() const { return impl_->corners.size(); }

void SurfaceProjector::closest_points(const std::vector<Vec3>& points, std::vector<Vec3>& closest,
                                      std::vector<int>& faces) const {
  closest.resize(points.size());
  faces.resize(points.size());
  const Impl& m = *impl_;
  const long n = static_cast<long>(points.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    const Vec3& p = points[static_cast<std::size_t>(i)];
    const auto [q, it] = m.tree.closest_point_and_primitive(to_point(p));
    closest[static_cast<std::size_t>(i)] = Vec3(q.x(), q.y(), q.z());
    faces[static_cast<std::size_t>(i)] = static_cast<int>(it - m.triangles.begin());
  }
}

namespace {
// closest_on_triangle of face f, with the interior tested first by its planes.
Vec3 closest_on_face(const Vec3& q, const FacePlanes& planes, const std::array<Vec3, 3>& t, int& region) {
  if (OpenMesh::dot(planes.edge_normal[0], q) > planes.edge_offset[0] &&
      OpenMesh::dot(planes.edge_normal[1], q) > planes.edge_offset[1] &&
      OpenMesh::dot(planes.edge_normal[2], q) > planes.edge_offset[2]) {
    region = Inside;
    return q - planes.normal * (OpenMesh::dot(planes.normal, q) - planes.offset);
  }
  return closest_on_triangle(q, t[0], t[1], t[2], region);
}
}  // namespace

Vec3 SurfaceProjector::closest_point_near(const Vec3& q, int& face) const {
  const Impl& m = *impl_;
  int region = Inside;
  const std::size_t f0 = static_cast<std::size_t>(face);
  Vec3 best = closest_on_face(q, m.planes[f0], m.corners[f0], region);
  double best_d2 = (q - best).sqrnorm();
  // Walk: from a corner to the faces around it, from an edge across it, while strictly nearer (so it cannot
  // cycle; among equals the first candidate, so it is deterministic).
  for (int step = 0; step < 64 && region != Inside; ++step) {
    const std::size_t f = static_cast<std::size_t>(face);
    int next = -1, next_region = Inside;
    Vec3 next_point;
    auto consider = [&](int g) {
      if (g < 0 || g == face) return;
      const std::size_t h = static_cast<std::size_t>(g);
      int r = Inside;
      const Vec3 c = closest_on_face(q, m.planes[h], m.corners[h], r);
      const double d2 = (q - c).sqrnorm();
      if (d2 < best_d2 * (1 - 1e-12)) best_d2 = d2, next = g, next_point = c, next_region = r;
    };
    if (region >= EdgeAB) {
      consider(m.across[f][region - EdgeAB]);
    } else {
      const std::size_t v = static_cast<std::size_t>(m.vertex[f][region - CornerA]);
      for (int k = m.star_start[v]; k < m.star_start[v + 1]; ++k) consider(m.star[static_cast<std::size_t>(k)]);
    }
    if (next < 0) break;
    face = next, best = next_point, region = next_region;
  }
  return best;
}

}  // namespace carbonmesh::detail
