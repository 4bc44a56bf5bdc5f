#pragma once
// PDB with HETATM records and CONECT bonds. Serial numbers above 99999 use the hybrid-36 encoding.
#include <filesystem>
#include <string>

#include "carbonmesh/carbon/structure.hpp"

namespace carbonmesh {

// Throws std::runtime_error if a coordinate does not fit the PDB columns (|x| >= 10000 A) or there are more
// atoms than hybrid-36 with 5 characters can number.
void write_pdb(const CarbonStructure& structure, const std::filesystem::path& file);

// A PDB serial number of width 5: decimal up to 99999, then hybrid-36 ("A0000", ...).
std::string hybrid36_serial(long value);

}  // namespace carbonmesh
