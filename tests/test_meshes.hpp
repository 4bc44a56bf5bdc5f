#pragma once
// Helpers shared by the remesher tests.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh::test {

// A mesh of the given points and triangles (vertex indices, counter-clockwise seen from outside).
inline TriMesh mesh_from(const std::vector<Vec3>& points, const std::vector<std::array<int, 3>>& triangles) {
  TriMesh mesh;
  std::vector<TriMesh::VertexHandle> v;
  for (const auto& p : points) v.push_back(mesh.add_vertex(p));
  for (const auto& t : triangles) {
    const auto f = mesh.add_face(v[t[0]], v[t[1]], v[t[2]]);
    EXPECT_TRUE(f.is_valid());
  }
  return mesh;
}

// The triangles of a mesh as vertex indices, in face order (mesh_from's inverse).
inline std::vector<std::array<int, 3>> triangles_of(const TriMesh& mesh) {
  std::vector<std::array<int, 3>> out;
  for (auto f : mesh.faces()) {
    std::array<int, 3> t{};
    int k = 0;
    for (auto v : mesh.fv_range(f)) t[static_cast<std::size_t>(k++)] = v.idx();
    out.push_back(t);
  }
  return out;
}

// Scales a mesh about the origin so that its mean edge length is `mean`.
inline TriMesh scaled(TriMesh mesh, double mean) {
  const double factor = mean / edge_stats(mesh).mean;
  for (auto v : mesh.vertices()) mesh.set_point(v, mesh.point(v) * factor);
  return mesh;
}

// Scales coordinate `axis` (0 x, 1 y, 2 z) of every vertex by `factor` (an ellipsoid or a disc from a sphere).
inline TriMesh stretched(TriMesh mesh, int axis, double factor) {
  for (auto v : mesh.vertices()) {
    Vec3 p = mesh.point(v);
    p[axis] *= factor;
    mesh.set_point(v, p);
  }
  return mesh;
}

// `mesh` with every vertex moved along its position vector by a factor 1 + N(0, sigma): a sphere centred at the
// origin with radial noise (fixed seed).
inline TriMesh radial_noise(TriMesh mesh, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  for (auto v : mesh.vertices()) mesh.set_point(v, mesh.point(v) * (1 + noise(rng)));
  return mesh;
}

// Half a cylinder about the z axis (angles 0 to pi, heights 0 to `length`), a 20 x 16 grid whose inner points are
// moved along the surface (so its triangles differ and are not parallel to the axis): one border, four straight sides
// once unrolled, the two along the axis `length` long.
inline TriMesh half_cylinder(double radius, double length) {
  std::vector<Vec3> points;
  std::vector<std::array<int, 3>> triangles;
  const int nt = 20, nz = 16;
  const double pi = std::acos(-1.0);
  for (int i = 0; i <= nt; ++i)
    for (int j = 0; j <= nz; ++j) {
      const bool rim = i == 0 || i == nt || j == 0 || j == nz;
      const double theta = pi * i / nt + (rim ? 0 : 0.03 * std::sin(7.0 * i * j));
      const double z = length * j / nz + (rim ? 0 : 0.0125 * length * std::cos(5.0 * i + j));
      points.emplace_back(radius * std::cos(theta), radius * std::sin(theta), z);
    }
  for (int i = 0; i < nt; ++i)
    for (int j = 0; j < nz; ++j) {
      const int p = i * (nz + 1) + j, q = p + nz + 1;
      triangles.push_back({p, q, q + 1});
      triangles.push_back({p, q + 1, p + 1});
    }
  return mesh_from(points, triangles);
}

// `mesh` turned about the axis (1, 2, 3) by 0.7 rad and shifted by (5, -3, 2): in no coordinate plane or axis.
inline TriMesh tilted(TriMesh mesh) {
  Vec3 k(1, 2, 3);
  k.normalize();
  const double c = std::cos(0.7), s = std::sin(0.7);
  for (auto v : mesh.vertices()) {
    const Vec3 p = mesh.point(v);  // Rodrigues' rotation
    mesh.set_point(v, c * p + s * OpenMesh::cross(k, p) + (1 - c) * OpenMesh::dot(k, p) * k + Vec3(5, -3, 2));
  }
  return mesh;
}

// A flat equilateral triangle of side `side` in the z = 0 plane, cut into n^2 equilateral triangles (n per side),
// facing +z: its three corners are 60 degrees, each a triangle with two border edges.
inline TriMesh triangle_sheet(int n, double side) {
  std::vector<Vec3> points;
  std::vector<std::vector<int>> index(static_cast<std::size_t>(n) + 1);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i + j <= n; ++i) {
      index[static_cast<std::size_t>(j)].push_back(static_cast<int>(points.size()));
      points.emplace_back(side * (i + 0.5 * j) / n, side * (std::sqrt(3.0) / 2) * j / n, 0.0);
    }
  auto at = [&](int i, int j) { return index[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)]; };
  std::vector<std::array<int, 3>> triangles;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i + j < n; ++i) {
      triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
      if (i + j + 1 < n) triangles.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return mesh_from(points, triangles);
}

// Adds a copy of `from`, scaled by `scale` about the origin and then shifted by `shift`, to `to` as another
// component.
inline void append_copy(TriMesh& to, const TriMesh& from, const Vec3& shift, double scale = 1.0) {
  std::vector<TriMesh::VertexHandle> map;
  for (auto v : from.vertices()) map.push_back(to.add_vertex(scale * from.point(v) + shift));
  for (auto f : from.faces()) {
    std::vector<TriMesh::VertexHandle> corners;
    for (auto v : from.fv_range(f)) corners.push_back(map[static_cast<std::size_t>(v.idx())]);
    to.add_face(corners);
  }
}

}  // namespace carbonmesh::test
