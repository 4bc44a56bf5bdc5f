#include "carbonmesh/simulations/baseline.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "carbonmesh/carbon/lammps_data.hpp"
#include "carbonmesh/carbon/output_files.hpp"
#include "carbonmesh/carbon/passivate.hpp"
#include "carbonmesh/carbon/structure.hpp"
#include "carbonmesh/dual/dual_mesh.hpp"
#include "carbonmesh/remesh/atomic_file.hpp"
#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/io.hpp"
#include "carbonmesh/remesh/shapes.hpp"
#include "carbonmesh/simulations/atom_graph.hpp"

namespace carbonmesh {
namespace fs = std::filesystem;
namespace {

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

// The input mesh: explicit, else what summary.json records (a file, or the built-in sphere).
TriMesh load_input(const BaselineSettings& s, std::string& name, bool& hydrogen) {
  const fs::path summary_file = s.build_dir / "summary.json";
  nlohmann::json summary;
  if (std::ifstream f(summary_file); f) summary = nlohmann::json::parse(f, nullptr, false);
  hydrogen = summary.is_object() && summary.value("hydrogen_atoms", 0) > 0;
  if (!s.input.empty()) {
    name = s.input.string();
    return load_mesh(s.input);
  }
  if (!summary.is_object() || !summary.contains("input") || !summary["input"].is_string())
    throw InputError(fmt::format("{}: no input recorded; pass the input mesh with --baseline-input MESH",
                                 summary_file.string()));
  name = summary["input"].get<std::string>();
  // The built-in sphere of `build` is the geodesic triangulation whose dual is a fullerene already: its baseline
  // is the default icosphere (1280 triangles, what `carbonmesh shape sphere` writes), a plain triangulation of it.
  if (starts_with(name, "built-in sphere")) return make_icosphere(SphereShape{});
  std::error_code ec;
  if (!fs::is_regular_file(name, ec))
    throw InputError(fmt::format("{} records input '{}', which is not a file from here; pass it with "
                                 "--baseline-input MESH",
                                 summary_file.string(), name));
  return load_mesh(name);
}

double mean_length(const std::vector<Vec3>& p, const std::vector<AtomPair>& bonds) {
  double sum = 0;
  for (const auto& b : bonds) sum += (p[b[0]] - p[b[1]]).norm();
  return bonds.empty() ? 0 : sum / static_cast<double>(bonds.size());
}

}  // namespace

BaselineBuild build_baseline(const BaselineSettings& s) {
  BaselineBuild b;
  b.output_dir = s.output_dir.empty() ? s.build_dir / "baseline" : s.output_dir;
  bool hydrogen = false;
  TriMesh mesh = load_input(s, b.input, hydrogen);

  // Mean C-C bond of the built structure (cutoff graph of its carbon atoms).
  const LammpsData built = read_lammps_data(s.build_dir / "structure.data");
  std::vector<Vec3> carbon;
  for (std::size_t i = 0; i < built.positions.size(); ++i) {
    const int t = built.types[i];
    const double mass = t >= 1 && static_cast<std::size_t>(t) <= built.masses.size() ? built.masses[t - 1] : 0;
    if (!(mass > 0 && mass < 1.5)) carbon.push_back(built.positions[i]);
  }
  const auto built_bonds = bonds_by_cutoff(carbon, s.cutoff);
  if (built_bonds.empty()) throw InputError((s.build_dir / "structure.data").string() + ": no C-C bonds");
  double sum = 0;
  for (const auto& bd : built_bonds) sum += (carbon[bd[0]] - carbon[bd[1]]).norm();
  b.built_mean_bond = sum / static_cast<double>(built_bonds.size());

  // The dual as it is, scaled about the origin.
  Dual dual = build_dual(mesh);
  std::vector<Vec3> p = dual.positions();
  b.dual_mean_bond = mean_length(p, dual.bonds);
  if (!(b.dual_mean_bond > 0)) throw InputError(b.input + ": the dual has no bonds");
  b.factor = b.built_mean_bond / b.dual_mean_bond;
  for (auto& x : p) x *= b.factor;
  dual.set_positions(p);
  CarbonStructure structure = carbon_structure(dual);
  if (hydrogen) passivate(structure);  // like the build it is compared with
  b.min_bond = 1e300, b.max_bond = 0;
  for (const auto& bd : dual.bonds) {
    const double l = (p[bd[0]] - p[bd[1]]).norm();
    b.min_bond = std::min(b.min_bond, l), b.max_bond = std::max(b.max_bond, l);
  }
  b.atoms = structure.atoms();
  b.carbon_atoms = structure.count(Element::C);
  b.hydrogen_atoms = structure.count(Element::H);
  b.bonds = structure.bonds.size();
  b.rings_by_size = dual.counts.ring_sizes;
  b.percent_three_bonds = dual.counts.percent_three_bonds;
  OutputSettings output;
  output.data.topology = built.atom_style == "full";
  write_structure_files(b.output_dir, structure, dual.mesh, output);
  const nlohmann::json summary = to_json(b);
  write_atomically(b.output_dir / "summary.json", [&summary](const fs::path& tmp) {
    std::ofstream f(tmp);
    f << summary.dump(2) << "\n";
    if (!f) throw std::runtime_error("cannot write " + tmp.string());
  });
  spdlog::info("baseline: dual of {} as it is, {} atoms, bonds scaled by {:.6g} to mean {:.4f} A (min {:.4f}, max "
               "{:.4f}) -> {}",
               b.input, b.atoms, b.factor, b.built_mean_bond, b.min_bond, b.max_bond, b.output_dir.string());
  return b;
}

nlohmann::json to_json(const BaselineBuild& b) {
  nlohmann::json rings = nlohmann::json::object();
  for (const auto& [k, v] : b.rings_by_size) rings[std::to_string(k)] = v;
  return {{"kind", "baseline: dual of the input without remeshing, scaled to the built mean bond"},
          {"input", b.input},
          {"output", b.output_dir.string()},
          {"atoms", b.atoms},
          {"carbon_atoms", b.carbon_atoms},
          {"hydrogen_atoms", b.hydrogen_atoms},
          {"bonds", b.bonds},
          {"rings_by_size", rings},
          {"percent_three_bonds", b.percent_three_bonds},
          {"built_mean_bond", b.built_mean_bond},
          {"dual_mean_bond_unscaled", b.dual_mean_bond},
          {"factor", b.factor},
          {"min_bond", b.min_bond},
          {"max_bond", b.max_bond}};
}

}  // namespace carbonmesh
