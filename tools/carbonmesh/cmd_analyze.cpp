// `carbonmesh analyze INPUT [-o DIR] [--plane x|y|z|nx,ny,nz,d|auto]`: ring statistics, defect distances,
// 5-7 pairs, topological floor and mirror-side counts; report.json, CSVs, defects.ply, PNG plots and report.html.
#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/simulations/analysis.hpp"
#include "carbonmesh/simulations/report_files.hpp"
#include "commands.hpp"

namespace carbonmesh::cli {
namespace fs = std::filesystem;
namespace {

// tools/analysis_report.py: installed next to the binary (../share/carbonmesh), else the source tree.
fs::path find_report_script(const std::string& given) {
  if (!given.empty()) return given;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path().parent_path() / "share" / "carbonmesh" / "analysis_report.py";
    if (fs::exists(installed, ec)) return installed;
  }
  return CARBONMESH_REPORT_SCRIPT;
}

}  // namespace

void add_analyze_command(CLI::App& app, Action& action) {
  struct Options {
    std::string input, output, plane, python = "/usr/bin/python3", script;
    AnalysisSettings settings;
    bool no_plots = false, json = false;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "analyze", "defect analysis: ring sizes, pentagon/heptagon distances, 5-7 pairs, topological floor, symmetry");
  cmd->add_option("input", opt->input,
                  "a `carbonmesh build` folder, a LAMMPS data file (bonds by --cutoff) or a triangle mesh "
                  "(rings = vertices by valence; a polygon mesh: rings = faces)")
      ->required();
  cmd->add_option("-o,--output", opt->output, "output folder (default: INPUT/analysis for a folder, else STEM-analysis)");
  cmd->add_option("--plane", opt->settings.plane,
                  "mirror plane for the side counts: x, y, z (through the centroid), nx,ny,nz,d, or auto");
  cmd->add_option("--cutoff", opt->settings.cutoff, "bond cutoff for data files (Angstrom)")->default_val(1.85);
  cmd->add_flag("--data-bonds", opt->settings.data_bonds, "use the data file's Bonds section instead of the cutoff");
  cmd->add_option("--max-ring", opt->settings.rings.max_size, "largest SP ring searched in data files")
      ->default_val(10)
      ->check(CLI::Range(3, 32));
  cmd->add_option("--mirror-samples", opt->settings.mirror.final_samples,
                  "Hausdorff samples a side for the mirror residual")
      ->default_val(100000)
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--no-plots", opt->no_plots, "skip the PNG plots and report.html (no Python needed)");
  cmd->add_option("--python", opt->python, "Python with matplotlib for the plots")->default_val("/usr/bin/python3");
  cmd->add_option("--report-script", opt->script, "the plot/HTML script (default: tools/analysis_report.py)");
  cmd->add_flag("--json", opt->json, "print report.json on stdout instead of the text summary");
  cmd->callback([&action, opt] {
    action = [opt]() -> int {
      const fs::path input(opt->input);
      fs::path out = opt->output;
      if (out.empty()) {
        std::error_code ec;
        out = fs::is_directory(input, ec) ? input / "analysis" : fs::path(input.stem().string() + "-analysis");
      }
      const Analysis a = analyze(input, opt->settings);
      const auto files = write_report_files(out, a);
      spdlog::info("wrote {} files to {}", files.size(), out.string());
      if (!opt->no_plots) {
        const fs::path script = find_report_script(opt->script);
        if (!fs::exists(script)) throw InputError(fmt::format("report script {} not found (--report-script, or --no-plots)", script.string()));
        if (access(opt->python.c_str(), X_OK) != 0)
          throw InputError(fmt::format("{} is not executable (--python, or --no-plots)", opt->python));
        const int rc = run_report_script(opt->python, script, out);
        if (rc != 0) {
          std::cerr << fmt::format("carbonmesh: error: {} {} {} failed (exit {})\n", opt->python, script.string(),
                                   out.string(), rc);
          return 1;
        }
        spdlog::info("plots and {}", (out / "report.html").string());
      }
      if (opt->json)
        std::cout << to_json(a).dump(2) << "\n";
      else
        std::cout << to_text(a) << "output: " << out.string() << "\n";
      return 0;
    };
  });
}

}  // namespace carbonmesh::cli
