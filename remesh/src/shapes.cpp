#include "carbonmesh/remesh/shapes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>
#include <vector>

#include "carbonmesh/remesh/error.hpp"
#include "icosahedral.hpp"

namespace carbonmesh {
namespace {

using VH = TriMesh::VertexHandle;

void require_positive(double value, const char* what) {
  if (!(value > 0) || !std::isfinite(value))
    throw InputError(std::string("shape: ") + what + " must be a positive number");
}

// A ring of vertices around the tube and their angles (ascending, in [0, 2 pi)).
struct Ring {
  std::vector<VH> vertices;
  std::vector<double> angles;
};

double wrap_pi(double a) {  // to (-pi, pi]
  a = std::fmod(a + M_PI, 2 * M_PI);
  if (a < 0) a += 2 * M_PI;
  return a - M_PI;
}

// Triangulates the band between ring `a` and ring `b`, where b lies further along the tube direction
// (outward normals by the right-hand rule around that direction). Rings may have different sizes.
void zip_rings(TriMesh& mesh, const Ring& a, const Ring& b) {
  const std::size_t na = a.vertices.size(), nb = b.vertices.size();
  if (na == 1 && nb == 1) return;
  if (na == 1) {
    for (std::size_t j = 0; j < nb; ++j) mesh.add_face(a.vertices[0], b.vertices[(j + 1) % nb], b.vertices[j]);
    return;
  }
  if (nb == 1) {
    for (std::size_t i = 0; i < na; ++i) mesh.add_face(a.vertices[i], a.vertices[(i + 1) % na], b.vertices[0]);
    return;
  }
  // Unwrapped angles starting at a[0] and at the b vertex closest to it.
  std::size_t b0 = 0;
  double best = 1e9;
  for (std::size_t k = 0; k < nb; ++k) {
    const double d = std::abs(wrap_pi(b.angles[k] - a.angles[0]));
    if (d < best) best = d, b0 = k;
  }
  auto angle_a = [&](std::size_t i) {
    return i < na ? a.angles[i] : a.angles[i - na] + 2 * M_PI;
  };
  const double b_start = a.angles[0] + wrap_pi(b.angles[b0] - a.angles[0]);
  auto angle_b = [&](std::size_t m) {
    const std::size_t k = (b0 + m) % nb;
    double d = b.angles[k] - b.angles[b0];
    if (d < 0 || (m > 0 && d == 0)) d += 2 * M_PI;
    if (m == nb) d = 2 * M_PI;
    return b_start + d;
  };
  std::size_t i = 0, m = 0;
  while (i < na || m < nb) {
    const bool advance_a = m == nb || (i < na && angle_a(i + 1) <= angle_b(m + 1));
    const VH ai = a.vertices[i % na], bm = b.vertices[(b0 + m) % nb];
    if (advance_a) {
      mesh.add_face(ai, a.vertices[(i + 1) % na], bm);
      ++i;
    } else {
      mesh.add_face(ai, b.vertices[(b0 + m + 1) % nb], bm);
      ++m;
    }
  }
}

struct Frame {
  Vec3 t, n, b;  // tangent, normal, binormal (b = t x n)
};

// Parallel-transported frames along a polyline.
std::vector<Frame> transport_frames(const std::vector<Vec3>& centers, bool closed) {
  const std::size_t n = centers.size();
  std::vector<Frame> frames(n);
  for (std::size_t i = 0; i < n; ++i) {
    Vec3 prev = (i > 0) ? centers[i - 1] : (closed ? centers[n - 1] : centers[i]);
    Vec3 next = (i + 1 < n) ? centers[i + 1] : (closed ? centers[0] : centers[i]);
    frames[i].t = (next - prev).normalized();
  }
  const Vec3 t0 = frames[0].t;
  Vec3 seed = std::abs(t0[0]) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  frames[0].n = (seed - t0 * OpenMesh::dot(seed, t0)).normalized();
  for (std::size_t i = 1; i < n; ++i) {
    const Vec3& t = frames[i].t;
    frames[i].n = (frames[i - 1].n - t * OpenMesh::dot(frames[i - 1].n, t)).normalized();
  }
  for (auto& f : frames) f.b = OpenMesh::cross(f.t, f.n);
  return frames;
}

Ring make_ring(TriMesh& mesh, const Vec3& center, const Frame& frame, double radius, std::size_t count,
               double angle_offset) {
  Ring ring;
  if (count == 1) {
    ring.vertices.push_back(mesh.add_vertex(center));
    ring.angles.push_back(0);
    return ring;
  }
  for (std::size_t j = 0; j < count; ++j) {
    double angle = std::fmod(angle_offset + 2 * M_PI * static_cast<double>(j) / static_cast<double>(count), 2 * M_PI);
    if (angle < 0) angle += 2 * M_PI;
    ring.angles.push_back(angle);
  }
  // Keep angles ascending from the smallest.
  const auto first = static_cast<std::size_t>(std::min_element(ring.angles.begin(), ring.angles.end()) - ring.angles.begin());
  std::rotate(ring.angles.begin(), ring.angles.begin() + static_cast<long>(first), ring.angles.end());
  for (double angle : ring.angles)
    ring.vertices.push_back(
        mesh.add_vertex(center + radius * (std::cos(angle) * frame.n + std::sin(angle) * frame.b)));
  return ring;
}

// A tube of `radius` around the polyline `centers`, `segments` vertices around, neighbouring rings offset by
// half a step (equilateral-like triangles). Open tubes are closed by hemispherical caps if `caps`.
TriMesh sweep_tube(const std::vector<Vec3>& centers, bool closed, double radius, std::size_t segments,
                   bool caps = true) {
  TriMesh mesh;
  const std::size_t n = centers.size();
  const auto frames = transport_frames(centers, closed);
  double twist = 0;  // holonomy of the transported frame around a closed curve, spread over the rings
  if (closed) {
    const Vec3 n_end = (frames[n - 1].n - frames[0].t * OpenMesh::dot(frames[n - 1].n, frames[0].t)).normalized();
    twist = std::atan2(OpenMesh::dot(OpenMesh::cross(frames[0].n, n_end), frames[0].t), OpenMesh::dot(frames[0].n, n_end));
  }
  const double step = 2 * M_PI / static_cast<double>(segments);
  std::vector<Ring> rings;
  for (std::size_t i = 0; i < n; ++i) {
    double offset = (i % 2) * 0.5 * step;
    if (closed) offset -= twist * static_cast<double>(i) / static_cast<double>(n);
    rings.push_back(make_ring(mesh, centers[i], frames[i], radius, segments, offset));
  }
  if (!closed && caps) {
    // Caps: rings shrinking along a quarter circle, down to a pole vertex.
    const double spacing = step * radius * std::sqrt(3.0) / 2.0;
    const std::size_t k_max = std::max<std::size_t>(2, static_cast<std::size_t>(std::lround(M_PI / 2 * radius / spacing)));
    auto cap = [&](std::size_t end, double direction) {
      std::vector<Ring> cap_rings;
      for (std::size_t k = 1; k <= k_max; ++k) {
        const double theta = M_PI / 2 * static_cast<double>(k) / static_cast<double>(k_max);
        const std::size_t count =
            k == k_max ? 1 : std::max<std::size_t>(3, static_cast<std::size_t>(std::lround(segments * std::cos(theta))));
        const Vec3 center = centers[end] + direction * radius * std::sin(theta) * frames[end].t;
        const double offset = ((end % 2) + k) % 2 * 0.5 * 2 * M_PI / static_cast<double>(count);
        cap_rings.push_back(make_ring(mesh, center, frames[end], radius * std::cos(theta), count, offset));
      }
      return cap_rings;
    };
    const auto start_cap = cap(0, -1.0);
    const auto end_cap = cap(n - 1, 1.0);
    zip_rings(mesh, start_cap[0], rings[0]);
    for (std::size_t k = 0; k + 1 < start_cap.size(); ++k) zip_rings(mesh, start_cap[k + 1], start_cap[k]);
    zip_rings(mesh, rings[n - 1], end_cap[0]);
    for (std::size_t k = 0; k + 1 < end_cap.size(); ++k) zip_rings(mesh, end_cap[k], end_cap[k + 1]);
  }
  for (std::size_t i = 0; i + 1 < n; ++i) zip_rings(mesh, rings[i], rings[i + 1]);
  if (closed) zip_rings(mesh, rings[n - 1], rings[0]);
  mesh.update_normals();
  return mesh;
}

std::size_t segments_for(double radius, double edge, std::size_t fallback) {
  if (edge <= 0) return fallback;
  return std::max<std::size_t>(6, static_cast<std::size_t>(std::lround(2 * M_PI * radius / edge)));
}

double ring_spacing(double radius, std::size_t segments) {
  return 2 * M_PI * radius / static_cast<double>(segments) * std::sqrt(3.0) / 2.0;
}

// A straight tube along z, centred on the origin, with or without hemispherical caps.
TriMesh straight_tube(double radius, double length, double edge, bool caps) {
  const std::size_t segments = segments_for(radius, edge, 24);
  const std::size_t rings =
      std::max<std::size_t>(2, static_cast<std::size_t>(std::lround(length / ring_spacing(radius, segments))) + 1);
  std::vector<Vec3> centers;
  for (std::size_t i = 0; i < rings; ++i)
    centers.emplace_back(0.0, 0.0, -length / 2 + length * static_cast<double>(i) / static_cast<double>(rings - 1));
  return sweep_tube(centers, false, radius, segments, caps);
}

}  // namespace

TriMesh make_icosphere(const SphereShape& shape) {
  require_positive(shape.radius, "sphere radius");
  if (shape.subdivisions < 0 || shape.subdivisions > 9)
    throw InputError("shape: sphere subdivisions must be between 0 and 9");
  // (Not a structured binding: the lambda below captures `points`, which clang before 16 refuses for a binding.)
  std::vector<Vec3> points;
  std::vector<std::array<int, 3>> faces;
  std::tie(points, faces) = icosahedral::icosahedron();
  for (int s = 0; s < shape.subdivisions; ++s) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = midpoint.find({key.first, key.second});
      if (it != midpoint.end()) return it->second;
      points.push_back((points[static_cast<std::size_t>(a)] + points[static_cast<std::size_t>(b)]).normalized());
      const int index = static_cast<int>(points.size()) - 1;
      midpoint.emplace(std::pair<int, int>(key.first, key.second), index);
      return index;
    };
    std::vector<std::array<int, 3>> finer;
    finer.reserve(faces.size() * 4);
    for (const auto& f : faces) {
      const int ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
      finer.push_back({f[0], ab, ca});
      finer.push_back({f[1], bc, ab});
      finer.push_back({f[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    faces = std::move(finer);
  }
  TriMesh mesh;
  std::vector<VH> handles;
  for (const auto& p : points) handles.push_back(mesh.add_vertex(p * shape.radius));
  for (const auto& f : faces)
    mesh.add_face(handles[static_cast<std::size_t>(f[0])], handles[static_cast<std::size_t>(f[1])],
                  handles[static_cast<std::size_t>(f[2])]);
  mesh.update_normals();
  return mesh;
}

namespace {

// Lattice point (i, j) of the spherical triangle (a, b, c) at frequency f (weight k = f - i - j on a), on the unit
// sphere (icosahedral::spherical_point). Longest / shortest edge 1.25 at frequency 129 with the sqrt(3) step; the
// central projection of the flat lattice shortens the edges near the 12 corners (1.52 at frequency 129 with sqrt(3)
// even after the springs).
Vec3 geodesic_point(const Vec3& a, const Vec3& b, const Vec3& c, int i, int j, int f) {
  const int k = f - i - j;
  const double fd = f;
  return icosahedral::spherical_point(a, b, c, k / fd, i / fd, j / fd);
}

}  // namespace

TriMesh make_geodesic_sphere(const GeodesicSphereShape& shape) {
  require_positive(shape.radius, "sphere radius");
  if (shape.frequency < 1 || shape.frequency > 1000)
    throw InputError("shape: geodesic sphere frequency must be between 1 and 1000");
  const auto [corners, triangles] = icosahedral::icosahedron();
  const int f = shape.frequency;
  // Lattice point (i, j) of face (A, B, C) has the weights i on B and j on C (geodesic_point). Points on an
  // icosahedron edge are shared by the two faces: keyed by the edge's corners (ascending) and the step from the
  // first.
  std::vector<Vec3> points(corners.begin(), corners.end());
  std::map<std::array<int, 3>, int> on_edge;
  std::vector<std::array<int, 3>> faces;
  faces.reserve(triangles.size() * static_cast<std::size_t>(f) * static_cast<std::size_t>(f));
  for (const auto& t : triangles) {
    const Vec3 &a = corners[static_cast<std::size_t>(t[0])], &b = corners[static_cast<std::size_t>(t[1])],
               &c = corners[static_cast<std::size_t>(t[2])];
    std::vector<int> id(static_cast<std::size_t>((f + 1) * (f + 1)), -1);
    auto at = [&](int i, int j) -> int& { return id[static_cast<std::size_t>(i * (f + 1) + j)]; };
    for (int i = 0; i <= f; ++i)
      for (int j = 0; i + j <= f; ++j) {
        const int k = f - i - j;  // weight of a
        if (k == f) { at(i, j) = t[0]; continue; }
        if (i == f) { at(i, j) = t[1]; continue; }
        if (j == f) { at(i, j) = t[2]; continue; }
        const Vec3 p = geodesic_point(a, b, c, i, j, f);
        // On an edge: j == 0 (a-b), i == 0 (a-c), k == 0 (b-c).
        int u = -1, w = -1, step = 0;
        if (j == 0) u = t[0], w = t[1], step = i;
        else if (i == 0) u = t[0], w = t[2], step = j;
        else if (k == 0) u = t[1], w = t[2], step = j;
        if (u >= 0) {
          if (u > w) std::swap(u, w), step = f - step;
          const auto [it, added] = on_edge.try_emplace({u, w, step}, static_cast<int>(points.size()));
          if (added) points.push_back(p);
          at(i, j) = it->second;
        } else {
          at(i, j) = static_cast<int>(points.size());
          points.push_back(p);
        }
      }
    for (int i = 0; i < f; ++i)
      for (int j = 0; i + j < f; ++j) {
        faces.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        if (i + j + 2 <= f) faces.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
  }
  TriMesh mesh;
  std::vector<VH> handles;
  handles.reserve(points.size());
  for (const auto& p : points) handles.push_back(mesh.add_vertex(p * shape.radius));
  for (const auto& t : faces)
    mesh.add_face(handles[static_cast<std::size_t>(t[0])], handles[static_cast<std::size_t>(t[1])],
                  handles[static_cast<std::size_t>(t[2])]);
  if (shape.sqrt3) {
    // Kobbelt's sqrt(3) step without smoothing: a vertex at each face centre, then every old edge flipped.
    std::vector<TriMesh::EdgeHandle> old_edges(mesh.edges().begin(), mesh.edges().end());
    std::vector<TriMesh::FaceHandle> old_faces(mesh.faces().begin(), mesh.faces().end());
    for (const auto fh : old_faces) {
      Vec3 centre(0, 0, 0);
      for (auto v : mesh.fv_range(fh)) centre += mesh.point(v);
      mesh.split(fh, centre.normalized() * shape.radius);
    }
    for (const auto e : old_edges) mesh.flip(e);
  }
  icosahedral::even_out_on_sphere(mesh, shape.radius);
  mesh.update_normals();
  return mesh;
}

GeodesicSphereShape geodesic_sphere_for_faces(double faces, double radius) {
  GeodesicSphereShape best{radius, 1, false};
  double best_error = std::abs(20.0 - faces);
  for (int f = 1; f <= 1000; ++f)
    for (const bool sqrt3 : {false, true}) {
      const double count = 20.0 * f * f * (sqrt3 ? 3 : 1);
      const double error = std::abs(count - faces);
      if (error < best_error) best = {radius, f, sqrt3}, best_error = error;
    }
  return best;
}

TriMesh make_torus(const TorusShape& shape) {
  require_positive(shape.major_radius, "torus major radius");
  require_positive(shape.minor_radius, "torus minor radius");
  if (shape.minor_radius >= shape.major_radius)
    throw InputError("shape: torus minor radius must be smaller than the major radius");
  const std::size_t segments = segments_for(shape.minor_radius, shape.edge, 24);
  std::size_t rings = static_cast<std::size_t>(
      std::lround(2 * M_PI * shape.major_radius / ring_spacing(shape.minor_radius, segments)));
  rings = std::max<std::size_t>(6, rings + rings % 2);  // even: the half-step offsets close up
  std::vector<Vec3> centers;
  for (std::size_t i = 0; i < rings; ++i) {
    const double t = 2 * M_PI * static_cast<double>(i) / static_cast<double>(rings);
    centers.emplace_back(shape.major_radius * std::cos(t), shape.major_radius * std::sin(t), 0.0);
  }
  return sweep_tube(centers, true, shape.minor_radius, segments);
}

TriMesh make_helix(const HelixShape& shape) {
  require_positive(shape.radius, "helix radius");
  require_positive(shape.pitch, "helix pitch");
  require_positive(shape.turns, "helix turns");
  require_positive(shape.tube_radius, "helix tube radius");
  if (shape.tube_radius >= shape.radius) throw InputError("shape: helix tube radius must be smaller than its radius");
  if (2 * shape.tube_radius >= shape.pitch)
    throw InputError("shape: helix pitch must exceed the tube diameter (the coils would touch)");
  const std::size_t segments = segments_for(shape.tube_radius, shape.edge, 16);
  const double rise = shape.pitch / (2 * M_PI);
  const double arc_per_radian = std::sqrt(shape.radius * shape.radius + rise * rise);
  const double total_angle = 2 * M_PI * shape.turns;
  const std::size_t rings = std::max<std::size_t>(
      2, static_cast<std::size_t>(std::lround(total_angle * arc_per_radian / ring_spacing(shape.tube_radius, segments))) + 1);
  std::vector<Vec3> centers;
  for (std::size_t i = 0; i < rings; ++i) {
    const double t = total_angle * static_cast<double>(i) / static_cast<double>(rings - 1);
    centers.emplace_back(shape.radius * std::cos(t), shape.radius * std::sin(t), rise * t);
  }
  return sweep_tube(centers, false, shape.tube_radius, segments);
}

TriMesh make_capsule(const CapsuleShape& shape) {
  require_positive(shape.radius, "capsule radius");
  require_positive(shape.length, "capsule length");
  return straight_tube(shape.radius, shape.length, shape.edge, true);
}

TriMesh make_open_tube(const TubeShape& shape) {
  require_positive(shape.radius, "tube radius");
  require_positive(shape.length, "tube length");
  return straight_tube(shape.radius, shape.length, shape.edge, false);
}

const std::vector<std::string>& shape_names() {
  static const std::vector<std::string> names = {"sphere", "geodesic", "torus", "helix", "capsule", "capped-tube", "tube"};
  return names;
}

}  // namespace carbonmesh
