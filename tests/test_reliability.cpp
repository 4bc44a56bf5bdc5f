// Reliability: interrupted writes leave nothing behind; outputs are byte-identical run to run and across
// thread counts.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "carbonmesh/carbon/lammps_data.hpp"
#include "carbonmesh/remesh/atomic_file.hpp"
#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/io.hpp"
#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/shapes.hpp"
#include "carbonmesh/simulations/lammps_atoms.hpp"
#include "test_meshes.hpp"
#include "test_paths.hpp"

namespace fs = std::filesystem;
using namespace carbonmesh;

namespace {

fs::path fresh_dir(const std::string& name) {
  const auto dir = fs::temp_directory_path() / ("carbonmesh-test-rel-" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

int count_files(const fs::path& dir) {
  int n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}

struct CliRun {
  int exit_code;
  std::string out, err;
};

// Runs the CLI (quiet: warnings and errors only) with stdout and stderr captured separately.
CliRun run_cli(const fs::path& dir, const std::string& args) {
  const auto out = dir / "stdout.txt", err = dir / "stderr.txt";
  const std::string command =
      std::string(CARBONMESH_CLI) + " -q " + args + " > " + out.string() + " 2> " + err.string();
  const int status = std::system(command.c_str());
  CliRun r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_bytes(out), read_bytes(err)};
  fs::remove(out);
  fs::remove(err);
  return r;
}

std::size_t lines(const std::string& text) { return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')); }

}  // namespace

TEST(AtomicOutput, SigtermWhileWritingLeavesNoFile) {
  const auto dir = fresh_dir("sigterm");
  const auto target = dir / "structure.data";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    remove_partial_files_on_interrupt();
    write_atomically(target, [](const fs::path& tmp) {
      std::ofstream(tmp) << "half of a data file";
      std::raise(SIGTERM);  // interrupted in the middle of the write
    });
    std::_Exit(0);  // not reached
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << "the process ends by the signal, non-zero";
  EXPECT_FALSE(fs::exists(target));
  EXPECT_EQ(count_files(dir), 0) << "no partial file is left";
}

TEST(AtomicOutput, FailedWriteKeepsThePreviousFile) {
  const auto dir = fresh_dir("keep");
  const auto target = dir / "mesh.off";
  save_mesh(make_icosphere({1.0, 1}), target);
  const std::string before = read_bytes(target);
  EXPECT_THROW(write_atomically(target,
                                [](const fs::path& tmp) {
                                  std::ofstream(tmp) << "partial";
                                  throw std::runtime_error("disk full");
                                }),
               std::runtime_error);
  EXPECT_EQ(read_bytes(target), before);
  EXPECT_EQ(count_files(dir), 1);
}

TEST(Determinism, RemeshIsByteIdenticalAcrossRunsAndThreadCounts) {
  const auto dir = fresh_dir("determinism");
  // A capsule scaled up so that the remesher refines and moves every vertex.
  save_mesh(make_capsule({4.0, 12.0, 2.4}), dir / "in.off");
  std::string outputs[3];
  const char* threads[3] = {"1", "2", "2"};
  for (int run = 0; run < 3; ++run) {
    const auto out = dir / ("out" + std::to_string(run) + ".off");
    const std::string command = std::string("OMP_NUM_THREADS=") + threads[run] + " " + CARBONMESH_CLI +
                                " -q remesh " + (dir / "in.off").string() + " " + out.string() +
                                " --emin 1.2 --emax 1.8 > /dev/null 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    outputs[run] = read_bytes(out);
    ASSERT_FALSE(outputs[run].empty());
  }
  EXPECT_EQ(outputs[0], outputs[1]) << "1 thread vs 2 threads";
  EXPECT_EQ(outputs[1], outputs[2]) << "two runs with 2 threads";
}

// The dual optimisation of a structure large enough for its parallel paths (term classes from 20000 atoms,
// the L-BFGS vector kernels from 60000 coordinates): the same structure.data for 1 and 2 threads.
TEST(Determinism, LargeBuildIsByteIdenticalAcrossThreadCounts) {
  const auto dir = fresh_dir("determinism-build");
  std::string outputs[2];
  const char* threads[2] = {"1", "2"};
  for (int run = 0; run < 2; ++run) {
    const auto out = dir / ("out" + std::to_string(run));
    const std::string command = std::string("OMP_NUM_THREADS=") + threads[run] + " " + CARBONMESH_CLI +
                                " -q build -o " + out.string() + " --atoms 20480 --no-report > /dev/null 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    outputs[run] = read_bytes(out / "structure.data");
    ASSERT_FALSE(outputs[run].empty());
  }
  EXPECT_EQ(outputs[0], outputs[1]) << "1 thread vs 2 threads";
}

TEST(FuzzRegression, DataFileWithAHugeIdIsAnInputError) {
  // Found by fuzz_lammps_data: an atom id of 1e300 was cast to int (undefined behaviour).
  const auto dir = fresh_dir("fuzz-data");
  const auto path = dir / "huge-id.data";
  std::ofstream(path) << "LAMMPS data file\n\n1 atoms\n1 atom types\n\n-5 5 xlo xhi\n-5 5 ylo yhi\n-5 5 zlo zhi\n\n"
                         "Masses\n\n1 12.011\n\nAtoms # atomic\n\n1e300 1 0 0 0\n";
  EXPECT_THROW(read_lammps_data(path), InputError);
  EXPECT_THROW(read_lammps_atoms(path), InputError);
}

TEST(BadInputCorpus, BuildRefusesBadOptionValuesInOneLine) {
  const auto dir = fresh_dir("options");
  for (const std::string option : {"--atoms 0", "--atoms -5", "--atoms 1e12", "--atoms nan", "--size 0",
                                   "--scale 0", "--scale -1", "--bond 0", "--bond inf"}) {
    const auto out = dir / "out";
    const CliRun r = run_cli(dir, "build -o " + out.string() + " --no-report " + option);
    EXPECT_EQ(r.exit_code, kExitBadInput) << option << ": " << r.err;
    EXPECT_EQ(lines(r.err), 1u) << option << ": " << r.err;
    EXPECT_NE(r.err.find(option.substr(0, option.find(' '))), std::string::npos) << "names the option: " << r.err;
    EXPECT_FALSE(fs::exists(out)) << option << ": nothing is written";
  }
  const CliRun limit = run_cli(dir, "build -o " + (dir / "out").string() + " --atoms 1e12");
  EXPECT_NE(limit.err.find("1e+08"), std::string::npos) << "names the limit: " << limit.err;
}

TEST(BadInputCorpus, ModelsInTheWrongUnitsAreRefusedNotRemeshedForever) {
  // A sphere of radius 1e9 remeshed to edges of about 2.5 would need ~1e18 triangles (it used to run until
  // the memory was full); one of radius 1e-9 would hold no atom.
  const auto dir = fresh_dir("units");
  save_mesh(make_icosphere({1e9, 2}), dir / "huge.off");
  save_mesh(make_icosphere({1e-9, 2}), dir / "tiny.off");
  const CliRun remeshed = run_cli(dir, "remesh " + (dir / "huge.off").string() + " " + (dir / "huge-out.off").string() +
                                        " --emin 1.2 --emax 1.8");
  EXPECT_EQ(remeshed.exit_code, kExitBadInput) << remeshed.err;
  EXPECT_NE(remeshed.err.find("more than the limit"), std::string::npos) << remeshed.err;
  EXPECT_FALSE(fs::exists(dir / "huge-out.off"));
  const CliRun huge = run_cli(dir, "build " + (dir / "huge.off").string() + " -o " + (dir / "huge").string());
  EXPECT_EQ(huge.exit_code, kExitBadInput) << huge.err;
  EXPECT_EQ(lines(huge.err), 1u) << huge.err;
  EXPECT_NE(huge.err.find("huge.off"), std::string::npos) << huge.err;
  EXPECT_NE(huge.err.find("--atoms"), std::string::npos) << "says how to fix it: " << huge.err;
  const CliRun tiny = run_cli(dir, "build " + (dir / "tiny.off").string() + " -o " + (dir / "tiny").string());
  EXPECT_EQ(tiny.exit_code, kExitBadInput) << tiny.err;
  EXPECT_NE(tiny.err.find("less than one"), std::string::npos) << tiny.err;
  EXPECT_FALSE(fs::exists(dir / "huge"));
  EXPECT_FALSE(fs::exists(dir / "tiny"));
  // Scaled with --atoms, the huge sphere is a correct structure.
  const CliRun scaled = run_cli(dir, "build " + (dir / "huge.off").string() + " -o " + (dir / "scaled").string() +
                                      " --atoms 200 --no-report --steps 10");
  ASSERT_EQ(scaled.exit_code, 0) << scaled.err;
  std::ifstream summary_file(dir / "scaled" / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(summary_file);
  EXPECT_GT(summary["atoms"].get<int>(), 150);
  EXPECT_LT(summary["atoms"].get<int>(), 250);
  EXPECT_EQ(summary["genus"], 0);
  EXPECT_EQ(summary["remesh"]["topology_violation"], false);
}

// [2.4, 2.9] (emin 0.83 emax): [2.2, 2.9] converged in 5 iterations since the nonlinear optimizer's damping follows
// its gain ratio (session 47; it had left 1 short edge).
TEST(BadInputCorpus, TooTightIntervalWarnsRunsAndReportsTheEdgesLeft) {
  const auto dir = fresh_dir("tight");
  save_mesh(make_icosphere({10.0, 2}), dir / "sphere.off");
  const CliRun r = run_cli(dir, "remesh " + (dir / "sphere.off").string() + " " + (dir / "tight.off").string() +
                                 " --emin 2.4 --emax 2.9 --iterations 5 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("too tight"), std::string::npos) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_FALSE(j["converged"].get<bool>());
  EXPECT_FALSE(j["topology_violation"].get<bool>());
  const std::string left = std::to_string(j["long"].get<std::size_t>()) + " long and " +
                           std::to_string(j["short"].get<std::size_t>()) + " short edges remain outside [2.4, 2.9]";
  EXPECT_GT(j["long"].get<std::size_t>() + j["short"].get<std::size_t>(), 0u);
  EXPECT_NE(r.err.find(left), std::string::npos) << "expected '" << left << "' in: " << r.err;
  EXPECT_TRUE(fs::is_regular_file(dir / "tight.off")) << "the best mesh is written";
}

// A number out of its range is named in words (CLI11's own checks wrote out the largest double, 309 digits).
TEST(BadInputCorpus, NumberOptionsOutOfRangeSayWhatIsWrong) {
  const auto dir = fresh_dir("numbers");
  const std::string remesh = "remesh in.off out.off --emin 1.2 --emax 1.8 ";
  for (const auto& [args, said] : std::vector<std::pair<std::string, std::string>>{
           {remesh + "--kl -1", "--kl: -1 must be a positive number"},
           {remesh + "--l nan", "--l: nan must be a finite number, not negative"},
           {remesh + "--iterations -3", "--iterations: -3 must be a finite number, not negative"},
           {"stats in.off --samples 0", "--samples: 0 must be a positive number"},
           {"simulate in.data --ps -1", "--ps: -1 must be a positive number"},
           {"simulate in.data --temp inf", "--temp: inf must be a positive number"},
           {"simulate in.data --ps abc", "--ps: abc is not a number"}}) {
    const CliRun r = run_cli(dir, args);
    EXPECT_EQ(r.exit_code, kExitBadInput) << args << ": " << r.err;
    EXPECT_EQ(lines(r.err), 1u) << args << ": " << r.err;
    EXPECT_NE(r.err.find(said), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(r.err.find("1797693"), std::string::npos) << args << ": " << r.err;
  }
}

TEST(BadInputCorpus, SnapToleranceMustBeFiniteAndNotNegative) {
  const auto dir = fresh_dir("snap_tolerance_bad");
  save_mesh(make_icosphere({10.0, 2}), dir / "sphere.off");
  for (const std::string value : {"nan", "inf", "-1"}) {
    const CliRun r = run_cli(dir, "remesh " + (dir / "sphere.off").string() + " " + (dir / "out.off").string() +
                                   " --emin 1.2 --emax 1.8 --snap-tolerance " + value);
    EXPECT_EQ(r.exit_code, kExitBadInput) << value << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("--snap-tolerance: " + value + " must be a finite number, not negative"), std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir / "out.off"));
  }
}

// The snap tolerance decides which input points count as cut off: on a sphere with 2% radial noise some are farther
// than the default, and with a tolerance beyond every distance the snap, the flips toward the input and the minimax
// fit leave the mesh as it is; every edge is inside either way.
TEST(RemeshCli, SnapToleranceSetsWhichInputPointsAreChased) {
  const auto dir = fresh_dir("snap_tolerance");
  save_mesh(test::scaled(test::radial_noise(make_icosphere({20.0, 3}), 0.02, 1), 2.25), dir / "noisy.off");
  auto remesh_json = [&](const std::string& extra) {
    const CliRun r = run_cli(dir, "remesh " + (dir / "noisy.off").string() + " " + (dir / "out.off").string() +
                                   " --emin 1.2 --emax 1.8 --json" + extra);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return nlohmann::json::parse(r.out);
  };
  const nlohmann::json chased = remesh_json("");
  const nlohmann::json left = remesh_json(" --snap-tolerance 100");
  for (const nlohmann::json* j : {&chased, &left}) {
    EXPECT_EQ((*j)["long"], 0);
    EXPECT_EQ((*j)["short"], 0);
  }
  EXPECT_GT(chased["snap_max_before"].get<double>(), chased["snap_tolerance"].get<double>() * 1.2);
  EXPECT_GT(chased["snapped_vertices"].get<int>(), 0);
  EXPECT_EQ(left["snap_tolerance"], 100.0);
  EXPECT_EQ(left["snapped_vertices"], 0);
  EXPECT_EQ(left["data_dependent_flips"], 0);
  EXPECT_EQ(left["minimax_moves"], 0);
}

// Debris beside a model (a speck, a stray triangle) has less area than the interval's smallest closed surface and
// cannot be remeshed into it: `remesh` removes it with a warning, and the model converges as it does alone and gets
// the steps that start once every edge is inside. Kept, their edges stay outside (a stray triangle of side 1 beside a
// sphere: 3 short edges after 59 iterations and 84.33% regular vertices, docs/reliability.md).
TEST(RemeshCli, ComponentsTooSmallForTheIntervalAreRemoved) {
  const auto dir = fresh_dir("remesh_debris");
  TriMesh mesh = test::scaled(make_icosphere({10.0, 3}), 2.25);
  const TriMesh speck = make_icosphere({0.2, 1});
  test::append_copy(mesh, speck, Vec3(40, 0, 0));
  mesh.add_face(mesh.add_vertex(Vec3(50, 0, 0)), mesh.add_vertex(Vec3(51, 0, 0)), mesh.add_vertex(Vec3(50.5, 0.8, 0)));
  save_mesh(mesh, dir / "debris.off");
  const CliRun r = run_cli(dir, "remesh " + (dir / "debris.off").string() + " " + (dir / "out.off").string() +
                                    " --emin 1.2 --emax 1.8 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("debris.off: removed 2 components with less area than four triangles of the interval"),
            std::string::npos)
      << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["removed_components"]["removed"], 2);
  EXPECT_EQ(j["removed_components"]["faces"], speck.n_faces() + 1);
  EXPECT_EQ(j["long"], 0);
  EXPECT_EQ(j["short"], 0);
  EXPECT_TRUE(j["snapped"].get<bool>());
  EXPECT_GE(j["percent_regular"].get<double>(), 90.0);
  EXPECT_EQ(topology(load_mesh(dir / "out.off")).components, 1u);
  // A model of one piece is written as remeshed, nothing removed.
  const CliRun whole = run_cli(dir, "remesh " + (dir / "out.off").string() + " " + (dir / "again.off").string() +
                                        " --emin 1.2 --emax 1.8 --json");
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_EQ(nlohmann::json::parse(whole.out)["removed_components"]["removed"], 0);
}
