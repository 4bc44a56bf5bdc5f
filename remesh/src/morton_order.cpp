#include "carbonmesh/remesh/morton_order.hpp"

#include <algorithm>
#include <cstdint>

namespace carbonmesh {
namespace {

// The 21 low bits of v spread to every third of 63 bits.
std::uint64_t spread(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

}  // namespace

std::vector<int> morton_order(const std::vector<Vec3>& points) {
  const std::size_t n = points.size();
  std::vector<int> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<int>(i);
  if (n == 0) return order;
  Vec3 lo = points[0], hi = points[0];
  for (const auto& p : points) lo.minimize(p), hi.maximize(p);
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-300});
  std::vector<std::uint64_t> key(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t code = 0;
    for (int k = 0; k < 3; ++k) {
      const double t = (points[i][k] - lo[k]) / extent;  // [0, 1]
      code |= spread(static_cast<std::uint64_t>(std::clamp(t, 0.0, 1.0) * 2097151.0)) << k;
    }
    key[i] = code;
  }
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const auto ka = key[static_cast<std::size_t>(a)], kb = key[static_cast<std::size_t>(b)];
    return ka != kb ? ka < kb : a < b;
  });
  return order;
}

}  // namespace carbonmesh
