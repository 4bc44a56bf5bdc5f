#pragma once
// Everything a build writes for one structure, into one folder: the LAMMPS data file and REBO2 deck, extended
// XYZ, PDB with CONECT, and the dual mesh as a ring-coloured PLY. Every file is written atomically.
#include <filesystem>

#include <nlohmann/json_fwd.hpp>

#include "carbonmesh/carbon/lammps_data.hpp"
#include "carbonmesh/carbon/rebo_deck.hpp"
#include "carbonmesh/carbon/structure.hpp"

namespace carbonmesh {

struct OutputSettings {
  // structure.data is always atom_style atomic (what REBO needs); data.topology adds structure-full.data,
  // atom_style full with Bonds and Angles, for other force fields.
  LammpsDataSettings data;
  ReboDeckSettings deck;    // data_file and the hydrogen switch are set by write_structure_files
};

struct OutputFiles {
  std::filesystem::path data, deck, xyz, pdb, ply;
  std::filesystem::path full_data;  // structure-full.data, empty without data.topology
};

// Writes structure.data, in.rebo, structure.xyz, structure.pdb and rings.ply (and structure-full.data with
// data.topology) into `dir` (created if missing).
OutputFiles write_structure_files(const std::filesystem::path& dir, const CarbonStructure& structure,
                                  const DualMesh& dual, const OutputSettings& settings);

nlohmann::json to_json(const OutputFiles& files);

}  // namespace carbonmesh
