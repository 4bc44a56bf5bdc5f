// A cylindrical surface cut from a triangular lattice rolled into a tube (carbonmesh/remesh/lattice_tube.hpp).
#include "carbonmesh/remesh/lattice_tube.hpp"

#include <Eigen/Dense>
#include <fmt/format.h>

#include <algorithm>
#include <deque>
#include <cmath>
#include <vector>

#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/lattice_sheet.hpp"
#include "lattice_cut.hpp"
#include "least_squares_fit.hpp"

namespace carbonmesh {
namespace {

using lattice::Point2;
using lattice::Triangle2;

Vec3 area_normal(const TriMesh& mesh, TriMesh::FaceHandle f) {  // twice the area, along the normal
  const auto h = mesh.halfedge_handle(f);
  const Vec3 a = mesh.point(mesh.from_vertex_handle(h)), b = mesh.point(mesh.to_vertex_handle(h)),
             c = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)));
  return OpenMesh::cross(b - a, c - a);
}

// A unit vector square to the unit vector w: the coordinate axis least along w, its part along w taken off.
Vec3 square_to(const Vec3& w) {
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(w[i]) < std::abs(w[k])) k = i;
  Vec3 e(0, 0, 0);
  e[k] = 1;
  return (e - OpenMesh::dot(e, w) * w).normalized();
}

// The residuals of the cylinder fit: each vertex's distance to the axis less the radius. Parameters (alpha, beta,
// x, y, r): the axis axis0 + alpha u0 + beta v0 (normalised) through centre + x u0 + y v0, the radius r.
struct CylinderResiduals : least_squares_fit::Residuals {

  const std::vector<Eigen::Vector3d>* points;  // relative to `centre`
  Eigen::Vector3d axis0, u0, v0;

  int inputs() const { return 5; }
  int values() const { return static_cast<int>(points->size()); }
  Eigen::Vector3d axis(const Eigen::VectorXd& x) const { return (axis0 + x[0] * u0 + x[1] * v0).normalized(); }
  int operator()(const Eigen::VectorXd& x, Eigen::VectorXd& f) const {
    const Eigen::Vector3d w = axis(x), p = x[2] * u0 + x[3] * v0;
    for (std::size_t i = 0; i < points->size(); ++i) {
      const Eigen::Vector3d d = (*points)[i] - p;
      f[static_cast<Eigen::Index>(i)] = (d - d.dot(w) * w).norm() - x[4];
    }
    return 0;
  }
};

constexpr std::size_t kFitPoints = 4096;

Eigen::Vector3d eigen(const Vec3& v) { return {v[0], v[1], v[2]}; }
Vec3 vec3(const Eigen::Vector3d& v) { return {v[0], v[1], v[2]}; }

}  // namespace

Cylinder cylinder_fit(const TriMesh& mesh) {
  Cylinder out;
  if (mesh.n_vertices() < 6 || mesh.n_faces() < 2) return out;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (auto v : mesh.vertices()) centre += eigen(mesh.point(v));
  centre /= static_cast<double>(mesh.n_vertices());
  // A first axis: the direction the faces' normals are most square to (area weighted).
  Eigen::Matrix3d normals = Eigen::Matrix3d::Zero();
  for (auto f : mesh.faces()) {
    const Eigen::Vector3d n = eigen(area_normal(mesh, f));
    if (const double twice_area = n.norm(); twice_area > 0) normals += n * n.transpose() / twice_area;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(normals);
  // The fit runs on at most kFitPoints vertices, every k-th in index order (points on a cylinder give its axis and
  // radius from any few of them); the distance is then taken over all.
  const std::size_t stride = (mesh.n_vertices() + kFitPoints - 1) / kFitPoints;
  CylinderResiduals residuals;
  std::vector<Eigen::Vector3d> points, all;
  all.reserve(mesh.n_vertices());
  for (auto v : mesh.vertices()) all.push_back(eigen(mesh.point(v)) - centre);
  for (std::size_t i = 0; i < all.size(); i += stride) points.push_back(all[i]);
  residuals.points = &points;
  residuals.axis0 = solver.eigenvectors().col(0);
  residuals.u0 = eigen(square_to(vec3(residuals.axis0)));
  residuals.v0 = residuals.axis0.cross(residuals.u0);
  // A first circle: the algebraic fit x^2 + y^2 + D x + E y + F = 0 of the points seen along that axis.
  Eigen::Matrix3d normal_matrix = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d row(p.dot(residuals.u0), p.dot(residuals.v0), 1.0);
    normal_matrix += row * row.transpose();
    rhs -= row * (row[0] * row[0] + row[1] * row[1]);
  }
  const Eigen::Vector3d def = normal_matrix.ldlt().solve(rhs);
  Eigen::VectorXd x(5);
  x << 0, 0, -def[0] / 2, -def[1] / 2, std::sqrt(std::max(0.0, def[0] * def[0] / 4 + def[1] * def[1] / 4 - def[2]));
  if (!x.allFinite() || !(x[4] > 0)) return out;
  // The least-squares cylinder (Levenberg-Marquardt, forward differences).
  if (!least_squares_fit::minimize(residuals, x, 2000)) return out;
  out.axis = vec3(least_squares_fit::canonical_axis(residuals.axis(x)));
  out.point = vec3(centre + x[2] * residuals.u0 + x[3] * residuals.v0);
  out.point -= OpenMesh::dot(out.point - vec3(centre), out.axis) * out.axis;  // level with the centroid
  out.radius = std::abs(x[4]);
  residuals.points = &all;
  Eigen::VectorXd f(all.size());
  residuals(x, f);
  out.distance = f.cwiseAbs().maxCoeff();
  if (!(out.radius > 0) || !std::isfinite(out.distance)) out.distance = std::numeric_limits<double>::infinity();
  return out;
}

void check_chirality(Chirality c) {
  const long n = c.n, m = c.m;
  if (n < 0 || m < 0 || n * n + n * m + m * m < kMinChiralNorm)
    throw InputError(fmt::format("chirality ({}, {}) makes no tube: n and m must be >= 0 with n^2 + nm + m^2 >= {} "
                                 "(the thinnest is (2, 1))",
                                 n, m, kMinChiralNorm));
}

double chiral_circumference(Chirality c, double edge) {
  const double n = c.n, m = c.m;
  return edge * std::sqrt(n * n + n * m + m * m);
}

double chiral_angle_deg(Chirality c) {
  return std::atan2(std::sqrt(3.0) * c.m, 2.0 * c.n + c.m) * 180 / std::acos(-1.0);
}

Chirality nearest_chirality(double radius, double edge) {
  const double target = 2 * std::acos(-1.0) * radius / edge;  // the circumference in lattice edges
  const double norm = target * target;                         // n^2 + nm + m^2 wanted
  Chirality best{2, 1};
  double best_miss = std::abs(std::sqrt(7.0) - target);
  auto consider = [&](long n, long m) {
    if (m < 0 || m > n || n * n + n * m + m * m < kMinChiralNorm) return;
    const double miss = std::abs(chiral_circumference({static_cast<int>(n), static_cast<int>(m)}, 1.0) - target);
    if (miss < best_miss || (miss == best_miss && m < best.m)) best = {static_cast<int>(n), static_cast<int>(m)};
    best_miss = std::min(best_miss, miss);
  };
  // With m <= n, n^2 <= n^2 + nm + m^2 <= 3 n^2: n lies in [sqrt(norm / 3), sqrt(norm)]; for each n the m nearest
  // the wanted norm are the two integers around the root of m^2 + n m + n^2 - norm = 0.
  const long low = std::max(0L, static_cast<long>(std::floor(std::sqrt(norm / 3))) - 2);
  const long high = static_cast<long>(std::ceil(std::sqrt(norm))) + 2;
  for (long n = low; n <= high; ++n) {
    const double root = (-static_cast<double>(n) + std::sqrt(std::max(0.0, 4 * norm - 3.0 * n * n))) / 2;
    consider(n, static_cast<long>(std::floor(root)));
    consider(n, static_cast<long>(std::ceil(root)));
    consider(n, 0);
    consider(n, n);
  }
  return best;
}

TriMesh cylinder_surface(const Cylinder& cylinder, double radius, double z0, double z1, double edge, bool inward) {
  const double pi = std::acos(-1.0);
  const Vec3 w = cylinder.axis, u = square_to(w), v = OpenMesh::cross(w, u);
  const double step = 2 * std::acos(std::max(-1.0, 1 - 1e-4 * edge / radius));  // chords within 1e-4 edge
  const int segments = static_cast<int>(std::clamp(std::ceil(2 * pi / step), 16.0, 1e6));
  TriMesh surface;
  std::vector<TriMesh::VertexHandle> low, high;
  for (int k = 0; k < segments; ++k) {
    const double theta = 2 * pi * k / segments;
    const Vec3 around = cylinder.point + radius * (std::cos(theta) * u + std::sin(theta) * v);
    low.push_back(surface.add_vertex(around + z0 * w));
    high.push_back(surface.add_vertex(around + z1 * w));
  }
  for (int k = 0; k < segments; ++k) {
    const auto b0 = low[static_cast<std::size_t>(k)], b1 = low[static_cast<std::size_t>((k + 1) % segments)],
               t0 = high[static_cast<std::size_t>(k)], t1 = high[static_cast<std::size_t>((k + 1) % segments)];
    if (inward) {
      surface.add_face(b0, t1, b1);
      surface.add_face(b0, t0, t1);
    } else {
      surface.add_face(b0, b1, t1);
      surface.add_face(b0, t1, t0);
    }
  }
  return surface;
}

LatticeTube lattice_tube(const TriMesh& input, const Cylinder& cylinder, double edge, Chirality chirality) {
  if (!(edge > 0) || !std::isfinite(edge)) throw InputError(fmt::format("lattice edge {} must be positive", edge));
  check_chirality(chirality);
  const long n = chirality.n, m = chirality.m;
  const double pi = std::acos(-1.0);
  const double period = chiral_circumference(chirality, edge);  // P, the circumference
  LatticeTube out;
  out.chirality = chirality;
  out.radius = period / (2 * pi);
  const Vec3 w = cylinder.axis, u = square_to(w), v = OpenMesh::cross(w, u);  // u x v = w
  auto unrolled = [&](const Vec3& q) {  // (s, z): the arc around the axis, scaled to the tube, and the height
    const Vec3 d = q - cylinder.point;
    return Point2{std::atan2(OpenMesh::dot(d, v), OpenMesh::dot(d, u)) * period / (2 * pi), OpenMesh::dot(d, w)};
  };

  std::vector<Point2> at(input.n_vertices());  // each vertex unrolled
  for (auto vh : input.vertices()) at[static_cast<std::size_t>(vh.idx())] = unrolled(input.point(vh));

  // The input unrolled, each triangle in one piece (its corners within half a circumference of its first).
  std::vector<Triangle2> region;
  double facing = 0;  // > 0: the faces face out of the tube
  for (auto f : input.faces()) {
    Triangle2 t;
    int k = 0;
    for (auto vh : input.fv_range(f)) t[static_cast<std::size_t>(k++)] = at[static_cast<std::size_t>(vh.idx())];
    for (std::size_t c = 1; c < 3; ++c) t[c].x -= period * std::round((t[c].x - t[0].x) / period);
    region.push_back(t);
    const Vec3 d = input.calc_face_centroid(f) - cylinder.point;
    facing += OpenMesh::dot(area_normal(input, f), d - OpenMesh::dot(d, w) * w);
  }

  // A lattice point at the vertex lowest along the axis; the chiral vector n e1 + m e2 along s.
  Point2 origin;
  double z0 = std::numeric_limits<double>::infinity(), z1 = -z0;
  for (const Point2& p : at) {
    if (p.y < z0) z0 = p.y, origin = p;
    z1 = std::max(z1, p.y);
  }
  const Point2 e1{edge, 0}, e2{edge / 2, edge * std::sqrt(3.0) / 2};
  const Point2 along{(n * e1.x + m * e2.x) / period, (n * e1.y + m * e2.y) / period};  // unit, along the chiral vector
  auto turned = [&](Point2 e) { return Point2{e.x * along.x + e.y * along.y, -e.x * along.y + e.y * along.x}; };
  const lattice::Lattice lattice{origin, turned(e1), turned(e2)};
  const lattice::Period rolled{n, m};
  const lattice::InsideTriangles inside = lattice::triangles_inside(region, lattice, rolled);
  out.dropped = inside.dropped;
  auto rolled_up = [&](double s, double z) {
    const double theta = 2 * pi * s / period;
    return cylinder.point + out.radius * (std::cos(theta) * u + std::sin(theta) * v) + z * w;
  };
  out.mesh = lattice::lattice_mesh(
      inside, rolled,
      [&](long i, long j) {
        const Point2 p = lattice.at(static_cast<double>(i), static_cast<double>(j));
        return rolled_up(p.x, p.y);
      },
      facing < 0);

  // The surface: the tube's cylinder one edge beyond the input's ends.
  out.surface = cylinder_surface(cylinder, out.radius, z0 - edge, z1 + edge, edge, facing < 0);
  return out;
}

std::optional<std::vector<double>> angles_along_surface(const TriMesh& mesh, const Cylinder& cylinder) {
  const double pi = std::acos(-1.0);
  const Vec3 w = cylinder.axis, u = square_to(w), v = OpenMesh::cross(w, u);
  std::vector<double> seen(mesh.n_vertices()), angle(mesh.n_vertices(), 0.0);
  for (auto vh : mesh.vertices()) {
    const Vec3 d = mesh.point(vh) - cylinder.point;
    seen[static_cast<std::size_t>(vh.idx())] = std::atan2(OpenMesh::dot(d, v), OpenMesh::dot(d, u));
  }
  auto step = [&](TriMesh::HalfedgeHandle h) {  // the turn from h's start to its end, in (-pi, pi]
    const double turn = seen[static_cast<std::size_t>(mesh.to_vertex_handle(h).idx())] -
                        seen[static_cast<std::size_t>(mesh.from_vertex_handle(h).idx())];
    return turn - 2 * pi * std::ceil((turn - pi) / (2 * pi));
  };
  // Breadth first from the first vertex of each component, each vertex one step from the one it was reached from.
  std::vector<char> reached(mesh.n_vertices(), 0);
  for (auto start : mesh.vertices()) {
    if (reached[static_cast<std::size_t>(start.idx())]) continue;
    reached[static_cast<std::size_t>(start.idx())] = 1;
    angle[static_cast<std::size_t>(start.idx())] = seen[static_cast<std::size_t>(start.idx())];
    std::deque<TriMesh::VertexHandle> queue{start};
    while (!queue.empty()) {
      const auto from = queue.front();
      queue.pop_front();
      for (auto h : mesh.voh_range(from)) {
        const auto to = mesh.to_vertex_handle(h);
        if (reached[static_cast<std::size_t>(to.idx())]) continue;
        reached[static_cast<std::size_t>(to.idx())] = 1;
        angle[static_cast<std::size_t>(to.idx())] = angle[static_cast<std::size_t>(from.idx())] + step(h);
        queue.push_back(to);
      }
    }
  }
  // An edge whose ends differ by a full turn closes a loop around the axis.
  for (auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    const double turn = angle[static_cast<std::size_t>(mesh.to_vertex_handle(h).idx())] -
                        angle[static_cast<std::size_t>(mesh.from_vertex_handle(h).idx())];
    if (std::abs(turn - step(h)) > pi) return std::nullopt;
  }
  return angle;
}

CurvedSheet curved_sheet(const TriMesh& input, const Cylinder& cylinder, const std::vector<double>& angles,
                         double edge, double turn_deg) {
  const Vec3 w = cylinder.axis, u = square_to(w), v = OpenMesh::cross(w, u);
  const double radius = cylinder.radius;
  // Unrolled: (radius * angle, height, 0), the faces as they are (facing +z where they face out of the cylinder).
  TriMesh unrolled = input;
  double z0 = std::numeric_limits<double>::infinity(), z1 = -z0;
  for (auto vh : unrolled.vertices()) {
    const double z = OpenMesh::dot(input.point(vh) - cylinder.point, w);
    unrolled.set_point(vh, Vec3(radius * angles[static_cast<std::size_t>(vh.idx())], z, 0));
    z0 = std::min(z0, z), z1 = std::max(z1, z);
  }
  const Flatness plane = flatness(unrolled);  // z = 0, up to rounding
  LatticeSheet sheet = lattice_sheet(unrolled, plane, edge, turn_deg);
  CurvedSheet out;
  out.angle_deg = sheet.angle_deg;
  out.dropped = sheet.dropped;
  out.mesh = std::move(sheet.mesh);
  for (auto vh : out.mesh.vertices()) {  // rolled back: s = radius * angle
    const Vec3 p = out.mesh.point(vh);
    const double theta = p[0] / radius;
    out.mesh.set_point(vh, cylinder.point + radius * (std::cos(theta) * u + std::sin(theta) * v) + p[1] * w);
  }
  out.surface = cylinder_surface(cylinder, radius, z0 - edge, z1 + edge, edge, plane.normal[2] < 0);
  return out;
}

}  // namespace carbonmesh
