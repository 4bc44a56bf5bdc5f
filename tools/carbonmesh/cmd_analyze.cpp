// `carbonmesh analyze INPUT [-o DIR] [--plane x|y|z|nx,ny,nz,d|auto]`: ring statistics, defect distances,
// 5-7 pairs, topological floor and mirror-side counts; report.json, CSVs, defects.ply, PNG plots and report.html.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "defect_report.hpp"
#include "commands.hpp"
#include "number_checks.hpp"

namespace carbonmesh::cli {
namespace fs = std::filesystem;

void add_analyze_command(CLI::App& app, Action& action) {
  struct Options {
    std::string input, output;
    DefectReportOptions report;
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
  cmd->add_option("--plane", opt->report.settings.plane,
                  "mirror plane for the side counts: x, y, z (through the centroid), nx,ny,nz,d (A), or auto (default: none, no side counts)");
  cmd->add_option("--cutoff", opt->report.settings.cutoff, "bond cutoff for data files (Angstrom)")->default_val(1.85);
  cmd->add_flag("--data-bonds", opt->report.settings.data_bonds, "use the data file's Bonds section instead of the cutoff");
  cmd->add_option("--max-ring", opt->report.settings.rings.max_size, "largest SP ring searched in data files (atoms)")
      ->default_val(10)
      ->check(CLI::Range(3, 32));
  cmd->add_option("--mirror-samples", opt->report.settings.mirror.final_samples,
                  "Hausdorff samples a side for the mirror residual (count)")
      ->default_val(100000)
      ->check(positive_number());
  cmd->add_flag("--no-plots", opt->no_plots, "skip the PNG plots and report.html (no Python needed)");
  cmd->add_option("--python", opt->report.python, "Python with matplotlib for the plots")->default_val("/usr/bin/python3");
  cmd->add_option("--report-script", opt->report.script, "the plot/HTML script (default: tools/analysis_report.py)");
  cmd->add_flag("--json", opt->json, "print report.json on stdout instead of the text summary");
  cmd->callback([&action, opt] {
    action = [opt]() -> int {
      const fs::path input(opt->input);
      fs::path out = opt->output;
      if (out.empty()) {
        std::error_code ec;
        out = fs::is_directory(input, ec) ? input / "analysis" : fs::path(input.stem().string() + "-analysis");
      }
      opt->report.plots = !opt->no_plots;
      const Analysis a = write_defect_report(input, out, opt->report);
      if (opt->json)
        std::cout << to_json(a).dump(2) << "\n";
      else
        std::cout << to_text(a) << "output: " << out.string() << "\n";
      return 0;
    };
  });
}

}  // namespace carbonmesh::cli
