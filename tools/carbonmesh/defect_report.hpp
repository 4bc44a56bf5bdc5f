#pragma once
// The defect report of `carbonmesh analyze`, also written by `carbonmesh build` into DIR/analysis.
#include <filesystem>
#include <string>

#include "carbonmesh/simulations/analysis.hpp"

namespace carbonmesh::cli {

struct DefectReportOptions {
  AnalysisSettings settings;
  bool plots = true;                     // PNG plots and report.html through the Python script
  std::string python = "/usr/bin/python3";
  std::string script;                    // empty: installed share/carbonmesh, else the source tree
};

// Analyses `input` and writes report.json, CSVs, defects.ply and (with plots) the PNGs and report.html into
// `out`. Throws InputError when Python or the script is missing, std::runtime_error when the script fails.
Analysis write_defect_report(const std::filesystem::path& input, const std::filesystem::path& out,
                             const DefectReportOptions& options);

}  // namespace carbonmesh::cli
