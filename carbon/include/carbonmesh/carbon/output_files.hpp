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
  LammpsDataSettings data;  // data.topology also selects atom_style full in the deck
  ReboDeckSettings deck;    // data_file and the hydrogen/topology switches are set by write_structure_files
};

struct OutputFiles {
  std::filesystem::path data, deck, xyz, pdb, ply;
};

// Writes structure.data, in.rebo, structure.xyz, structure.pdb and rings.ply into `dir` (created if missing).
OutputFiles write_structure_files(const std::filesystem::path& dir, const CarbonStructure& structure,
                                  const DualMesh& dual, const OutputSettings& settings);

nlohmann::json to_json(const OutputFiles& files);

}  // namespace carbonmesh
