#include "carbonmesh/carbon/output_files.hpp"

#include <spdlog/spdlog.h>

#include <future>
#include <nlohmann/json.hpp>

#include "carbonmesh/carbon/pdb.hpp"
#include "carbonmesh/carbon/ring_ply.hpp"
#include "carbonmesh/carbon/xyz.hpp"

namespace carbonmesh {

OutputFiles write_structure_files(const std::filesystem::path& dir, const CarbonStructure& structure,
                                  const DualMesh& dual, const OutputSettings& settings) {
  std::filesystem::create_directories(dir);
  OutputFiles files{dir / "structure.data", dir / "in.rebo", dir / "structure.xyz", dir / "structure.pdb",
                    dir / "rings.ply", {}};
  // The XYZ and PDB files are formatted in a second thread while this one writes the LAMMPS files and the ring
  // PLY (10^6 atoms: about 3 s of number formatting in all); a writer's exception reaches the caller through get().
  auto others = std::async(std::launch::async, [&] {
    write_extended_xyz(structure, files.xyz, settings.data.vacuum);
    write_pdb(structure, files.pdb);
  });
  try {
    LammpsDataSettings atomic = settings.data;
    atomic.topology = false;
    write_lammps_data(structure, files.data, atomic);
    if (settings.data.topology) {
      files.full_data = dir / "structure-full.data";
      write_lammps_data(structure, files.full_data, settings.data);
      spdlog::info("wrote {} (atom_style full, Bonds and Angles)", files.full_data.string());
    }
    ReboDeckSettings deck = settings.deck;
    deck.data_file = files.data.filename().string();
    deck.hydrogen = structure.has_hydrogen();
    deck.topology = false;
    write_rebo_deck(deck, files.deck);
    write_ring_ply(dual, files.ply);
  } catch (...) {
    others.wait();  // it reads `structure` and `dual`: let it finish before they go
    throw;
  }
  others.get();
  spdlog::info("wrote {}, {}, {}, {}, {}", files.data.string(), files.deck.string(), files.xyz.string(),
               files.pdb.string(), files.ply.string());
  return files;
}

nlohmann::json to_json(const OutputFiles& f) {
  nlohmann::json j{{"lammps_data", f.data.string()}, {"rebo_deck", f.deck.string()}, {"xyz", f.xyz.string()},
                   {"pdb", f.pdb.string()},          {"rings_ply", f.ply.string()}};
  if (!f.full_data.empty()) j["lammps_data_full"] = f.full_data.string();
  return j;
}

}  // namespace carbonmesh
