#include "carbonmesh/simulations/simulate.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <map>
#include <nlohmann/json.hpp>

#include "carbonmesh/carbon/lammps_data.hpp"
#include "carbonmesh/carbon/lammps_dump.hpp"
#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/simulations/analysis.hpp"
#include "carbonmesh/simulations/md_deck.hpp"
#include "carbonmesh/simulations/report_files.hpp"

namespace carbonmesh {
namespace fs = std::filesystem;
namespace {

struct BuiltAtoms {
  std::vector<Vec3> positions;  // by atom id 1..N
  std::vector<bool> carbon;
  bool topology = false;
};

BuiltAtoms read_built(const fs::path& data_file) {
  const LammpsData data = read_lammps_data(data_file);
  BuiltAtoms b;
  const std::size_t n = data.ids.size();
  if (n == 0) throw InputError(data_file.string() + ": no atoms");
  b.positions.resize(n);
  b.carbon.assign(n, true);
  std::vector<bool> seen(n, false);
  for (std::size_t k = 0; k < n; ++k) {
    const int id = data.ids[k];
    if (id < 1 || static_cast<std::size_t>(id) > n || seen[id - 1])
      throw InputError(fmt::format("{}: atom ids must be 1..{} without repeats (found {})", data_file.string(), n, id));
    seen[id - 1] = true;
    b.positions[id - 1] = data.positions[k];
    const int type = data.types[k];
    const double mass = type >= 1 && static_cast<std::size_t>(type) <= data.masses.size() ? data.masses[type - 1] : 0;
    b.carbon[id - 1] = !(mass > 0 && mass < 1.5);  // hydrogen: mass 1.008
  }
  b.topology = data.atom_style == "full";
  return b;
}

// Moves every file of `from` into `to` (renames within one file system: each file appears whole) and removes
// `from`. Returns the names moved.
std::vector<std::string> move_files(const fs::path& from, const fs::path& to) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(from)) {
    fs::rename(e.path(), to / e.path().filename());
    names.push_back(e.path().filename().string());
  }
  fs::remove_all(from);
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

SimulationResult simulate(const SimulationSettings& s) {
  const fs::path data_file = s.structure_dir / "structure.data";
  std::error_code ec;
  if (!fs::is_regular_file(data_file, ec))
    throw InputError(fmt::format("{}: no structure.data (run carbonmesh build -o {} first)", s.structure_dir.string(),
                                 s.structure_dir.string()));
  const fs::path potential = s.potential.empty() ? find_potential("CH.rebo") : s.potential;
  if (potential.empty() || !fs::is_regular_file(potential, ec))
    throw InputError(potential.empty() ? "REBO2 potential CH.rebo not found (current folder, $LAMMPS_POTENTIALS, "
                                         "/usr/share/lammps/potentials; Debian package lammps-data)"
                                       : potential.string() + ": potential file not found");
  const BuiltAtoms built = read_built(data_file);

  SimulationResult r;
  r.structure_dir = s.structure_dir;
  r.output_dir = s.output_dir.empty() ? s.structure_dir / "simulation" : s.output_dir;
  r.atoms = built.positions.size();
  r.carbon_atoms = static_cast<std::size_t>(std::count(built.carbon.begin(), built.carbon.end(), true));
  r.hydrogen_atoms = r.atoms - r.carbon_atoms;
  r.picoseconds = s.picoseconds;
  r.temperature = s.temperature;
  r.timestep_fs = s.timestep_fs;
  fs::create_directories(r.output_dir);
  // LAMMPS writes its files into a staging folder; they are renamed into place after a successful run.
  const fs::path out = fs::absolute(r.output_dir);
  const fs::path stage = out / fmt::format(".lammps-partial-{}", getpid());
  fs::remove_all(stage);
  fs::create_directories(stage);

  MdDeckSettings deck;
  deck.data_file = fs::absolute(data_file);
  deck.potential_file = fs::absolute(potential);
  deck.dump_file = stage / "dump.lammpstrj";
  deck.final_data_file = stage / "final.data";
  deck.thermo_csv = stage / "thermo.csv";
  deck.hydrogen = r.hydrogen_atoms > 0;
  deck.topology = built.topology;
  deck.temperature = s.temperature;
  deck.timestep_fs = s.timestep_fs;
  deck.picoseconds = s.picoseconds;
  deck.seed = s.seed;
  LammpsRunSettings run;
  try {
    run.commands = md_commands(deck);
    run.steps = md_steps(deck);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  run.work_dir = stage;
  run.np = s.np;
  run.lmp = s.lmp;
  run.mpirun = s.mpirun;
  run.timestep_fs = s.timestep_fs;
  run.atoms = r.atoms;
  spdlog::info("{}: {} atoms ({} H), minimise + NVT {} K for {} ps ({} steps of {} fs), {}", data_file.string(),
               r.atoms, r.hydrogen_atoms, s.temperature, s.picoseconds, run.steps, s.timestep_fs,
               s.np == 1 ? "in-process liblammps" : fmt::format("mpirun -np {}", s.np));
  try {
    r.run = run_lammps(run);
  } catch (const InputError& e) {  // keep the log next to the outputs and name it there
    if (fs::exists(stage / "log.lammps", ec)) fs::rename(stage / "log.lammps", out / "log.lammps", ec);
    fs::remove_all(stage, ec);
    std::string what = e.what();
    const std::string staged = (stage / "log.lammps").string();
    if (const auto at = what.find(staged); at != std::string::npos)
      what.replace(at, staged.size(), (out / "log.lammps").string());
    throw InputError(what);
  } catch (...) {
    fs::remove_all(stage, ec);
    throw;
  }
  if (r.run.steps != run.steps)
    throw InputError(fmt::format("LAMMPS stopped at step {} of {} (log: {})", r.run.steps, run.steps,
                                 (stage / "log.lammps").string()));

  std::vector<Vec3> final_positions = std::move(r.run.final_positions);
  r.run.final_positions.clear();
  if (final_positions.empty()) {  // mpirun: the last dump frame (the last NVT step; sorted by id)
    const DumpFrame frame = read_last_dump_frame(deck.dump_file);
    if (frame.ids.size() != r.atoms || frame.timestep != run.steps)
      throw InputError(fmt::format("{}: last frame is step {} with {} atoms, expected step {} with {}",
                                   deck.dump_file.string(), frame.timestep, frame.ids.size(), run.steps, r.atoms));
    final_positions = frame.positions;
  }
  if (final_positions.size() != r.atoms)
    throw InputError(fmt::format("LAMMPS returned {} atoms, expected {}", final_positions.size(), r.atoms));
  r.files = move_files(stage, out);
  r.run.log = out / "log.lammps";

  const double n = static_cast<double>(r.atoms);
  r.pe_minimized_per_atom = r.run.pe_minimized / n;
  r.pe_final_per_atom = r.run.pe_final / n;
  r.atom_steps_per_second = r.run.md_seconds > 0 ? n * static_cast<double>(run.steps) / r.run.md_seconds : 0;
  spdlog::info("comparing the final frame with the built structure (cutoff {} A, SP rings)", s.stability.cutoff);
  r.comparison = compare_frames(built.positions, final_positions, built.carbon, s.stability);

  if (s.report) {
    AnalysisSettings a;
    a.cutoff = s.stability.cutoff;
    a.rings = s.stability.rings;
    const Analysis analysis = analyze(out / "final.data", a);
    for (const auto& name : write_report_files(out / "report", analysis)) r.files.push_back("report/" + name);
  }
  return r;
}

nlohmann::json to_json(const SimulationResult& r) {
  return {{"structure", r.structure_dir.string()},
          {"output", r.output_dir.string()},
          {"atoms", r.atoms},
          {"carbon_atoms", r.carbon_atoms},
          {"hydrogen_atoms", r.hydrogen_atoms},
          {"picoseconds", r.picoseconds},
          {"temperature", r.temperature},
          {"timestep_fs", r.timestep_fs},
          {"steps", r.run.steps},
          {"mode", r.run.mode},
          {"np", r.run.np},
          {"seconds", r.run.seconds},
          {"md_seconds", r.run.md_seconds},
          {"atom_steps_per_second", r.atom_steps_per_second},
          {"pe_minimized", r.run.pe_minimized},
          {"pe_final", r.run.pe_final},
          {"pe_minimized_per_atom", r.pe_minimized_per_atom},
          {"pe_final_per_atom", r.pe_final_per_atom},
          {"pe_change_per_atom", r.pe_final_per_atom - r.pe_minimized_per_atom},
          {"graphene_reference_per_atom", kGrapheneReboEnergy},
          {"pe_minimized_above_graphene_per_atom", r.pe_minimized_per_atom - kGrapheneReboEnergy},
          {"temperature_final", r.run.temperature_final},
          {"stability", to_json(r.comparison)},
          {"files", r.files}};
}

std::string to_text(const SimulationResult& r) {
  const FrameComparison& c = r.comparison;
  auto counts = [](const std::map<int, std::size_t>& m) {
    std::string t;
    for (const auto& [k, v] : m) t += fmt::format(" {}:{}", k, v);
    return t.empty() ? std::string(" none") : t;
  };
  return fmt::format(
      "{}: {} atoms ({} C, {} H), {} ps NVT at {} K, timestep {} fs, {} steps, {}\n"
      "verdict: {}  ({})\n"
      "rule: {}\n"
      "coordination (C neighbours: atoms) before{}  after{}\n"
      "three-bonded kept {} / {} ({:.2f}%)  C-C bonds {} -> {} (broken {}, formed {})  mean bond {:.4f} -> {:.4f} A\n"
      "rings before{}  after{}  lost {} formed {} ({:.2f}% changed)\n"
      "RMSD after alignment {:.4f} A  max displacement {:.4f} A\n"
      "pe minimised {:.4f} eV/atom ({:+.4f} vs graphene {:.1f})  final {:.4f} eV/atom (change {:+.4f})  T final {:.1f} K\n"
      "wall {:.2f} s (MD {:.2f} s)  {:.3g} atom-steps/s\n",
      r.structure_dir.string(), r.atoms, r.carbon_atoms, r.hydrogen_atoms, r.picoseconds, r.temperature,
      r.timestep_fs, r.run.steps, r.run.mode, c.verdict.stable ? "stable" : "unstable", c.verdict.reason,
      c.verdict.rule, counts(c.coordination_before), counts(c.coordination_after), c.three_kept, c.three_before,
      100 * c.three_kept_fraction, c.bonds_before, c.bonds_after, c.bonds_broken, c.bonds_formed,
      c.mean_bond_before, c.mean_bond_after, counts(c.rings_before), counts(c.rings_after), c.rings_lost,
      c.rings_formed, 100 * c.rings_changed_fraction, c.alignment.rmsd, c.alignment.max_displacement,
      r.pe_minimized_per_atom, r.pe_minimized_per_atom - kGrapheneReboEnergy, kGrapheneReboEnergy,
      r.pe_final_per_atom, r.pe_final_per_atom - r.pe_minimized_per_atom, r.run.temperature_final, r.run.seconds,
      r.run.md_seconds, r.atom_steps_per_second);
}

}  // namespace carbonmesh
