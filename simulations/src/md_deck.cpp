#include "carbonmesh/simulations/md_deck.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "carbonmesh/carbon/rebo_deck.hpp"

namespace carbonmesh {
namespace fs = std::filesystem;
namespace {

std::string quoted(const fs::path& p) { return fmt::format("\"{}\"", p.string()); }

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

}  // namespace

long md_steps(const MdDeckSettings& s) {
  if (!(s.picoseconds > 0) || !(s.timestep_fs > 0) || !(s.temperature > 0) || s.thermo_every <= 0)
    throw std::invalid_argument("simulation time, timestep, temperature and thermo interval must be positive");
  return std::max(1L, std::lround(s.picoseconds * 1000.0 / s.timestep_fs));
}

long steps_per_ps(const MdDeckSettings& s) { return std::max(1L, std::lround(1000.0 / s.timestep_fs)); }

std::vector<std::string> md_commands(const MdDeckSettings& s) {
  const long steps = md_steps(s), segment = std::min(steps, steps_per_ps(s));
  for (const auto* p : {&s.data_file, &s.potential_file, &s.dump_file, &s.final_data_file, &s.thermo_csv})
    if (p->string().find('"') != std::string::npos) throw std::invalid_argument("md_commands: a path holds a quote");
  ReboDeckSettings deck;
  deck.data_file = quoted(s.data_file);
  deck.dump_file = quoted(s.dump_file);
  deck.final_data_file = quoted(s.final_data_file);
  deck.hydrogen = s.hydrogen;
  deck.topology = s.topology;
  deck.temperature = s.temperature;
  deck.timestep = s.timestep_fs / 1000.0;
  deck.steps = steps;
  deck.thermo_every = s.thermo_every;
  deck.dump_every = segment;  // one frame a picosecond (the deck keeps it a divisor of the run)
  deck.seed = s.seed;

  std::vector<std::string> out;
  std::istringstream text(rebo_deck(deck));
  std::string line;
  while (std::getline(text, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (starts_with(line, "pair_coeff")) {
      out.push_back(fmt::format("pair_coeff      * * {} C{}", quoted(s.potential_file), s.hydrogen ? " H" : ""));
    } else if (starts_with(line, "thermo_style")) {
      out.push_back(line);
      for (const char* v : {"step", "temp", "pe", "ke", "etotal", "press"})
        out.push_back(fmt::format("variable        cm_{} equal {}", v, v));
    } else if (starts_with(line, "minimize")) {
      out.push_back(line);
      out.push_back(fmt::format("print           \"{} minimized pe ${{cm_pe}}\" screen yes", kMdMarker));
    } else if (starts_with(line, "run")) {
      out.push_back(fmt::format(
          "fix             thermo_csv all print {} \"${{cm_step}},${{cm_temp}},${{cm_pe}},${{cm_ke}},${{cm_etotal}},"
          "${{cm_press}}\" file {} screen no title \"step,temp,pe,ke,etotal,press\"",
          s.thermo_every, quoted(s.thermo_csv)));
      for (long done = 0; done < steps;) {
        const long n = std::min(segment, steps - done);
        out.push_back(fmt::format("run             {}", n));
        done += n;
        out.push_back(fmt::format("print           \"{} step ${{cm_step}} temp ${{cm_temp}} pe ${{cm_pe}}\" screen yes",
                                  kMdMarker));
      }
    } else {
      out.push_back(line);
    }
  }
  return out;
}

fs::path find_potential(const std::string& name) {
  std::vector<fs::path> dirs{fs::current_path()};
  if (const char* env = std::getenv("LAMMPS_POTENTIALS")) dirs.emplace_back(env);
  dirs.emplace_back("/usr/share/lammps/potentials");
  std::error_code ec;
  for (const auto& d : dirs)
    if (fs::is_regular_file(d / name, ec)) return fs::absolute(d / name);
  return {};
}

}  // namespace carbonmesh
