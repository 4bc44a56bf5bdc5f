// carbonmesh simulate: Kabsch alignment, the stability rule, the MD deck, the run-time loading of liblammps, and
// short REBO2 runs of a C80 fullerene through liblammps (in-process) and mpirun, plus the CLI's error for a missing
// potential.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "carbonmesh/carbon/output_files.hpp"
#include "carbonmesh/carbon/structure.hpp"
#include "carbonmesh/dual/dual_mesh.hpp"
#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/shapes.hpp"
#include "carbonmesh/simulations/kabsch.hpp"
#include "carbonmesh/simulations/md_deck.hpp"
#include "carbonmesh/simulations/simulate.hpp"
#include "carbonmesh/simulations/stability.hpp"
#include "lammps_library.hpp"

namespace carbonmesh {
namespace {
namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("carbonmesh_test_simulate_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// C80 (Ih): the dual of the once-subdivided icosahedron, scaled to a mean bond of 1.42 A.
fs::path write_c80(const fs::path& dir) {
  Dual dual = build_dual(make_icosphere(SphereShape{1.0, 1}));
  std::vector<Vec3> p = dual.positions();
  double mean = 0;
  for (const auto& b : dual.bonds) mean += (p[b[0]] - p[b[1]]).norm();
  mean /= static_cast<double>(dual.bonds.size());
  for (auto& x : p) x *= 1.42 / mean;
  dual.set_positions(p);
  write_structure_files(dir, carbon_structure(dual), dual.mesh, OutputSettings{});
  return dir;
}

std::vector<Vec3> c80_positions() {
  Dual dual = build_dual(make_icosphere(SphereShape{5.0, 1}));
  return dual.positions();
}

TEST(Kabsch, RotatedAndTranslatedCopyAlignsExactly) {
  const auto ref = c80_positions();
  const double a = 0.7, b = -1.1;
  std::vector<Vec3> moved;
  for (const auto& q : ref) {  // rotate about z by a, about x by b, then translate
    const Vec3 r1(std::cos(a) * q[0] - std::sin(a) * q[1], std::sin(a) * q[0] + std::cos(a) * q[1], q[2]);
    const Vec3 r2(r1[0], std::cos(b) * r1[1] - std::sin(b) * r1[2], std::sin(b) * r1[1] + std::cos(b) * r1[2]);
    moved.push_back(r2 + Vec3(3.0, -2.0, 7.5));
  }
  const Alignment al = kabsch_align(ref, moved);
  EXPECT_LT(al.rmsd, 1e-9);
  EXPECT_LT(al.max_displacement, 1e-9);
  const auto back = apply_alignment(al, moved);
  for (std::size_t i = 0; i < ref.size(); ++i) EXPECT_LT((back[i] - ref[i]).norm(), 1e-9);
}

TEST(Kabsch, MirrorImageIsNotAProperRotation) {
  const auto ref = c80_positions();
  std::vector<Vec3> mirrored;
  for (const auto& q : ref) mirrored.emplace_back(q[0], q[1], -q[2] + 0.3 * q[0]);  // reflection + shear
  EXPECT_GT(kabsch_align(ref, mirrored).rmsd, 0.1);
  EXPECT_THROW(kabsch_align(ref, {}), std::invalid_argument);
}

TEST(Stability, VerdictRuleThresholds) {
  const StabilitySettings s;
  EXPECT_TRUE(stability_verdict(1.0, 0.0, s).stable);
  EXPECT_TRUE(stability_verdict(0.99, 0.01, s).stable);
  EXPECT_FALSE(stability_verdict(0.989, 0.0, s).stable);
  EXPECT_FALSE(stability_verdict(1.0, 0.011, s).stable);
  EXPECT_NE(stability_verdict(1.0, 0.0, s).rule.find("99%"), std::string::npos);
  EXPECT_NE(stability_rule(s).find("1%"), std::string::npos);
}

TEST(Stability, RigidMotionKeepsEverythingAndABrokenBondIsSeen) {
  std::vector<Vec3> ref = c80_positions();
  double mean = 0;  // scale to 1.42 A bonds
  Dual dual = build_dual(make_icosphere(SphereShape{5.0, 1}));
  for (const auto& b : dual.bonds) mean += (ref[b[0]] - ref[b[1]]).norm();
  mean /= static_cast<double>(dual.bonds.size());
  for (auto& x : ref) x *= 1.42 / mean;
  const std::vector<bool> carbon(ref.size(), true);
  std::vector<Vec3> moved;
  for (const auto& q : ref) moved.emplace_back(-q[1] + 1, q[0] - 2, q[2] + 3);  // 90 degrees about z
  const FrameComparison same = compare_frames(ref, moved, carbon);
  EXPECT_TRUE(same.verdict.stable);
  EXPECT_EQ(same.coordination_after.at(3), 80u);
  EXPECT_EQ(same.bonds_broken + same.bonds_formed + same.rings_lost + same.rings_formed, 0u);
  EXPECT_EQ(same.ring_count_before, 42u);  // 12 pentagons + 30 hexagons
  EXPECT_LT(same.alignment.rmsd, 1e-9);

  // Pull one atom 1.5 A outwards: its three bonds break.
  std::vector<Vec3> pulled = ref;
  pulled[0] *= 1 + 1.5 / pulled[0].norm();
  const FrameComparison broken = compare_frames(ref, pulled, carbon);
  EXPECT_EQ(broken.bonds_broken, 3u);
  EXPECT_EQ(broken.three_kept, 76u);  // the atom and its three neighbours
  EXPECT_FALSE(broken.verdict.stable);
  EXPECT_EQ(broken.alignment.max_atom, 0);
  // Hydrogen is left out: marking the pulled atom as H makes its neighbours two-bonded before and after.
  std::vector<bool> h = carbon;
  h[0] = false;
  EXPECT_EQ(compare_frames(ref, pulled, h).carbon_atoms, 79u);
}

TEST(MdDeck, ThermoCsvSegmentsAndMarkers) {
  MdDeckSettings s;
  s.data_file = "/d/structure.data", s.potential_file = "/p/CH.rebo", s.dump_file = "/o/dump.lammpstrj";
  s.final_data_file = "/o/final.data", s.thermo_csv = "/o/thermo.csv";
  s.picoseconds = 2.5;
  EXPECT_EQ(md_steps(s), 2500);
  const auto c = md_commands(s);
  int runs = 0, csv = 0, markers = 0;
  for (const auto& line : c) {
    runs += line.rfind("run ", 0) == 0;
    csv += line.find("print 100") != std::string::npos && line.find("\"/o/thermo.csv\"") != std::string::npos;
    markers += line.find(kMdMarker) != std::string::npos;
  }
  EXPECT_EQ(runs, 3);  // 1000 + 1000 + 500
  EXPECT_EQ(csv, 1);
  EXPECT_EQ(markers, 4);  // minimised + one per segment
  EXPECT_NE(std::find(c.begin(), c.end(), "pair_coeff      * * \"/p/CH.rebo\" C"), c.end());
  s.timestep_fs = 0;
  EXPECT_THROW(md_steps(s), std::invalid_argument);
}

bool lmp_available() { return !find_potential().empty(); }

TEST(LammpsLibrary, LoadsEveryFunctionOfTheLibraryTheBuildFound) {
  const LammpsLibrary l = load_lammps_library();
  EXPECT_NE(l.open_no_mpi, nullptr);
  EXPECT_NE(l.close, nullptr);
  EXPECT_NE(l.mpi_finalize, nullptr);
  EXPECT_NE(l.version, nullptr);
  EXPECT_NE(l.command, nullptr);
  EXPECT_NE(l.has_error, nullptr);
  EXPECT_NE(l.get_last_error_message, nullptr);
  EXPECT_NE(l.get_thermo, nullptr);
  EXPECT_NE(l.get_natoms, nullptr);
  EXPECT_NE(l.gather_atoms, nullptr);
}

TEST(LammpsLibrary, AMissingFileOrAnotherLibraryIsAnErrorNamingIt) {
  try {
    load_lammps_library("liblammps-not-installed.so.0");
    FAIL() << "no error for a missing library";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("liblammps-not-installed.so.0"), std::string::npos) << e.what();
  }
  try {
    load_lammps_library("libm.so.6");  // loads, but is not LAMMPS
    FAIL() << "no error for a library without the LAMMPS functions";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("libm.so.6 has no lammps_open_no_mpi"), std::string::npos) << e.what();
  }
}

// The other commands do not load LAMMPS (and its MPI, Python, curl, ...) at start: the program is not linked with it.
TEST(LammpsLibrary, TheCarbonmeshProgramIsNotLinkedWithLiblammps) {
  const std::string command = std::string("ldd '") + CARBONMESH_CLI + "' 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) out += buffer;
  ASSERT_EQ(::pclose(pipe), 0) << out;
  EXPECT_NE(out.find("libOpenMeshCore"), std::string::npos) << out;  // ldd did list the libraries
  EXPECT_EQ(out.find("liblammps"), std::string::npos) << out;
}

TEST(Simulate, C80ShortRunInProcessIsStable) {
  if (!lmp_available()) GTEST_SKIP() << "CH.rebo not found (Debian package lammps-data)";
  const fs::path dir = write_c80(temp_dir("c80"));
  SimulationSettings s;
  s.structure_dir = dir;
  s.picoseconds = 0.3;  // 300 steps
  const SimulationResult r = simulate(s);
  EXPECT_EQ(r.atoms, 80u);
  EXPECT_EQ(r.run.steps, 300);
  EXPECT_TRUE(r.comparison.verdict.stable) << r.comparison.verdict.reason;
  EXPECT_EQ(r.comparison.coordination_after.size(), 1u);
  EXPECT_EQ(r.comparison.coordination_after.at(3), 80u);  // every atom keeps three neighbours
  EXPECT_EQ(r.comparison.bonds_broken + r.comparison.bonds_formed, 0u);
  EXPECT_LT(r.pe_minimized_per_atom, -6.5);  // C80 under REBO2: about -7.0 eV/atom
  EXPECT_GT(r.pe_minimized_per_atom, -7.4);
  EXPECT_LT(r.comparison.alignment.rmsd, 0.5);
  for (const char* f : {"thermo.csv", "dump.lammpstrj", "final.data", "log.lammps", "report/report.json"})
    EXPECT_TRUE(fs::exists(r.output_dir / f)) << f;
  std::ifstream csv(r.output_dir / "thermo.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header, "step,temp,pe,ke,etotal,press");
  fs::remove_all(dir);
}

TEST(Simulate, C80ShortRunThroughMpirun) {
  if (!lmp_available() || std::system("command -v mpirun > /dev/null && command -v lmp > /dev/null") != 0)
    GTEST_SKIP() << "mpirun or lmp not on PATH";
  const fs::path dir = write_c80(temp_dir("c80mpi"));
  SimulationSettings s;
  s.structure_dir = dir;
  s.picoseconds = 0.2;
  s.np = 2;
  s.report = false;
  const SimulationResult r = simulate(s);
  EXPECT_NE(r.run.mode.find("-np 2"), std::string::npos);
  EXPECT_TRUE(r.comparison.verdict.stable) << r.comparison.verdict.reason;
  EXPECT_EQ(r.comparison.coordination_after.at(3), 80u);
  EXPECT_LT(r.pe_final_per_atom, -6.5);
  fs::remove_all(dir);
}

TEST(Simulate, MissingPotentialAndBadPotentialAreInputErrors) {
  const fs::path dir = write_c80(temp_dir("errors"));
  SimulationSettings s;
  s.structure_dir = dir;
  s.picoseconds = 0.1;
  s.potential = dir / "missing.rebo";
  EXPECT_THROW(simulate(s), InputError);
  std::ofstream(dir / "bad.rebo") << "not a potential\n";
  s.potential = dir / "bad.rebo";
  testing::internal::CaptureStderr();  // (the forked LAMMPS child writes to the same stderr)
  try {
    simulate(s);
    ADD_FAILURE() << "a broken potential file must fail";
  } catch (const InputError& e) {
    // One line naming the command that failed (the library throws a C++ exception on this file).
    const std::string what = e.what();
    EXPECT_NE(what.find("LAMMPS run failed"), std::string::npos) << what;
    EXPECT_NE(what.find("pair_coeff"), std::string::npos) << what;
    EXPECT_NE(what.find("bad.rebo"), std::string::npos) << what;
  }
  const std::string stderr_text = testing::internal::GetCapturedStderr();
  EXPECT_EQ(stderr_text.find("LAMMPS child"), std::string::npos) << stderr_text;  // no second error line
  s.structure_dir = dir / "nothing";
  EXPECT_THROW(simulate(s), InputError);
  fs::remove_all(dir);
}

TEST(SimulateCli, MissingPotentialExitsTwoWithOneLine) {
  const fs::path dir = write_c80(temp_dir("cli"));
  const std::string cmd = std::string(CARBONMESH_CLI) + " -q simulate " + dir.string() +
                          " --ps 0.1 --potential /nonexistent/CH.rebo > " + (dir / "out").string() + " 2> " +
                          (dir / "err").string();
  const int status = std::system(cmd.c_str());
  EXPECT_EQ(WEXITSTATUS(status), 2);
  std::ifstream err(dir / "err");
  std::string line, rest;
  std::getline(err, line);
  EXPECT_NE(line.find("potential file not found"), std::string::npos) << line;
  EXPECT_FALSE(std::getline(err, rest)) << rest;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace carbonmesh
