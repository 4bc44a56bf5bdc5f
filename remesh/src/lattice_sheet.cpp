// A flat surface cut from a triangular lattice (carbonmesh/remesh/lattice_sheet.hpp).
#include "carbonmesh/remesh/lattice_sheet.hpp"

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "carbonmesh/remesh/error.hpp"
#include "lattice_cut.hpp"

namespace carbonmesh {
namespace {

using lattice::Point2;
using lattice::Triangle2;

// Border edges in one run turn by less than this (radians): a straight side tessellated into several edges.
constexpr double kStraight = 1e-4;  // (coordinates read as single precision bend a straight side by up to ~1e-5)

// The ends of the longest run of consecutive border edges in one direction (a straight side of the outline, however
// it is tessellated), in the plane; the first such run of the loops in order of their first border halfedge. Throws
// InputError if there is no border.
template <typename ToPlane>
std::pair<Point2, Point2> longest_straight_run(const TriMesh& flat, const ToPlane& to_plane) {
  std::vector<char> seen(flat.n_halfedges(), 0);
  double best = -1;
  std::pair<Point2, Point2> ends;
  for (auto start : flat.halfedges()) {
    if (!flat.is_boundary(start) || seen[static_cast<std::size_t>(start.idx())]) continue;
    std::vector<TriMesh::HalfedgeHandle> loop;
    for (auto h = start; !seen[static_cast<std::size_t>(h.idx())]; h = flat.next_halfedge_handle(h)) {
      seen[static_cast<std::size_t>(h.idx())] = 1;
      loop.push_back(h);
    }
    const std::size_t n = loop.size();
    std::vector<Point2> from(n), to(n);
    for (std::size_t k = 0; k < n; ++k) {
      from[k] = to_plane(flat.point(flat.from_vertex_handle(loop[k])));
      to[k] = to_plane(flat.point(flat.to_vertex_handle(loop[k])));
    }
    auto turns = [&](std::size_t k) {  // between edge k - 1 and edge k
      const std::size_t p = (k + n - 1) % n;
      const double ux = to[p].x - from[p].x, uy = to[p].y - from[p].y, vx = to[k].x - from[k].x,
                   vy = to[k].y - from[k].y;
      return std::abs(std::atan2(ux * vy - uy * vx, ux * vx + uy * vy)) >= kStraight;
    };
    std::size_t first = 0;  // a run starts where the border turns (a loop turns somewhere)
    while (first < n && !turns(first)) ++first;
    if (first == n) first = 0;
    for (std::size_t s = 0; s < n;) {
      const std::size_t k0 = (first + s) % n;
      double length = 0;
      std::size_t k = k0;
      do {
        length += std::hypot(to[k].x - from[k].x, to[k].y - from[k].y);
        k = (k + 1) % n, ++s;
      } while (s < n && !turns(k));
      if (length > best) best = length, ends = {from[k0], to[(k + n - 1) % n]};
    }
  }
  if (best < 0) throw InputError("the flat surface has no border (a flat surface is open)");
  return ends;
}

}  // namespace

Flatness flatness(const TriMesh& mesh) {
  Flatness out;
  std::size_t n = 0;
  Vec3 c(0, 0, 0);
  for (auto v : mesh.vertices()) c += mesh.point(v), ++n;
  if (n == 0) return out;
  c /= static_cast<double>(n);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (auto v : mesh.vertices()) {
    const Vec3 d = mesh.point(v) - c;
    const Eigen::Vector3d e(d[0], d[1], d[2]);
    cov += e * e.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov);  // eigenvalues in increasing order
  const Eigen::Vector3d least = solver.eigenvectors().col(0), most = solver.eigenvectors().col(2);
  Vec3 normal(least[0], least[1], least[2]);
  Vec3 facing(0, 0, 0);  // the faces' area-weighted normal
  for (auto f : mesh.faces()) {
    const auto h = mesh.halfedge_handle(f);
    const Vec3 a = mesh.point(mesh.from_vertex_handle(h)), b = mesh.point(mesh.to_vertex_handle(h)),
               p = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)));
    facing += OpenMesh::cross(b - a, p - a);
  }
  if (OpenMesh::dot(facing, normal) < 0) normal = -normal;
  out.centroid = c;
  out.normal = normal;
  out.u = Vec3(most[0], most[1], most[2]);
  out.v = OpenMesh::cross(normal, out.u);
  for (auto v : mesh.vertices())
    out.distance = std::max(out.distance, std::abs(OpenMesh::dot(mesh.point(v) - c, normal)));
  return out;
}

LatticeSheet lattice_sheet(const TriMesh& flat, const Flatness& plane, double edge, double turn_deg) {
  if (!(edge > 0) || !std::isfinite(edge)) throw InputError(fmt::format("lattice edge {} must be positive", edge));
  auto to_plane = [&](const Vec3& p) {
    const Vec3 d = p - plane.centroid;
    return Point2{OpenMesh::dot(d, plane.u), OpenMesh::dot(d, plane.v)};
  };
  // The lattice direction: the longest straight run of the border (ties: the first), one lattice line along it.
  const auto [a, b] = longest_straight_run(flat, to_plane);
  LatticeSheet out;
  if (!std::isfinite(turn_deg)) throw InputError(fmt::format("lattice turn {} must be a finite angle", turn_deg));
  const double pi = std::acos(-1.0);
  const double angle = std::atan2(b.y - a.y, b.x - a.x) + turn_deg * pi / 180;
  out.angle_deg = angle * 180 / pi;
  const double third = pi / 3;
  const lattice::Lattice lattice{a, {edge * std::cos(angle), edge * std::sin(angle)},
                                 {edge * std::cos(angle + third), edge * std::sin(angle + third)}};

  std::vector<Triangle2> triangles;
  for (auto f : flat.faces()) {
    Triangle2 t;
    int k = 0;
    for (auto v : flat.fv_range(f)) t[static_cast<std::size_t>(k++)] = to_plane(flat.point(v));
    triangles.push_back(t);
  }
  const lattice::InsideTriangles inside = lattice::triangles_inside(triangles, lattice, {});
  out.dropped = inside.dropped;
  out.mesh = lattice::lattice_mesh(
      inside, {},
      [&](long i, long j) {
        const Point2 p = lattice.at(static_cast<double>(i), static_cast<double>(j));
        return plane.centroid + p.x * plane.u + p.y * plane.v;
      },
      false);
  return out;
}

}  // namespace carbonmesh
