// A spherical surface replaced by an icosahedral fullerene's triangulation (carbonmesh/remesh/lattice_sphere.hpp).
#include "carbonmesh/remesh/lattice_sphere.hpp"

#include <Eigen/Dense>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/shapes.hpp"
#include "add_faces.hpp"

namespace carbonmesh {

Sphere sphere_fit(const TriMesh& mesh) {
  std::vector<Eigen::Vector3d> points;
  for (auto v : mesh.vertices())
    if (!mesh.status(v).deleted() && !mesh.is_isolated(v)) points.emplace_back(mesh.point(v).data());
  Sphere out;
  if (points.size() < 4) return out;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  // Algebraic fit about the centroid: |q|^2 = 2 c.q + d for q = p - mean, linear in (c, d) (Kasa).
  Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
  Eigen::Vector4d rhs = Eigen::Vector4d::Zero();
  for (const auto& p : points) {
    const Eigen::Vector3d q = p - mean;
    const Eigen::Vector4d row(2 * q[0], 2 * q[1], 2 * q[2], 1.0);
    normal += row * row.transpose();
    rhs += row * q.squaredNorm();
  }
  const Eigen::Vector4d x = normal.ldlt().solve(rhs);
  Eigen::Vector3d c = x.head<3>();
  double r2 = x[3] + c.squaredNorm();
  if (!x.allFinite() || !(r2 > 0)) return out;
  double r = std::sqrt(r2);
  // Geometric refinement (Gauss-Newton on the distances |q - c| - r).
  for (int it = 0; it < 20; ++it) {
    Eigen::Matrix4d jtj = Eigen::Matrix4d::Zero();
    Eigen::Vector4d jtr = Eigen::Vector4d::Zero();
    for (const auto& p : points) {
      const Eigen::Vector3d d = p - mean - c;
      const double n = d.norm();
      if (!(n > 0)) continue;
      Eigen::Vector4d row;
      row << -d / n, -1.0;
      jtj += row * row.transpose();
      jtr += row * (n - r);
    }
    const Eigen::Vector4d step = jtj.ldlt().solve(-jtr);
    if (!step.allFinite()) break;
    c += step.head<3>();
    r += step[3];
    if (step.norm() <= 1e-14 * (r + c.norm())) break;
  }
  if (!std::isfinite(r) || !(r > 0) || !c.allFinite()) return out;
  double farthest = 0;
  for (const auto& p : points) farthest = std::max(farthest, std::abs((p - mean - c).norm() - r));
  const Eigen::Vector3d centre = mean + c;
  out.centre = Vec3(centre[0], centre[1], centre[2]);
  out.radius = r;
  out.distance = farthest;
  return out;
}

double fullerene_radius(GoldbergIndices g, double edge) {
  return edge * std::sqrt(5 * std::sqrt(3.0) * static_cast<double>(triangulation_number(g.h, g.k)) /
                          (4 * std::acos(-1.0)));
}

GoldbergIndices nearest_goldberg_indices(double radius, double edge) {
  GoldbergIndices best{1, 0};
  double best_error = std::abs(fullerene_radius(best, edge) - radius);
  long best_t = 1;
  for (int h = 1; triangulation_number(h, 0) <= kMaxTriangulationNumber; ++h) {
    if (fullerene_radius({h, 0}, edge) - radius > best_error) break;  // T >= h^2 only grows from here
    for (int k = 0; k <= h; ++k) {
      const long t = triangulation_number(h, k);
      if (t > kMaxTriangulationNumber) break;
      const double error = std::abs(fullerene_radius({h, k}, edge) - radius);
      if (error < best_error || (error == best_error && (t < best_t || (t == best_t && k < best.k))))
        best = {h, k}, best_error = error, best_t = t;
    }
  }
  return best;
}

LatticeFullerene lattice_fullerene(const TriMesh& input, const Sphere& sphere, double edge, GoldbergIndices indices) {
  if (!(edge > 0) || !std::isfinite(edge)) throw InputError(fmt::format("lattice edge {} must be positive", edge));
  check_goldberg_coxeter(indices.h, indices.k);
  LatticeFullerene out;
  out.indices = indices;
  const TriMesh unit = make_goldberg_coxeter_sphere({1.0, indices.h, indices.k});
  out.radius = edge / edge_stats(unit).mean;
  // Which side the input's faces face: the sign of its volume about the sphere's centre.
  const double volume = signed_volume(input, sphere.centre);
  for (auto v : unit.vertices()) out.mesh.add_vertex(sphere.centre + out.radius * unit.point(v));
  if (!add_faces(out.mesh, face_corners(unit, volume < 0)))
    throw std::logic_error("lattice fullerene: a triangle that does not fit its neighbours");
  out.mesh.update_normals();
  return out;
}

}  // namespace carbonmesh
