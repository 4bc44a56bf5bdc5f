// Reliability: interrupted writes leave nothing behind; outputs are byte-identical run to run and across
// thread counts.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "carbonmesh/carbon/lammps_data.hpp"
#include "carbonmesh/remesh/atomic_file.hpp"
#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/io.hpp"
#include "carbonmesh/remesh/shapes.hpp"
#include "carbonmesh/simulations/lammps_atoms.hpp"
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

TEST(FuzzRegression, DataFileWithAHugeIdIsAnInputError) {
  // Found by fuzz_lammps_data: an atom id of 1e300 was cast to int (undefined behaviour).
  const auto dir = fresh_dir("fuzz-data");
  const auto path = dir / "huge-id.data";
  std::ofstream(path) << "LAMMPS data file\n\n1 atoms\n1 atom types\n\n-5 5 xlo xhi\n-5 5 ylo yhi\n-5 5 zlo zhi\n\n"
                         "Masses\n\n1 12.011\n\nAtoms # atomic\n\n1e300 1 0 0 0\n";
  EXPECT_THROW(read_lammps_data(path), InputError);
  EXPECT_THROW(read_lammps_atoms(path), InputError);
}
