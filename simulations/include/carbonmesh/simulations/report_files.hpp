#pragma once
// The files of `carbonmesh analyze -o DIR`: report.json, CSVs, defects.ply (rings as coloured polygons) and
// view.json (atoms, bonds and defect rings for the 3D view); PNG plots and report.html come from the Python
// script tools/analysis_report.py, run by run_report_script. Every file is written atomically.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "carbonmesh/simulations/analysis.hpp"

namespace carbonmesh {

// Colour of a ring of `size` (hexagons light grey, pentagons red, heptagons blue, ...); shared with the plots.
std::array<unsigned char, 3> defect_ring_colour(int size);

struct ReportFilesSettings {
  std::size_t max_view_atoms = 300000;  // above this, view.json holds only the defect rings' atoms
};

// Writes the data files into `dir` (created if missing) and returns their names.
std::vector<std::string> write_report_files(const std::filesystem::path& dir, const Analysis& a,
                                            const ReportFilesSettings& settings = {});

// Runs `python script dir`; returns the exit status (non-zero or -1 if it could not start).
int run_report_script(const std::filesystem::path& python, const std::filesystem::path& script,
                      const std::filesystem::path& dir);

}  // namespace carbonmesh
