#include "carbonmesh/simulations/lammps_run.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/simulations/md_deck.hpp"
#include "lammps_library.hpp"

namespace carbonmesh {
namespace fs = std::filesystem;
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

bool on_path(const std::string& exe) {
  return std::system(("command -v " + shell_quote(exe) + " > /dev/null 2>&1").c_str()) == 0;
}

void log_progress(const LammpsRunSettings& s, long step, double temp, double pe) {
  const double ps = static_cast<double>(step) * s.timestep_fs / 1000.0;
  const double total = static_cast<double>(s.steps) * s.timestep_fs / 1000.0;
  spdlog::info("MD {:6.2f} / {:.2f} ps  step {:7d}  T {:7.1f} K  pe {:.4f} eV/atom", ps, total, step, temp,
               s.atoms ? pe / static_cast<double>(s.atoms) : pe);
}

// ---- in-process (liblammps in a forked child) ------------------------------------------------------------

// Runs in the child: every command through the library, results to `result_file` (with "error" when one failed).
// Returns the exit code.
int child_run(const LammpsRunSettings& s, const fs::path& result_file) {
  nlohmann::json out;
  // One OpenMP thread (LAMMPS reads this when it opens): a forked child must not start OpenMP thread teams of
  // a parent that already used them (libgomp would wait for the parent's pool threads forever).
  setenv("OMP_NUM_THREADS", "1", 1);
  const std::string log = (s.work_dir / "log.lammps").string();
  const char* args[] = {"carbonmesh", "-log", log.c_str(), "-screen", "none", "-nocite"};
  LammpsLibrary lammps;
  void* lmp = nullptr;
  try {
    lammps = load_lammps_library();
    lmp = lammps.open_no_mpi(6, const_cast<char**>(args), nullptr);
    if (!lmp) out["error"] = "liblammps could not be opened";
  } catch (const std::exception& e) {
    out["error"] = e.what();
  }
  if (lmp) {
    out["version"] = lammps.version(lmp);
    const auto start = Clock::now();
    std::optional<Clock::time_point> md_start;
    bool thrown = false;
    for (const auto& command : s.commands) {
      std::string error;
      try {
        lammps.command(lmp, command.c_str());
      } catch (const std::exception& e) {
        // A C++ exception out of the C interface: the Debian library (20220106) throws std::logic_error ("basic_string:
        // construction from null") on a REBO file that is not one. The instance is not closed after it.
        error = *e.what() ? e.what() : "C++ exception";
        thrown = true;
      }
      if (!thrown && lammps.has_error(lmp)) {
        char buffer[1024] = {0};
        lammps.get_last_error_message(lmp, buffer, sizeof buffer);
        error = buffer[0] ? buffer : "unknown error";
      }
      if (!error.empty()) {
        out["error"] = fmt::format("LAMMPS: {} (command: {})", error, command);
        break;
      }
      if (starts_with(command, "minimize")) {
        out["pe_minimized"] = lammps.get_thermo(lmp, "pe");
        spdlog::info("minimised: pe {:.4f} eV/atom", s.atoms ? lammps.get_thermo(lmp, "pe") / s.atoms : 0.0);
        md_start = Clock::now();
      } else if (starts_with(command, "run")) {
        log_progress(s, std::lround(lammps.get_thermo(lmp, "step")), lammps.get_thermo(lmp, "temp"),
                     lammps.get_thermo(lmp, "pe"));
        out["pe_final"] = lammps.get_thermo(lmp, "pe");
        out["temperature_final"] = lammps.get_thermo(lmp, "temp");
        out["steps"] = std::lround(lammps.get_thermo(lmp, "step"));
        if (md_start) out["md_seconds"] = since(*md_start);
      }
    }
    if (!out.contains("error")) {
      const auto n = static_cast<std::size_t>(lammps.get_natoms(lmp));
      std::vector<double> x(3 * n);
      lammps.gather_atoms(lmp, const_cast<char*>("x"), 1, 3, x.data());  // ordered by atom id 1..N
      out["x"] = x;
    }
    out["seconds"] = since(start);
    if (!thrown) lammps.close(lmp);
  }
  if (lammps.mpi_finalize) lammps.mpi_finalize();
  std::ofstream f(result_file);
  f << out.dump();
  return f && !out.contains("error") ? 0 : 1;
}

LammpsRunResult run_in_process(const LammpsRunSettings& s) {
  const fs::path result_file = s.work_dir / "liblammps-result.json";
  fs::remove(result_file);
  spdlog::default_logger()->flush();
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed: cannot start the LAMMPS run");
  if (pid == 0) {
    int code = 1;
    try {
      code = child_run(s, result_file);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "carbonmesh: LAMMPS child: %s\n", e.what());
    }
    spdlog::default_logger()->flush();
    std::fflush(nullptr);
    _exit(code);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw std::runtime_error("waitpid failed on the LAMMPS run");

  LammpsRunResult r;
  r.mode = "liblammps (in-process)";
  r.log = s.work_dir / "log.lammps";
  nlohmann::json j;
  if (std::ifstream f(result_file); f) j = nlohmann::json::parse(f, nullptr, false);
  fs::remove(result_file);
  const bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0 && j.is_object() && !j.contains("error");
  if (!ok) {
    std::string why = j.is_object() && j.contains("error") ? j["error"].get<std::string>() : lammps_error_line(r.log);
    if (WIFSIGNALED(status)) why = fmt::format("LAMMPS ended by signal {}; {}", WTERMSIG(status), why);
    throw InputError(fmt::format("LAMMPS run failed: {} (log: {})", why.empty() ? "no message" : why, r.log.string()));
  }
  r.seconds = j.value("seconds", 0.0);
  r.md_seconds = j.value("md_seconds", 0.0);
  r.pe_minimized = j.value("pe_minimized", r.pe_minimized);
  r.pe_final = j.value("pe_final", r.pe_final);
  r.temperature_final = j.value("temperature_final", r.temperature_final);
  r.steps = j.value("steps", 0L);
  const auto x = j["x"].get<std::vector<double>>();
  for (std::size_t i = 0; i + 2 < x.size(); i += 3) r.final_positions.emplace_back(x[i], x[i + 1], x[i + 2]);
  return r;
}

// ---- mpirun -np N lmp ---------------------------------------------------------------------------------------

LammpsRunResult run_mpirun(const LammpsRunSettings& s) {
  for (const auto& exe : {s.mpirun, s.lmp})
    if (!on_path(exe))
      throw InputError(fmt::format("{} not found on PATH (Debian packages lammps and openmpi-bin)", exe));
  const fs::path deck = s.work_dir / "in.simulate";
  {
    std::ofstream f(deck);
    for (const auto& c : s.commands) f << c << "\n";
    if (!f) throw InputError("cannot write " + deck.string());
  }
  LammpsRunResult r;
  r.np = s.np;
  r.log = s.work_dir / "log.lammps";
  const std::string root = geteuid() == 0 ? " --allow-run-as-root" : "";
  r.mode = fmt::format("{}{} --oversubscribe -np {} {} -in in.simulate", s.mpirun, root, s.np, s.lmp);
  const std::string command = fmt::format("cd {} && {}{} --oversubscribe -np {} {} -in in.simulate -log log.lammps 2>&1",
                                          shell_quote(s.work_dir.string()), shell_quote(s.mpirun), root, s.np,
                                          shell_quote(s.lmp));
  spdlog::debug("{}", command);
  const auto start = Clock::now();
  std::optional<Clock::time_point> md_start;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) throw InputError("cannot start " + s.mpirun);
  std::deque<std::string> tail;
  char buffer[4096];
  std::string line;
  while (std::fgets(buffer, sizeof buffer, pipe)) {
    line += buffer;
    if (line.empty() || line.back() != '\n') continue;
    line.pop_back();
    spdlog::trace("lmp: {}", line);
    if (starts_with(line, kMdMarker)) {
      std::istringstream in(line.substr(std::string(kMdMarker).size()));
      std::string key;
      in >> key;
      if (key == "minimized") {
        std::string pe;
        in >> pe >> r.pe_minimized;
        md_start = Clock::now();
        spdlog::info("minimised: pe {:.4f} eV/atom", s.atoms ? r.pe_minimized / s.atoms : 0.0);
      } else if (key == "step") {
        std::string t, p;
        double step = 0;
        in >> step >> t >> r.temperature_final >> p >> r.pe_final;
        r.steps = std::lround(step);
        log_progress(s, r.steps, r.temperature_final, r.pe_final);
        if (md_start) r.md_seconds = since(*md_start);
      }
    }
    tail.push_back(line);
    if (tail.size() > 20) tail.pop_front();
    line.clear();
  }
  const int status = pclose(pipe);
  r.seconds = since(start);
  if (status != 0) {
    std::string why = lammps_error_line(r.log);
    if (why.empty())
      for (auto it = tail.rbegin(); it != tail.rend(); ++it)
        if (!it->empty()) {
          why = *it;
          break;
        }
    throw InputError(fmt::format("LAMMPS run failed ({} exited with {}): {} (log: {})", s.mpirun,
                                 WIFEXITED(status) ? WEXITSTATUS(status) : -1, why, r.log.string()));
  }
  return r;
}

}  // namespace

std::string lammps_error_line(const fs::path& file) {
  std::ifstream f(file);
  std::string line, last;
  while (std::getline(f, line)) {
    if (starts_with(line, "ERROR")) return line;
    if (!line.empty()) last = line;
  }
  return last;
}

LammpsRunResult run_lammps(const LammpsRunSettings& s) {
  if (s.np < 1) throw InputError(fmt::format("--np {} must be at least 1", s.np));
  fs::create_directories(s.work_dir);
  return s.np == 1 ? run_in_process(s) : run_mpirun(s);
}

}  // namespace carbonmesh
