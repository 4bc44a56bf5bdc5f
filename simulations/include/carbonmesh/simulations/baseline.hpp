#pragma once
// The baseline of `carbonmesh simulate --baseline` (the dissertation's chapter 6 experiment): the input surface
// WITHOUT remeshing, its dual as it is (atom per triangle centroid, no optimisation), scaled so its mean C-C
// bond equals the mean bond of the built structure, written like a build (write_structure_files).
#include <cstddef>
#include <filesystem>
#include <map>
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace carbonmesh {

struct BaselineSettings {
  std::filesystem::path build_dir;   // the built structure: structure.data and summary.json
  std::filesystem::path input;       // the input mesh; empty: "input" of build_dir/summary.json
  std::filesystem::path output_dir;  // empty: build_dir / "baseline"
  double cutoff = 1.85;              // C-C bonds of the built structure (for its mean bond)
};

struct BaselineBuild {
  std::string input;                 // the mesh used (or the built-in shape)
  std::filesystem::path output_dir;
  std::size_t atoms = 0, carbon_atoms = 0, hydrogen_atoms = 0, bonds = 0;
  std::map<int, std::size_t> rings_by_size;
  double percent_three_bonds = 0;
  double built_mean_bond = 0;        // target (Angstrom)
  double dual_mean_bond = 0;         // of the dual before scaling (input units)
  double factor = 0;                 // scale applied to the dual
  double min_bond = 0, max_bond = 0;  // after scaling
};

// Throws InputError when the input cannot be found (summary.json records no readable file: pass the mesh).
BaselineBuild build_baseline(const BaselineSettings& settings);

nlohmann::json to_json(const BaselineBuild& b);

}  // namespace carbonmesh
