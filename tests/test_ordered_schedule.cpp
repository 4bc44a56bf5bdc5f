// OrderedSchedule (remesh/src/ordered_schedule.hpp): tasks whose balls may meet run in order, so tasks that each
// read and write a shared field within their ball give the field of one thread running them in order.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "ordered_schedule.hpp"

namespace {

using carbonmesh::OrderedSchedule;
using carbonmesh::Vec3;

// 3000 balls of radius 4 in a 60 x 60 x 10 box: each meets a dozen others, earlier and later.
std::vector<Vec3> centres() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> x(0.0, 60.0), z(0.0, 10.0);
  std::vector<Vec3> out;
  for (int k = 0; k < 3000; ++k) out.emplace_back(x(rng), x(rng), z(rng));
  return out;
}

constexpr double kRadius = 4.0;

TEST(OrderedSchedule, NoTaskStartsBeforeAnEarlierTaskWhoseBallMeetsItsOwnHasFinished) {
  const std::vector<Vec3> c = centres();
  std::vector<int> started(c.size(), -1), finished(c.size(), -1), runs(c.size(), 0);
  std::atomic<int> clock{0};
  OrderedSchedule(c, kRadius).run([&](std::size_t k, int) {
    started[k] = clock++;
    volatile double work = 0;  // long enough for the other thread to start tasks meanwhile
    for (int i = 0; i < 2000; ++i) work = work + std::sqrt(static_cast<double>(i));
    ++runs[k];
    finished[k] = clock++;
  });
  std::size_t meeting = 0;
  for (std::size_t j = 0; j < c.size(); ++j) {
    ASSERT_EQ(runs[j], 1) << "task " << j;
    for (std::size_t k = j + 1; k < c.size(); ++k)
      if ((c[j] - c[k]).norm() <= 2 * kRadius) {
        ++meeting;
        ASSERT_LT(finished[j], started[k]) << "tasks " << j << " and " << k;
      }
  }
  EXPECT_GT(meeting, 3000u);
}

// Each task adds to the points of a grid within its ball a value that depends on what it reads there.
std::vector<double> field_after(const std::vector<Vec3>& c, bool scheduled) {
  const int n = 61, layers = 11;
  std::vector<double> field(static_cast<std::size_t>(n * n * layers), 1.0);
  auto task = [&](std::size_t k) {
    const Vec3& p = c[k];
    double sum = 0;
    std::vector<std::size_t> inside;
    for (int x = 0; x < n; ++x)
      for (int y = 0; y < n; ++y)
        for (int z = 0; z < layers; ++z)
          if ((Vec3(x, y, z) - p).norm() <= kRadius) {
            const auto i = static_cast<std::size_t>((x * n + y) * layers + z);
            inside.push_back(i);
            sum += field[i];
          }
    for (auto i : inside) field[i] = std::fmod(field[i] * 1.5 + sum + static_cast<double>(k), 1000.0);
  };
  if (scheduled) {
    OrderedSchedule(c, kRadius).run([&](std::size_t k, int) { task(k); });
  } else {
    for (std::size_t k = 0; k < c.size(); ++k) task(k);
  }
  return field;
}

TEST(OrderedSchedule, GivesTheResultOfOneThreadTakingTheTasksInOrder) {
  std::vector<Vec3> c = centres();
  c.resize(600);
#ifdef _OPENMP
  omp_set_num_threads(std::max(2, omp_get_num_procs()));
#endif
  const std::vector<double> in_order = field_after(c, false), scheduled = field_after(c, true);
#ifdef _OPENMP
  omp_set_num_threads(omp_get_num_procs());
#endif
  EXPECT_EQ(in_order, scheduled);
}

// Whether the tasks ran inside a parallel region of two threads.
std::vector<char> in_parallel(const std::vector<Vec3>& c) {
  std::vector<char> out(c.size(), 0);
#ifdef _OPENMP
  omp_set_num_threads(2);
#endif
  std::vector<std::size_t> order;
  OrderedSchedule(c, kRadius).run([&](std::size_t k, int thread) {
#ifdef _OPENMP
    out[k] = omp_in_parallel() ? 1 : 0;
#endif
    if (out[k] == 0) {  // (alone: the order is the schedule's own)
      EXPECT_EQ(thread, 0);
      order.push_back(k);
    }
  });
#ifdef _OPENMP
  omp_set_num_threads(omp_get_num_procs());
#endif
  if (order.size() == c.size()) {
    for (std::size_t i = 0; i < order.size(); ++i) EXPECT_EQ(order[i], i);
  }
  return out;
}

TEST(OrderedSchedule, RunsAChainInOrderOnTheCallingThread) {
  // Each ball meets the one before it: no two tasks can run side by side, so no thread is woken for them.
  std::vector<Vec3> chain;
  for (int k = 0; k < 200; ++k) chain.emplace_back(0.1 * (k % 7), 0.2 * (k % 5), 0.05 * k);
  const std::vector<char> chained = in_parallel(chain);
  EXPECT_EQ(std::count(chained.begin(), chained.end(), 1), 0);
#ifdef _OPENMP
  // Balls apart from each other run in a parallel region (the other thread may take some).
  std::vector<Vec3> apart = centres();
  apart.resize(300);
  const std::vector<char> spread = in_parallel(apart);
  EXPECT_EQ(std::count(spread.begin(), spread.end(), 1), 300);
#endif
}

TEST(OrderedSchedule, RunsNothingForNoTasks) {
  int runs = 0;
  OrderedSchedule({}, 1.0).run([&](std::size_t, int) { ++runs; });
  EXPECT_EQ(runs, 0);
}

}  // namespace
