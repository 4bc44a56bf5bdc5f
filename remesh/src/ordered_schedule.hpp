#pragma once
// Tasks on every thread with the result of one thread running them in order. Each task reads and writes the mesh
// only near a point, within a radius common to all; a task starts once every earlier task whose ball may meet its
// own has finished, so tasks that run at the same time touch nothing in common; where that leaves one order only, they
// run in it on the calling thread. Internal (regularize's chains, the minimax fit's spots).
#include <algorithm>
#include <array>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <queue>
#include <utility>
#include <vector>

#include "carbonmesh/remesh/mesh.hpp"
#include "threads.hpp"

namespace carbonmesh {

class OrderedSchedule {
 public:
  // Task k touches the mesh only within `radius` of centres[k].
  OrderedSchedule(const std::vector<Vec3>& centres, double radius) : tasks_(centres.size()) {
    // Two balls that meet share a point, and that point's cell lies in the boxes of both: the cells (side 2 radius,
    // at most 8 per ball) of each ball's bounding box stand for it.
    Vec3 origin(0, 0, 0), top(0, 0, 0);
    for (std::size_t k = 0; k < tasks_; ++k)
      for (int a = 0; a < 3; ++a) {
        origin[a] = k == 0 ? centres[k][a] : std::min(origin[a], centres[k][a]);
        top[a] = k == 0 ? centres[k][a] : std::max(top[a], centres[k][a]);
      }
    // (Cell coordinates fit in 20 bits, and side >= radius keeps them >= 0 with the + 1 of cell(): a negative one
    // would run into the other coordinates' bits of key(). Cells of side radius or less gave regularize's chains no
    // more parallelism on bunny and fertility, session 25.)
    double side = 2 * radius;
    for (int a = 0; a < 3; ++a) side = std::max(side, (top[a] - origin[a] + 2 * radius) / double(1 << 20));
    std::vector<std::pair<std::uint64_t, int>> pairs;  // (cell key, task)
    for (std::size_t k = 0; k < tasks_; ++k) {
      std::array<std::int64_t, 3> lo{}, hi{};
      for (int a = 0; a < 3; ++a) {
        lo[static_cast<std::size_t>(a)] = cell(centres[k][a] - radius - origin[a], side);
        hi[static_cast<std::size_t>(a)] = cell(centres[k][a] + radius - origin[a], side);
      }
      for (auto x = lo[0]; x <= hi[0]; ++x)
        for (auto y = lo[1]; y <= hi[1]; ++y)
          for (auto z = lo[2]; z <= hi[2]; ++z) pairs.emplace_back(key(x, y, z), static_cast<int>(k));
    }
    std::sort(pairs.begin(), pairs.end());
    // Per cell its tasks in ascending order (the queue a task must head in every cell of its own to start), and
    // per task its cells.
    std::vector<int> count(tasks_ + 1, 0);
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      if (i == 0 || pairs[i].first != pairs[i - 1].first) queue_begin_.push_back(static_cast<int>(i));
      queue_.push_back(pairs[i].second);
      ++count[static_cast<std::size_t>(pairs[i].second) + 1];
    }
    queue_begin_.push_back(static_cast<int>(pairs.size()));
    for (std::size_t k = 0; k < tasks_; ++k) count[k + 1] += count[k];
    cell_begin_ = count;
    cells_.resize(pairs.size());
    std::vector<int> fill(count.begin(), count.end() - 1);
    for (std::size_t c = 0; c + 1 < queue_begin_.size(); ++c)
      for (int i = queue_begin_[c]; i < queue_begin_[c + 1]; ++i)
        cells_[static_cast<std::size_t>(fill[static_cast<std::size_t>(queue_[static_cast<std::size_t>(i)])]++)] =
            static_cast<int>(c);
    // When each task shares a cell with the one before it, every task waits for the one before: no two ever run at
    // the same time (every pass of regularize's chains on bunny and the sphere, cells 39.6 wide on surfaces 75 and 21
    // across), and run() takes them in order on the calling thread.
    chain_ = true;
    for (std::size_t k = 1; k < tasks_ && chain_; ++k) chain_ = share_cell(k - 1, k);
  }

  // Runs run(k, thread) for every task k: on every thread, or in order on the calling thread for a chain.
  void run(const std::function<void(std::size_t, int)>& run) {
    if (tasks_ == 0) return;
    if (chain_) {  // in order on this thread, without waking the others for nothing
      for (std::size_t k = 0; k < tasks_; ++k) run(k, thread_index());
      return;
    }
    std::vector<int> head(queue_begin_.begin(), queue_begin_.end() - 1);  // the first unfinished task of each cell
    std::vector<int> heading(tasks_, 0);  // the cells a task heads
    std::priority_queue<int, std::vector<int>, std::greater<int>> ready;
    for (std::size_t c = 0; c < head.size(); ++c)
      ++heading[static_cast<std::size_t>(queue_[static_cast<std::size_t>(head[c])])];
    for (std::size_t k = 0; k < tasks_; ++k)
      if (heading[k] == cell_begin_[k + 1] - cell_begin_[k]) ready.push(static_cast<int>(k));
    std::size_t finished = 0;
    std::mutex mutex;
    std::condition_variable wake;
#pragma omp parallel
    {
      const int thread = thread_index();
      // A thread that finishes a task takes the next ready one itself; a sleeping thread is woken only for a second
      // ready task (most tasks take a microsecond: a wake-up per task cost more than the tasks).
      std::unique_lock<std::mutex> lock(mutex);
      for (;;) {
        wake.wait(lock, [&] { return !ready.empty() || finished == tasks_; });
        if (ready.empty()) break;  // every task finished
        const int k = ready.top();
        ready.pop();
        if (!ready.empty()) wake.notify_one();
        lock.unlock();
        run(static_cast<std::size_t>(k), thread);
        lock.lock();
        ++finished;
        for (int j = cell_begin_[static_cast<std::size_t>(k)]; j < cell_begin_[static_cast<std::size_t>(k) + 1]; ++j) {
          const auto c = static_cast<std::size_t>(cells_[static_cast<std::size_t>(j)]);
          if (++head[c] == queue_begin_[c + 1]) continue;
          const auto next = static_cast<std::size_t>(queue_[static_cast<std::size_t>(head[c])]);
          if (++heading[next] == cell_begin_[next + 1] - cell_begin_[next]) ready.push(static_cast<int>(next));
        }
        if (finished == tasks_) wake.notify_all();
      }
    }
  }

 private:
  bool share_cell(std::size_t a, std::size_t b) const {
    for (int i = cell_begin_[a]; i < cell_begin_[a + 1]; ++i)
      for (int j = cell_begin_[b]; j < cell_begin_[b + 1]; ++j)
        if (cells_[static_cast<std::size_t>(i)] == cells_[static_cast<std::size_t>(j)]) return true;
    return false;
  }
  static std::int64_t cell(double x, double side) { return static_cast<std::int64_t>(std::floor(x / side)) + 1; }
  static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z) {
    const auto u = [](std::int64_t c) { return static_cast<std::uint64_t>(c); };
    return (u(x) << 42) | (u(y) << 21) | u(z);
  }

  std::size_t tasks_;
  std::vector<int> queue_begin_, queue_;  // per cell (CSR): its tasks, ascending
  std::vector<int> cell_begin_, cells_;   // per task (CSR): its cells
  bool chain_ = false;                    // every task waits for the one before it
};

}  // namespace carbonmesh
