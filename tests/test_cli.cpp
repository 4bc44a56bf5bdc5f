// The command line's help: `carbonmesh help TOPIC` and every option of every command showing its default.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "test_paths.hpp"

namespace {

struct RunResult {
  int exit_code;
  std::string output;
};

RunResult run_cli(const std::string& args) {
  const auto out = std::filesystem::temp_directory_path() /
                   ("carbonmesh-test-cli-" + std::to_string(::getpid()) + ".txt");
  const std::string command = std::string(CARBONMESH_CLI) + " " + args + " > " + out.string() + " 2>&1";
  const int status = std::system(command.c_str());
  std::ifstream in(out);
  std::stringstream text;
  text << in.rdbuf();
  std::filesystem::remove(out);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

const std::vector<std::string> kCommands{"stats", "shape", "remesh", "build", "analyze", "simulate"};

// The option blocks of a CLI11 help text: a line starting with "  -" and its indented continuation lines.
std::vector<std::string> option_blocks(const std::string& help) {
  std::vector<std::string> blocks;
  std::istringstream in(help);
  std::string line;
  bool in_options = false;
  while (std::getline(in, line)) {
    if (line.rfind("Options:", 0) == 0) {
      in_options = true;
      continue;
    }
    if (!in_options) continue;
    if (line.rfind("  -", 0) == 0)
      blocks.push_back(line);
    else if (line.rfind("      ", 0) == 0 && !blocks.empty())
      blocks.back() += " " + line;
    else if (!line.empty() && line[0] != ' ')
      in_options = false;
  }
  return blocks;
}

}  // namespace

// `shape geodesic`: frequency 2 with the sqrt(3) step is the triangulation whose dual is C240.
TEST(CliShape, GeodesicWritesTheDualOfC240) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("carbonmesh-test-geodesic-" + std::to_string(::getpid()) + ".off");
  EXPECT_EQ(run_cli("shape geodesic --frequency 2 --sqrt3 -o " + path.string()).exit_code, 0);
  const RunResult stats = run_cli("stats " + path.string());
  EXPECT_EQ(stats.exit_code, 0);
  EXPECT_NE(stats.output.find("V 122  E 360  F 240"), std::string::npos) << stats.output;
  EXPECT_NE(stats.output.find("valence interior 5:12 6:110"), std::string::npos) << stats.output;
  std::filesystem::remove(path);
}

// `shape geodesic --indices 2,1`: the Goldberg-Coxeter sphere whose dual is the chiral C140 (T = 7); the indices
// replace --frequency and --sqrt3.
TEST(CliShape, GeodesicIndicesWriteTheDualOfC140) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("carbonmesh-test-goldberg-" + std::to_string(::getpid()) + ".off");
  EXPECT_EQ(run_cli("shape geodesic --indices 2,1 -o " + path.string()).exit_code, 0);
  const RunResult stats = run_cli("stats " + path.string());
  EXPECT_EQ(stats.exit_code, 0);
  EXPECT_NE(stats.output.find("V 72  E 210  F 140"), std::string::npos) << stats.output;
  EXPECT_NE(stats.output.find("valence interior 5:12 6:60"), std::string::npos) << stats.output;
  std::filesystem::remove(path);
  EXPECT_NE(run_cli("shape geodesic --indices 2,1 --sqrt3 -o " + path.string()).exit_code, 0);
  EXPECT_EQ(run_cli("shape geodesic --indices 0,0 -o " + path.string()).exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(path));
}

// The capped (10, 0) tube (icosahedral caps) and the capped (9, 0) and (6, 6) tubes (apex caps): 12 vertices of
// valence 5 and the rest of valence 6, which `build` takes as it is (every edge inside its interval, the mean at the
// lattice edge): 12 pentagons in the carbon net, hexagons otherwise.
TEST(CliShape, CappedTubeWritesTheDualOfACappedNanotube) {
  for (const char* chirality : {"10,0", "9,0", "6,6"}) {
    SCOPED_TRACE(chirality);
    const auto base =
        std::filesystem::temp_directory_path() / ("carbonmesh-test-capped-" + std::to_string(::getpid()));
    const std::string path = base.string() + ".off";
    const RunResult shape =
        run_cli(std::string("shape capped-tube --chirality ") + chirality + " --length 20 -o " + path);
    EXPECT_EQ(shape.exit_code, 0) << shape.output;
    const RunResult stats = run_cli("stats " + path);
    EXPECT_NE(stats.output.find("valence interior 5:12 6:"), std::string::npos) << stats.output;
    EXPECT_NE(stats.output.find("genus 0"), std::string::npos) << stats.output;
    const RunResult build = run_cli("build " + path + " -o " + base.string() + " --no-report");
    EXPECT_EQ(build.exit_code, 0) << build.output;
    EXPECT_NE(build.output.find("iterations 0"), std::string::npos) << build.output;
    // The ring counts, "rings 5:12 6:N  open rings": pentagons and hexagons only (not a search of the whole output,
    // whose log lines carry the time of day).
    const std::size_t rings = build.output.find("rings 5:12 6:");
    ASSERT_NE(rings, std::string::npos) << build.output;
    const std::string counts = build.output.substr(rings, build.output.find("open rings", rings) - rings);
    EXPECT_EQ(std::count(counts.begin(), counts.end(), ':'), 2) << counts;
    std::filesystem::remove_all(base);
    std::filesystem::remove(path);
  }
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("carbonmesh-test-capped-" + std::to_string(::getpid()) + ".off"))
                               .string();
  EXPECT_EQ(run_cli("shape capped-tube --chirality 2,1 -o " + path).exit_code, 2);
  EXPECT_EQ(run_cli("shape capped-tube --radius 5 -o " + path).exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(CliHelp, ListsTheTopicsWithoutOne) {
  const RunResult r = run_cli("help");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  for (const char* topic : {"all", "build", "units", "exit-codes", "files", "verdict"})
    EXPECT_NE(r.output.find(topic), std::string::npos) << topic << " missing from\n" << r.output;
}

TEST(CliHelp, EveryCommandHasAHelpTopic) {
  for (const std::string& command : kCommands) {
    const RunResult topic = run_cli("help " + command);
    EXPECT_EQ(topic.exit_code, 0) << command << ": " << topic.output;
    EXPECT_EQ(topic.output, run_cli(command + " --help").output) << command;
  }
}

TEST(CliHelp, EveryValueOptionStatesItsDefault) {
  // A value option (FLOAT, INT, UINT, TEXT, ENUM) shows "=default", is REQUIRED, or says "default" in its text.
  const std::regex value_type("(FLOAT|INT|UINT|TEXT|ENUM)");
  for (const std::string& command : kCommands) {
    const std::vector<std::string> blocks = option_blocks(run_cli(command + " --help").output);
    ASSERT_FALSE(blocks.empty()) << command;
    for (const std::string& block : blocks) {
      if (!std::regex_search(block, value_type)) continue;  // a flag
      // The signature is the first line up to the description, which CLI11 sets off by two or more spaces.
      const std::string signature = block.substr(0, block.find("  ", 2));
      const bool has_default = signature.find('=') != std::string::npos ||
                               block.find("REQUIRED") != std::string::npos ||
                               block.find("default") != std::string::npos;
      EXPECT_TRUE(has_default) << command << ": " << block;
    }
  }
}

TEST(CliHelp, TopicPagesAndAllPrint) {
  EXPECT_NE(run_cli("help exit-codes").output.find("topology guard"), std::string::npos);
  EXPECT_NE(run_cli("help verdict").output.find("99%"), std::string::npos);
  EXPECT_NE(run_cli("help units").output.find("Angstrom"), std::string::npos);
  const RunResult all = run_cli("help all");
  EXPECT_EQ(all.exit_code, 0);
  for (const std::string& command : kCommands) EXPECT_NE(all.output.find(command), std::string::npos) << command;
  EXPECT_NE(all.output.find("--surface-weight"), std::string::npos);
}

TEST(CliHelp, UnknownTopicIsOneLineAndExit2) {
  const RunResult r = run_cli("help nonsense");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("no help topic 'nonsense'"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}
