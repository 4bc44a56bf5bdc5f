// The carbon module: scaling, structure, passivation, writers (parsed back) and a REBO2 run of the Debian lmp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "carbonmesh/carbon/lammps_data.hpp"
#include "carbonmesh/carbon/lammps_dump.hpp"
#include "carbonmesh/carbon/output_files.hpp"
#include "carbonmesh/carbon/passivate.hpp"
#include "carbonmesh/carbon/pdb.hpp"
#include "carbonmesh/carbon/rebo_deck.hpp"
#include "carbonmesh/carbon/ring_ply.hpp"
#include "carbonmesh/carbon/structure.hpp"
#include "carbonmesh/carbon/structure_scale.hpp"
#include "carbonmesh/carbon/xyz.hpp"
#include "carbonmesh/dual/optimize.hpp"
#include "carbonmesh/remesh/atomic_file.hpp"
#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/shapes.hpp"

using namespace carbonmesh;
namespace fs = std::filesystem;

namespace {

fs::path temp_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("carbonmesh_test_carbon_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::vector<std::string> lines_of(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// An icosphere fullerene: scaled to about `atoms` atoms for bond b, dual, optimised.
CarbonStructure fullerene(int subdivisions, double b = 1.42) {
  TriMesh mesh = make_icosphere({1.0, subdivisions});
  ScaleSettings scale;
  scale.mode = ScaleMode::Atoms;
  scale.value = static_cast<double>(mesh.n_faces());
  scale.bond = b;
  scale_mesh(mesh, structure_scale(mesh, scale).factor);
  Dual dual = build_dual(mesh);
  DualOptimizeSettings opt;
  opt.bond = b;
  optimize_dual(dual, mesh, opt);
  return carbon_structure(dual);
}

// The upper half of an icosphere (faces with centroid z > 0), with triangles that have two border edges
// removed, so that every border atom of its dual has two bonds.
TriMesh hemisphere(int subdivisions, double radius) {
  TriMesh mesh = make_icosphere({radius, subdivisions});
  for (auto f : mesh.faces()) {
    Vec3 c(0, 0, 0);
    for (auto v : mesh.fv_range(f)) c += mesh.point(v);
    if (c[2] < 0) mesh.delete_face(f, true);
  }
  for (bool removed = true; removed;) {
    removed = false;
    for (auto f : mesh.faces()) {
      int border = 0;
      for (auto e : mesh.fe_range(f)) border += mesh.is_boundary(e) ? 1 : 0;
      if (border >= 2) {
        mesh.delete_face(f, true);
        removed = true;
      }
    }
  }
  mesh.garbage_collection();
  mesh.update_normals();
  return mesh;
}

// Neighbours of every atom within `cutoff` (all pairs: the structures here are small).
std::vector<int> neighbour_counts(const std::vector<Vec3>& p, double cutoff) {
  std::vector<int> n(p.size(), 0);
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j)
      if ((p[i] - p[j]).norm() < cutoff) ++n[i], ++n[j];
  return n;
}

bool lmp_on_path() { return std::system("command -v lmp > /dev/null 2>&1") == 0; }

}  // namespace

TEST(StructureScale, EdgeAndAreaPerAtomFollowTheBond) {
  EXPECT_NEAR(target_edge(1.42), 2.4595121, 1e-6);
  EXPECT_NEAR(area_per_atom(1.42), 2.6194, 1e-3);  // = 3 sqrt(3)/4 b^2, the graphene area per atom
  EXPECT_NEAR(area_per_atom(1.42), 3 * std::sqrt(3.0) / 4 * 1.42 * 1.42, 1e-12);
}

TEST(StructureScale, ModesGiveSizeFactorAndAtoms) {
  const TriMesh sphere = make_icosphere({10.0, 3});
  ScaleSettings s;
  const StructureScale none = structure_scale(sphere, s);
  EXPECT_DOUBLE_EQ(none.factor, 1.0);
  EXPECT_NEAR(none.emin, 0.8 * target_edge(1.42), 1e-12);
  EXPECT_NEAR(none.emax, 1.2 * target_edge(1.42), 1e-12);
  s.mode = ScaleMode::Size;
  s.value = 50.0;
  EXPECT_NEAR(structure_scale(sphere, s).longest_side, 50.0, 1e-9);
  EXPECT_NEAR(structure_scale(sphere, s).factor, 2.5, 1e-9);  // the sphere is 20 wide
  s.mode = ScaleMode::Factor;
  s.value = 3.0;
  EXPECT_NEAR(structure_scale(sphere, s).area, 9.0 * surface_area(sphere), 1e-6);
  s.mode = ScaleMode::Atoms;
  s.value = 5000;
  const StructureScale atoms = structure_scale(sphere, s);
  EXPECT_NEAR(atoms.expected_atoms, 5000.0, 1e-6);
  TriMesh scaled = sphere;
  scale_mesh(scaled, atoms.factor);
  EXPECT_NEAR(surface_area(scaled) / area_per_atom(1.42), 5000.0, 1e-6);
}

TEST(StructureScale, RejectsBadValues) {
  const TriMesh sphere = make_icosphere({1.0, 1});
  ScaleSettings s;
  s.mode = ScaleMode::Atoms;
  s.value = 0;
  EXPECT_THROW(structure_scale(sphere, s), InputError);
  s.value = 100;
  s.bond = -1;
  EXPECT_THROW(structure_scale(sphere, s), InputError);
  s.bond = 1.42;
  s.low = 1.3;
  EXPECT_THROW(structure_scale(sphere, s), InputError);
}

TEST(StructureScale, AtomCountOfAScaledFullereneHasMeanBondNearTarget) {
  // Scaling by the atom count gives the area a bond-b net needs, so the optimised mean bond is close to b.
  const CarbonStructure c = fullerene(3);
  EXPECT_EQ(c.atoms(), 1280u);
  const SampleStats bonds = sample_stats(bond_lengths(c.positions, c.bonds));
  EXPECT_NEAR(bonds.mean, 1.42, 0.02);
}

TEST(Structure, FromDualIsAllCarbonWithItsRings) {
  const CarbonStructure c = fullerene(1);
  EXPECT_EQ(c.atoms(), 80u);
  EXPECT_EQ(c.count(Element::C), 80u);
  EXPECT_FALSE(c.has_hydrogen());
  EXPECT_EQ(c.bonds.size(), 120u);
  EXPECT_EQ(c.rings.size(), 42u);
  for (int n : c.coordination()) EXPECT_EQ(n, 3);
  EXPECT_EQ(c.angles().size(), 240u);
}

TEST(Passivate, HydrogenOnTwoCoordinatedBorderCarbons) {
  const TriMesh cap = hemisphere(2, 8.2);
  const Dual dual = build_dual(cap);
  CarbonStructure c = carbon_structure(dual);
  const std::size_t two = dual.counts.coordination.at(2);
  ASSERT_GT(two, 0u);
  EXPECT_EQ(dual.counts.coordination.count(1), 0u);
  const PassivationResult r = passivate(c);
  EXPECT_EQ(r.hydrogens, two);
  EXPECT_EQ(c.count(Element::H), two);
  EXPECT_EQ(c.atoms(), dual.atoms() + two);
  for (int n : c.coordination()) EXPECT_GE(n, 1);
  const auto coordination = c.coordination();
  for (std::size_t i = 0; i < dual.atoms(); ++i) EXPECT_EQ(coordination[i], 3) << "carbon " << i;
  for (std::size_t k = dual.bonds.size(); k < c.bonds.size(); ++k) {
    const int carbon = c.bonds[k][0], h = c.bonds[k][1];
    ASSERT_EQ(c.elements[static_cast<std::size_t>(h)], Element::H);
    const Vec3 ch = c.positions[static_cast<std::size_t>(h)] - c.positions[static_cast<std::size_t>(carbon)];
    EXPECT_NEAR(ch.norm(), 1.09, 1e-12);
    // In the plane of the two C-C bonds, at equal angles to both, pointing away from them (> 90 degrees).
    std::vector<Vec3> cc;
    for (std::size_t m = 0; m < dual.bonds.size(); ++m)
      for (int side : {0, 1})
        if (dual.bonds[m][side] == carbon)
          cc.push_back(c.positions[static_cast<std::size_t>(dual.bonds[m][1 - side])] -
                       c.positions[static_cast<std::size_t>(carbon)]);
    ASSERT_EQ(cc.size(), 2u);
    EXPECT_NEAR(OpenMesh::dot(ch, OpenMesh::cross(cc[0], cc[1]).normalized()), 0.0, 1e-9);
    const double a0 = OpenMesh::dot(ch, cc[0].normalized()), a1 = OpenMesh::dot(ch, cc[1].normalized());
    EXPECT_NEAR(a0, a1, 1e-9);
    EXPECT_LT(a0, 0.0);
  }
}

TEST(LammpsData, AtomicRoundTrip) {
  const CarbonStructure c = fullerene(1);
  const fs::path dir = temp_dir("atomic");
  write_lammps_data(c, dir / "c80.data");
  const LammpsData d = read_lammps_data(dir / "c80.data");
  EXPECT_EQ(d.atom_style, "atomic");
  EXPECT_EQ(d.atom_types, 1);
  ASSERT_EQ(d.positions.size(), c.atoms());
  ASSERT_EQ(d.masses.size(), 1u);
  EXPECT_DOUBLE_EQ(d.masses[0], 12.011);
  EXPECT_TRUE(d.bonds.empty());
  for (std::size_t i = 0; i < c.atoms(); ++i) {
    EXPECT_EQ(d.ids[i], static_cast<int>(i + 1));
    EXPECT_EQ(d.types[i], 1);
    EXPECT_LT((d.positions[i] - c.positions[i]).norm(), 1e-7);
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(d.positions[i][k] - d.box.lo[k], 10.0 - 1e-7);
      EXPECT_GE(d.box.hi[k] - d.positions[i][k], 10.0 - 1e-7);
    }
  }
  EXPECT_FALSE(fs::exists(partial_path(dir / "c80.data")));
  fs::remove_all(dir);
}

TEST(LammpsData, TopologyRoundTripWithHydrogen) {
  CarbonStructure c = carbon_structure(build_dual(hemisphere(2, 8.2)));
  passivate(c);
  const fs::path dir = temp_dir("full");
  LammpsDataSettings settings;
  settings.topology = true;
  write_lammps_data(c, dir / "cap.data", settings);
  const LammpsData d = read_lammps_data(dir / "cap.data");
  EXPECT_EQ(d.atom_style, "full");
  EXPECT_EQ(d.atom_types, 2);
  EXPECT_EQ(d.bond_types, 2);
  EXPECT_EQ(d.angle_types, 2);
  ASSERT_EQ(d.masses.size(), 2u);
  EXPECT_DOUBLE_EQ(d.masses[1], 1.008);
  ASSERT_EQ(d.positions.size(), c.atoms());
  std::size_t h = 0;
  for (std::size_t i = 0; i < c.atoms(); ++i) {
    EXPECT_EQ(d.types[i], lammps_type(c.elements[i]));
    h += d.types[i] == 2 ? 1 : 0;
  }
  EXPECT_EQ(h, c.count(Element::H));
  ASSERT_EQ(d.bonds.size(), c.bonds.size());
  std::size_t ch_bonds = 0;
  for (std::size_t k = 0; k < c.bonds.size(); ++k) {
    EXPECT_EQ(d.bonds[k][1], c.bonds[k][0] + 1);
    EXPECT_EQ(d.bonds[k][2], c.bonds[k][1] + 1);
    ch_bonds += d.bonds[k][0] == 2 ? 1 : 0;
  }
  EXPECT_EQ(ch_bonds, c.count(Element::H));
  EXPECT_EQ(d.angles.size(), c.angles().size());
  fs::remove_all(dir);
}

TEST(Writers, ExtendedXyzPdbAndPly) {
  const CarbonStructure c = fullerene(1);
  const Dual dual = build_dual(make_icosphere({5.0, 1}));
  const fs::path dir = temp_dir("writers");
  write_extended_xyz(c, dir / "c.xyz");
  write_pdb(c, dir / "c.pdb");
  write_ring_ply(dual.mesh, dir / "c.ply");

  const auto xyz = lines_of(dir / "c.xyz");
  ASSERT_EQ(xyz.size(), c.atoms() + 2);
  EXPECT_EQ(std::stoul(xyz[0]), c.atoms());
  EXPECT_NE(xyz[1].find("Properties=species:S:1:pos:R:3"), std::string::npos);
  EXPECT_EQ(xyz[2].substr(0, 2), "C ");

  std::size_t hetatm = 0, conect_pairs = 0;
  for (const auto& line : lines_of(dir / "c.pdb")) {
    if (line.rfind("HETATM", 0) == 0) {
      ++hetatm;
      EXPECT_EQ(line.size(), 78u);
      EXPECT_EQ(line.substr(76, 2), " C");
    }
    if (line.rfind("CONECT", 0) == 0) conect_pairs += (line.size() - 11) / 5;
  }
  EXPECT_EQ(hetatm, c.atoms());
  EXPECT_EQ(conect_pairs, 2 * c.bonds.size());

  const auto ply = lines_of(dir / "c.ply");
  std::size_t pentagons = 0, hexagons = 0, header = 0;
  for (std::size_t i = 0; i < ply.size(); ++i)
    if (ply[i] == "end_header") header = i;
  EXPECT_NE(std::find(ply.begin(), ply.end(), "element vertex 80"), ply.end());
  EXPECT_NE(std::find(ply.begin(), ply.end(), "element face 42"), ply.end());
  for (std::size_t i = header + 1 + 80; i < ply.size(); ++i) {
    if (ply[i].rfind("5 ", 0) == 0 && ply[i].ends_with(" 220 40 40")) ++pentagons;
    if (ply[i].rfind("6 ", 0) == 0 && ply[i].ends_with(" 170 170 170")) ++hexagons;
  }
  EXPECT_EQ(pentagons, 12u);
  EXPECT_EQ(hexagons, 30u);
  fs::remove_all(dir);
}

TEST(Writers, StructureFilesGoTogether) {
  const TriMesh cap = hemisphere(2, 8.2);
  const Dual dual = build_dual(cap);
  CarbonStructure c = carbon_structure(dual);
  passivate(c);
  const fs::path dir = temp_dir("bundle") / "out";
  OutputSettings settings;
  settings.deck.mpi_ranks = 8;
  const OutputFiles files = write_structure_files(dir, c, dual.mesh, settings);
  for (const fs::path& f : {files.data, files.deck, files.xyz, files.pdb, files.ply}) {
    EXPECT_TRUE(fs::is_regular_file(f)) << f;
    EXPECT_EQ(f.parent_path(), dir);
  }
  const auto deck = lines_of(files.deck);
  EXPECT_NE(std::find(deck.begin(), deck.end(), "read_data       structure.data"), deck.end());
  EXPECT_NE(std::find(deck.begin(), deck.end(), "pair_coeff      * * CH.rebo C H"), deck.end());
  EXPECT_NE(std::find(deck.begin(), deck.end(), "# Parallel: mpirun -np 8 lmp -in in.rebo"), deck.end());
  EXPECT_EQ(read_lammps_data(files.data).positions.size(), c.atoms());
  fs::remove_all(dir.parent_path());
}

TEST(Writers, Hybrid36Serials) {
  EXPECT_EQ(hybrid36_serial(1), "    1");
  EXPECT_EQ(hybrid36_serial(99999), "99999");
  EXPECT_EQ(hybrid36_serial(100000), "A0000");
  EXPECT_EQ(hybrid36_serial(100001), "A0001");
  EXPECT_EQ(hybrid36_serial(100000 + 36), "A0010");
}

TEST(ReboDeck, NamesTheTypesAndTheMpiCommand) {
  ReboDeckSettings s;
  const std::string carbon_only = rebo_deck(s);
  EXPECT_NE(carbon_only.find("pair_coeff      * * CH.rebo C\n"), std::string::npos);
  EXPECT_NE(carbon_only.find("# Parallel: mpirun -np 4 lmp -in in.rebo"), std::string::npos);
  EXPECT_NE(carbon_only.find("run             10000\n"), std::string::npos);
  EXPECT_NE(carbon_only.find("timestep        0.001\n"), std::string::npos);
  EXPECT_NE(carbon_only.find("atom_style      atomic"), std::string::npos);
  s.hydrogen = true;
  s.topology = true;
  const std::string with_h = rebo_deck(s);
  EXPECT_NE(with_h.find("pair_coeff      * * CH.rebo C H\n"), std::string::npos);
  EXPECT_NE(with_h.find("atom_style      full"), std::string::npos);
  EXPECT_NE(with_h.find("special_bonds   lj/coul 1.0 1.0 1.0"), std::string::npos);
  EXPECT_NE(with_h.find("dump            traj all custom 1000 "), std::string::npos);
  s.steps = 1500;  // the dump interval divides the run, so the last step is in the dump
  EXPECT_NE(rebo_deck(s).find("dump            traj all custom 750 "), std::string::npos);
  s.steps = 100;
  EXPECT_NE(rebo_deck(s).find("dump            traj all custom 100 "), std::string::npos);
}

TEST(LammpsDump, LastFrameSortedById) {
  const fs::path dir = temp_dir("dump");
  std::ofstream(dir / "d.lammpstrj")
      << "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS ss ss ss\n0 1\n0 1\n0 1\n"
         "ITEM: ATOMS id type x y z\n1 1 0 0 0\n2 1 1 0 0\n"
         "ITEM: TIMESTEP\n200\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS ss ss ss\n0 1\n0 1\n0 1\n"
         "ITEM: ATOMS id type x y z\n2 2 5 6 7\n1 1 1 2 3\n";
  const DumpFrame f = read_last_dump_frame(dir / "d.lammpstrj");
  EXPECT_EQ(f.timestep, 200);
  ASSERT_EQ(f.ids.size(), 2u);
  EXPECT_EQ(f.ids[0], 1);
  EXPECT_EQ(f.types[1], 2);
  EXPECT_EQ(f.positions[1], Vec3(5, 6, 7));
  fs::remove_all(dir);
}

// ---- the Debian lmp on written decks (minimise + 200 NVT steps) ------------------------------------------

namespace {

// Writes the data file and a short deck into `dir`, runs lmp there, returns the last dump frame.
DumpFrame run_short_rebo(const CarbonStructure& c, const fs::path& dir, bool topology) {
  LammpsDataSettings data;
  data.topology = topology;
  write_lammps_data(c, dir / "structure.data", data);
  ReboDeckSettings deck;
  deck.hydrogen = c.has_hydrogen();
  deck.topology = topology;
  deck.steps = 200;
  deck.dump_every = 200;
  deck.minimize_iterations = 1000;
  write_rebo_deck(deck, dir / "in.rebo");
  const std::string command =
      "cd '" + dir.string() + "' && lmp -in in.rebo -log log.lammps -screen none > lmp.out 2>&1";
  const int status = std::system(command.c_str());
  EXPECT_EQ(status, 0) << "lmp failed; see " << (dir / "log.lammps");
  return read_last_dump_frame(dir / deck.dump_file);
}

}  // namespace

TEST(LammpsRebo, FullereneKeepsThreeNeighbours) {
  if (!lmp_on_path()) GTEST_SKIP() << "lmp is not on PATH (Debian package lammps): REBO run skipped";
  const CarbonStructure c = fullerene(1);  // C80
  const fs::path dir = temp_dir("rebo_c80");
  const DumpFrame f = run_short_rebo(c, dir, false);
  EXPECT_EQ(f.timestep, 200);
  ASSERT_EQ(f.positions.size(), c.atoms());
  const auto n = neighbour_counts(f.positions, 1.85);
  for (std::size_t i = 0; i < n.size(); ++i) EXPECT_EQ(n[i], 3) << "atom " << i + 1;
  fs::remove_all(dir);
}

TEST(LammpsRebo, TopologyDeckWithPassivatedCapRuns) {
  if (!lmp_on_path()) GTEST_SKIP() << "lmp is not on PATH (Debian package lammps): REBO run skipped";
  const TriMesh cap = hemisphere(2, 8.2);
  Dual dual = build_dual(cap);
  optimize_dual(dual, cap);
  CarbonStructure c = carbon_structure(dual);
  passivate(c);
  const fs::path dir = temp_dir("rebo_cap");
  const DumpFrame f = run_short_rebo(c, dir, true);
  ASSERT_EQ(f.positions.size(), c.atoms());
  const auto n = neighbour_counts(f.positions, 1.85);
  for (std::size_t i = 0; i < n.size(); ++i)
    EXPECT_EQ(n[i], c.elements[i] == Element::C ? 3 : 1) << "atom " << i + 1 << " " << element_symbol(c.elements[i]);
  fs::remove_all(dir);
}
