// The energy of the dual optimisation (internal to dual): its gradient against finite differences, on a net
// where every term is active, in one thread and in parallel, and the same bits for any thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "carbonmesh/dual/dual_mesh.hpp"
#include "carbonmesh/dual/graph_stats.hpp"
#include "carbonmesh/remesh/shapes.hpp"
#include "dual_energy.hpp"

using namespace carbonmesh;

namespace {

// The dual of a torus with its atoms shaken by up to `shake` A: bonds off the window, angles below 90 degrees
// (two-bond contacts) and atoms off the surface. The thin torus also has pairs across its tube within r_c.
struct Problem {
  TriMesh surface;
  Dual dual;
  std::vector<AtomTriple> angles;
  std::vector<double> targets;
  std::vector<int> faces;
  Eigen::VectorXd x;

  Problem(const TorusShape& shape, double shake) : surface(make_torus(shape)), dual(build_dual(surface)) {
    angles = bond_angles(dual.atoms(), dual.bonds);
    targets.assign(angles.size(), -0.5);
    for (std::size_t a = 0; a < angles.size(); a += 7) targets[a] = std::cos(108.0 * M_PI / 180);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-shake, shake);
    std::vector<Vec3> p = dual.positions();
    for (Vec3& q : p) q += Vec3(u(rng), u(rng), u(rng));
    const detail::SurfaceProjector projector(surface);
    std::vector<Vec3> closest;
    projector.closest_points(p, closest, faces);
    x.resize(static_cast<Eigen::Index>(3 * p.size() + 1));
    for (std::size_t i = 0; i < p.size(); ++i)
      for (int c = 0; c < 3; ++c) x[static_cast<Eigen::Index>(3 * i + c)] = p[i][c];
    x[x.size() - 1] = 0.3;  // a scale a little above 1
  }
};

// Central differences on `count` coordinates spread over x, and on the scale.
void expect_gradient_matches(const Problem& problem, int count) {
  const detail::SurfaceProjector projector(problem.surface);
  const DualOptimizeSettings settings;
  detail::DualEnergy energy(problem.dual.bonds, problem.angles, problem.targets, projector, 10.0, problem.faces,
                            settings);
  Eigen::VectorXd g, scratch;
  Eigen::VectorXd x = problem.x;
  energy(x, g);
  const Eigen::Index n = x.size();
  constexpr double h = 1e-5;
  for (int k = 0; k <= count; ++k) {
    const Eigen::Index i = k == count ? n - 1 : (static_cast<Eigen::Index>(k) * 7919) % (n - 1);
    const double keep = x[i];
    x[i] = keep + h;
    const double up = energy(x, scratch);
    x[i] = keep - h;
    const double down = energy(x, scratch);
    x[i] = keep;
    const double numeric = (up - down) / (2 * h);
    EXPECT_NEAR(g[i], numeric, 1e-4 * std::max(1.0, std::abs(numeric))) << "coordinate " << i;
  }
}

}  // namespace

// 1200 atoms (one thread): a torus of tube radius 1.2 A, thinner than the bond scale.
TEST(DualEnergy, GradientMatchesFiniteDifferencesOnASmallNet) {
  const Problem problem({3.0, 1.2, std::sqrt(3.0) * 1.42}, 0.25);
  ASSERT_LT(problem.dual.atoms(), detail::DualEnergy::kParallelAtoms);
  expect_gradient_matches(problem, 150);
}

// Above kParallelAtoms: the parallel evaluation.
TEST(DualEnergy, GradientMatchesFiniteDifferencesOnALargeNet) {
  const Problem problem({60.0, 24.0, std::sqrt(3.0) * 1.42}, 0.25);
  ASSERT_GE(problem.dual.atoms(), detail::DualEnergy::kParallelAtoms);
  expect_gradient_matches(problem, 150);
}

TEST(DualEnergy, SameBitsForOneAndTwoThreads) {
#ifndef _OPENMP
  GTEST_SKIP() << "built without OpenMP";
#else
  const Problem problem({60.0, 24.0, std::sqrt(3.0) * 1.42}, 0.25);
  const detail::SurfaceProjector projector(problem.surface);
  const DualOptimizeSettings settings;
  auto evaluate = [&](int threads, Eigen::VectorXd& g) {
    omp_set_num_threads(threads);
    detail::DualEnergy energy(problem.dual.bonds, problem.angles, problem.targets, projector, 10.0, problem.faces,
                              settings);
    return energy(problem.x, g);
  };
  Eigen::VectorXd one, two;
  const double e1 = evaluate(1, one), e2 = evaluate(2, two);
  omp_set_num_threads(omp_get_num_procs());
  EXPECT_EQ(e1, e2);
  EXPECT_TRUE(one == two);
#endif
}
