#pragma once
// `carbonmesh analyze`: ring statistics, defect distances, 5-7 pairs, topological floor and mirror-side counts
// of a carbon structure given as a build folder, a LAMMPS data file or a triangle (or polygon) mesh.
#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "carbonmesh/simulations/defect_stats.hpp"
#include "carbonmesh/simulations/mirror_plane.hpp"
#include "carbonmesh/simulations/ring_structure.hpp"
#include "carbonmesh/simulations/sp_rings.hpp"

namespace carbonmesh {

struct AnalysisSettings {
  double cutoff = 1.85;          // bond cutoff for data files (Angstrom)
  bool data_bonds = false;       // use the data file's Bonds section instead of the cutoff
  SpRingSettings rings;          // SP ring search (data files)
  std::string plane;             // "" (none), "auto", "x", "y", "z" or "nx,ny,nz,d"
  MirrorSettings mirror;
};

// What `input` resolved to.
struct ResolvedInput {
  std::string kind;            // "lammps data", "triangle mesh", "polygon mesh"
  std::filesystem::path file;  // the file read
  bool from_folder = false;    // found inside a build folder
};
// A folder: its dual PLY (a .ply whose name contains "dual") if any, else structure.data, else its only *.data.
// A file: .off/.obj/.ply/.stl are meshes, anything else a LAMMPS data file. Throws InputError.
ResolvedInput resolve_input(const std::filesystem::path& input);

struct PlaneAnalysis {
  std::string requested;               // the --plane text
  Plane plane;
  std::optional<MirrorResult> search;  // for "auto"
  HausdorffResult residual;            // shape vs its mirror image in `plane`
  double diagonal = 0;
  SideCounts sides;
};

struct Analysis {
  std::string input;
  ResolvedInput resolved;
  RingStructure structure;
  std::map<int, std::size_t> coordination;  // atom degree -> atoms
  std::optional<SpRingResult> sp;           // data input: SP ring search figures (rings moved out)
  RingSizeCounts sizes;
  NearestDistances pentagons, heptagons;
  PairStats pairs;
  TopologicalFloor floor;
  std::optional<PlaneAnalysis> plane;
  std::map<std::string, double> seconds;  // step -> wall time
};

Analysis analyze(const std::filesystem::path& input, const AnalysisSettings& settings = {});

// The ring structure of an input (no statistics): used by analyze and by callers that count rings only.
RingStructure load_ring_structure(const ResolvedInput& in, const AnalysisSettings& settings,
                                  std::optional<SpRingResult>* sp = nullptr);

nlohmann::json to_json(const Analysis& a);
std::string to_text(const Analysis& a);

}  // namespace carbonmesh
