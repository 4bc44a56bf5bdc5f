// `carbonmesh simulate DIR [--ps 10] [--temp 300] [--timestep 1] [--np N] [--baseline [--baseline-input MESH]]`:
// REBO2 minimisation + NVT of a build folder with the Debian LAMMPS, and the stability verdict of the final frame
// against the structure as built; --baseline also builds and simulates the dual of the input without remeshing.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "carbonmesh/remesh/atomic_file.hpp"
#include "carbonmesh/simulations/baseline.hpp"
#include "carbonmesh/simulations/simulate.hpp"
#include "commands.hpp"
#include "number_checks.hpp"

namespace carbonmesh::cli {
namespace fs = std::filesystem;
namespace {

struct SimulateOptions {
  std::string dir, output, baseline_input, potential;
  SimulationSettings settings;
  bool baseline = false, no_report = false;
};

void write_text(const fs::path& file, const std::string& text) {
  write_atomically(file, [&text](const fs::path& tmp) {
    std::ofstream f(tmp);
    f << text;
    if (!f) throw std::runtime_error("cannot write " + tmp.string());
  });
}

int run_simulate(const SimulateOptions& o) {
  SimulationSettings s = o.settings;
  s.structure_dir = o.dir;
  s.output_dir = o.output.empty() ? fs::path(o.dir) / "simulation" : fs::path(o.output);
  s.potential = o.potential;
  s.report = !o.no_report;

  // The baseline structure is built first: nothing else has run yet when LAMMPS starts.
  std::optional<BaselineBuild> baseline;
  if (o.baseline) {
    BaselineSettings b;
    b.build_dir = o.dir;
    b.input = o.baseline_input;
    b.output_dir = s.output_dir / "baseline";
    b.cutoff = s.stability.cutoff;
    baseline = build_baseline(b);
  }
  const SimulationResult main = simulate(s);
  nlohmann::json j = to_json(main);
  std::string text = to_text(main);
  write_text(s.output_dir / "simulation.json", j.dump(2) + "\n");  // written now: a failing baseline keeps it

  if (baseline) {
    SimulationSettings bs = s;
    bs.structure_dir = baseline->output_dir;
    bs.output_dir = baseline->output_dir / "simulation";
    const SimulationResult base = simulate(bs);
    write_text(bs.output_dir / "simulation.json", to_json(base).dump(2) + "\n");
    write_text(bs.output_dir / "summary.txt", to_text(base));
    j["baseline"] = {{"build", to_json(*baseline)}, {"simulation", to_json(base)}};
    const auto& m = main.comparison;
    const auto& b = base.comparison;
    text += fmt::format(
        "\nbaseline (dual of {} without remeshing, {} atoms, bonds {:.3f}..{:.3f} A):\n{}"
        "remeshing: verdict {} vs baseline {}; three-bonded kept {:.2f}% vs {:.2f}%; rings changed {:.2f}% vs {:.2f}%; "
        "RMSD {:.3f} vs {:.3f} A; pe final {:.4f} vs {:.4f} eV/atom\n",
        baseline->input, baseline->atoms, baseline->min_bond, baseline->max_bond, to_text(base),
        m.verdict.stable ? "stable" : "unstable", b.verdict.stable ? "stable" : "unstable",
        100 * m.three_kept_fraction, 100 * b.three_kept_fraction, 100 * m.rings_changed_fraction,
        100 * b.rings_changed_fraction, m.alignment.rmsd, b.alignment.rmsd, main.pe_final_per_atom,
        base.pe_final_per_atom);
    write_text(s.output_dir / "simulation.json", j.dump(2) + "\n");
  }
  write_text(s.output_dir / "summary.txt", text);
  std::cout << text;
  return 0;
}

}  // namespace

void add_simulate_command(CLI::App& app, Action& action) {
  auto opt = std::make_shared<SimulateOptions>();
  auto* cmd = app.add_subcommand(
      "simulate", "REBO2 MD of a build folder (minimise, NVT) with LAMMPS and the stability verdict of the final frame");
  cmd->add_option("dir", opt->dir, "build folder (carbonmesh build -o DIR)")->required();
  cmd->add_option("-o,--output", opt->output, "output folder (default DIR/simulation)");
  cmd->add_option("--ps", opt->settings.picoseconds, "NVT time (ps)")->capture_default_str()->check(positive_number());
  cmd->add_option("--temp", opt->settings.temperature, "temperature (K)")->capture_default_str()
      ->check(positive_number());
  cmd->add_option("--timestep", opt->settings.timestep_fs, "timestep (fs)")->capture_default_str()
      ->check(positive_number());
  cmd->add_option("--np", opt->settings.np, "1: in-process liblammps; N > 1: mpirun -np N lmp")->capture_default_str()
      ->check(positive_number());
  cmd->add_option("--seed", opt->settings.seed, "velocity seed (LAMMPS velocity create)")->capture_default_str()->check(positive_number());
  cmd->add_option("--cutoff", opt->settings.stability.cutoff, "C-C bond cutoff of the analysis (A)")
      ->capture_default_str()->check(positive_number());
  cmd->add_option("--potential", opt->potential, "CH.rebo (default: $LAMMPS_POTENTIALS, /usr/share/lammps/potentials)");
  cmd->add_option("--lmp", opt->settings.lmp, "lmp executable for --np > 1")->capture_default_str();
  cmd->add_option("--mpirun", opt->settings.mpirun, "mpirun executable for --np > 1")->capture_default_str();
  cmd->add_flag("--baseline", opt->baseline, "also build and simulate the dual of the input without remeshing");
  cmd->add_option("--baseline-input", opt->baseline_input,
                  "input mesh of the baseline (default: the input recorded in DIR/summary.json)");
  cmd->add_flag("--no-report", opt->no_report, "skip the analysis report of the final frame");
  cmd->callback([&action, opt] { action = [opt]() -> int { return run_simulate(*opt); }; });
}

}  // namespace carbonmesh::cli
