#pragma once
// Bond length and bond angle statistics of an atom network given as positions and bonds.
#include <array>
#include <cstddef>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

using AtomTriple = std::array<int, 3>;  // an angle j-i-k: {j, i, k} with the vertex atom i in the middle, j < k

struct SampleStats {
  std::size_t count = 0;
  double min = 0, mean = 0, std = 0, max = 0;  // std: population standard deviation
};
SampleStats sample_stats(const std::vector<double>& values);

// Every pair of bonds sharing an atom, ordered by vertex atom then by (j, k).
std::vector<AtomTriple> bond_angles(std::size_t atoms, const std::vector<std::array<int, 2>>& bonds);

std::vector<double> bond_lengths(const std::vector<Vec3>& positions, const std::vector<std::array<int, 2>>& bonds);
std::vector<double> angle_degrees(const std::vector<Vec3>& positions, const std::vector<AtomTriple>& angles);

nlohmann::json to_json(const SampleStats& s);

}  // namespace carbonmesh
