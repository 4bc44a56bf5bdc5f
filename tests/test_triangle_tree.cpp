// The AABB tree's closest-point queries (triangle_tree::Traits: Ericson's closest point on a triangle in CGAL's tree)
// against CGAL's own projection and against a search of every triangle.
#include <gtest/gtest.h>

#include <CGAL/squared_distance_3.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "carbonmesh/remesh/shapes.hpp"
#include "carbonmesh/remesh/triangle_tree.hpp"

using namespace carbonmesh;
using namespace carbonmesh::triangle_tree;

namespace {

double area(const Triangle& t) { return std::sqrt(t.squared_area()); }

}  // namespace

// Points all around random triangles (acute, obtuse, long and thin), so that every region of the closest point is
// met: the three corners, the three edges and the inside.
TEST(TriangleTree, ClosestPointOnATriangleIsCGALsProjection) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), around(-2.5, 2.5);
  const Kernel::Construct_projected_point_3 project;
  int regions[3] = {0, 0, 0};  // closest point at a corner, on an edge, inside
  for (int k = 0; k < 4000; ++k) {
    Point a(unit(rng), unit(rng), unit(rng)), b(unit(rng), unit(rng), unit(rng)), c(unit(rng), unit(rng), unit(rng));
    if (k % 4 == 3) c = Point(a.x() + 0.01 * unit(rng), a.y() + 0.01 * unit(rng), a.z() + 0.01 * unit(rng));  // thin
    const Triangle t(a, b, c);
    if (area(t) < 1e-6) continue;
    for (int j = 0; j < 8; ++j) {
      const Point p(around(rng), around(rng), around(rng));
      const Point ours = closest_point_on(t, p), cgal = project(t, p);
      ASSERT_LT(std::sqrt(CGAL::squared_distance(ours, cgal)), 1e-9) << "triangle " << t << ", point " << p;
      const bool corner = ours == a || ours == b || ours == c;
      const double to_plane =
          std::abs(CGAL::squared_distance(p, t.supporting_plane()) - CGAL::squared_distance(p, ours));
      ++regions[corner ? 0 : (to_plane < 1e-12 ? 2 : 1)];
    }
  }
  for (const int count : regions) EXPECT_GT(count, 100);
}

// The tree's distance and closest point are those of the nearest of all the triangles.
TEST(TriangleTree, DistanceIsTheNearestTriangles) {
  const Triangles triangles = triangles_of(make_icosphere({5.0, 3}));
  Tree tree(triangles.begin(), triangles.end());
  tree.build();
  tree.accelerate_distance_queries();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> around(-8.0, 8.0);
  for (int k = 0; k < 500; ++k) {
    const Point q(around(rng), around(rng), around(rng));
    double nearest = std::numeric_limits<double>::infinity();
    for (const Triangle& t : triangles) nearest = std::min(nearest, CGAL::squared_distance(q, t));
    const auto [closest, primitive] = tree.closest_point_and_primitive(q);
    EXPECT_NEAR(tree.squared_distance(q), nearest, 1e-9 * (1 + nearest));
    EXPECT_NEAR(CGAL::squared_distance(q, closest), nearest, 1e-9 * (1 + nearest));
    EXPECT_NEAR(CGAL::squared_distance(q, *primitive), nearest, 1e-9 * (1 + nearest));
  }
}

// closest_points_from_hints() names the tree's own closest point and primitive: groups of 12 points around a face
// of a coarser, noisy sphere (the surface fit's samples), each from the hint of a point nearby (its last position).
TEST(TriangleTree, ClosestPointsFromHintsAreTheTreesResults) {
  TriMesh surface = make_icosphere({5.0, 3});
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> noise(-0.05, 0.05), unit(0.0, 1.0), step(-0.2, 0.2);
  for (auto v : surface.vertices()) surface.point(v) += Vec3(noise(rng), noise(rng), noise(rng));
  const Triangles triangles = triangles_of(surface);
  Tree tree(triangles.begin(), triangles.end());
  tree.build();
  tree.accelerate_distance_queries();
  const Triangles coarse = triangles_of(make_icosphere({5.3, 2}));
  std::vector<Tree::Primitive_id> listed;
  std::size_t moved = 0;
  for (const Triangle& t : coarse) {
    std::array<Point, 12> points;
    std::array<Tree::Point_and_primitive_id, 12> hints, expected;
    for (std::size_t q = 0; q < points.size(); ++q) {
      double u = unit(rng), v = unit(rng);
      if (u + v > 1) u = 1 - u, v = 1 - v;
      const Point p = t[0] + u * (t[1] - t[0]) + v * (t[2] - t[0]);
      hints[q] = tree.closest_point_and_primitive(Point(p.x() + step(rng), p.y() + step(rng), p.z() + step(rng)));
      points[q] = p;
      expected[q] = tree.closest_point_and_primitive(p, hints[q]);
      moved += expected[q].second != hints[q].second;
    }
    closest_points_from_hints(tree, points.data(), hints.data(), points.size(), listed);
    for (std::size_t q = 0; q < points.size(); ++q) {
      ASSERT_EQ(hints[q].first, expected[q].first) << "point " << points[q];
      ASSERT_EQ(hints[q].second, expected[q].second) << "point " << points[q];
    }
  }
  EXPECT_GT(moved, coarse.size());  // most hints were not the answer
}

// face_distance() (each point's search started from the closest point of the point before) gives the largest of
// the tree's own distances of the face's seven points, and that is the largest distance to the nearest triangle of
// all: faces of a coarser sphere, some moved off the surface, against a finer noisy one.
TEST(TriangleTree, FaceDistanceIsTheLargestOfItsSevenPointsDistances) {
  TriMesh surface = make_icosphere({5.0, 3});
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> noise(-0.05, 0.05), scale(0.8, 1.3);
  for (auto v : surface.vertices()) surface.point(v) += Vec3(noise(rng), noise(rng), noise(rng));
  const Triangles triangles = triangles_of(surface);
  Tree tree(triangles.begin(), triangles.end());
  tree.build();
  tree.accelerate_distance_queries();
  const TriMesh coarse = make_icosphere({5.0, 2});
  double largest = 0;
  for (auto f : coarse.faces()) {
    Vec3 a, b, c;
    auto fv = coarse.cfv_begin(f);
    a = coarse.point(*fv), b = coarse.point(*++fv), c = coarse.point(*++fv);
    const double s = scale(rng);
    a *= s, b *= s, c *= s;
    const Vec3 g = (a + b + c) / 3.0;
    double tree_worst = 0, all_worst = 0;
    for (const Vec3& p : {g, 0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a), (2.0 * g + a) / 3.0, (2.0 * g + b) / 3.0,
                          (2.0 * g + c) / 3.0}) {
      tree_worst = std::max(tree_worst, tree.squared_distance(to_point(p)));
      double nearest = std::numeric_limits<double>::infinity();
      for (const Triangle& t : triangles) nearest = std::min(nearest, CGAL::squared_distance(to_point(p), t));
      all_worst = std::max(all_worst, nearest);
    }
    const double d = face_distance(tree, a, b, c);
    ASSERT_EQ(d, std::sqrt(tree_worst)) << "face " << f.idx();
    ASSERT_NEAR(d, std::sqrt(all_worst), 1e-9) << "face " << f.idx();
    largest = std::max(largest, d);
  }
  EXPECT_GT(largest, 1.0);  // faces well off the surface too
}
