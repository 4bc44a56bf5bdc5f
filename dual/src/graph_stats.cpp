#include "carbonmesh/dual/graph_stats.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

namespace carbonmesh {

SampleStats sample_stats(const std::vector<double>& values) {
  SampleStats s;
  s.count = values.size();
  if (values.empty()) return s;
  s.min = *std::min_element(values.begin(), values.end());
  s.max = *std::max_element(values.begin(), values.end());
  double sum = 0;
  for (double v : values) sum += v;
  s.mean = sum / static_cast<double>(values.size());
  double sq = 0;
  for (double v : values) sq += (v - s.mean) * (v - s.mean);
  s.std = std::sqrt(sq / static_cast<double>(values.size()));
  return s;
}

std::vector<AtomTriple> bond_angles(std::size_t atoms, const std::vector<std::array<int, 2>>& bonds) {
  std::vector<std::vector<int>> neighbours(atoms);
  for (const auto& b : bonds) {
    neighbours[static_cast<std::size_t>(b[0])].push_back(b[1]);
    neighbours[static_cast<std::size_t>(b[1])].push_back(b[0]);
  }
  std::vector<AtomTriple> out;
  for (std::size_t i = 0; i < atoms; ++i) {
    auto& n = neighbours[i];
    std::sort(n.begin(), n.end());
    for (std::size_t a = 0; a < n.size(); ++a)
      for (std::size_t b = a + 1; b < n.size(); ++b) out.push_back({n[a], static_cast<int>(i), n[b]});
  }
  return out;
}

std::vector<double> bond_lengths(const std::vector<Vec3>& positions, const std::vector<std::array<int, 2>>& bonds) {
  std::vector<double> out;
  out.reserve(bonds.size());
  for (const auto& b : bonds)
    out.push_back((positions[static_cast<std::size_t>(b[0])] - positions[static_cast<std::size_t>(b[1])]).norm());
  return out;
}

std::vector<double> angle_degrees(const std::vector<Vec3>& positions, const std::vector<AtomTriple>& angles) {
  std::vector<double> out;
  out.reserve(angles.size());
  for (const auto& t : angles) {
    const Vec3& c = positions[static_cast<std::size_t>(t[1])];
    const Vec3 u = positions[static_cast<std::size_t>(t[0])] - c, v = positions[static_cast<std::size_t>(t[2])] - c;
    const double cosine = std::clamp(OpenMesh::dot(u, v) / (u.norm() * v.norm()), -1.0, 1.0);
    out.push_back(std::acos(cosine) * 180.0 / std::numbers::pi);
  }
  return out;
}

nlohmann::json to_json(const SampleStats& s) {
  return {{"count", s.count}, {"min", s.min}, {"mean", s.mean}, {"std", s.std}, {"max", s.max}};
}

}  // namespace carbonmesh
