// carbonmesh: from a triangle surface to a LAMMPS-ready sp2 carbon structure.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <iostream>
#if defined(__GLIBC__)
#include <malloc.h>
#include <unistd.h>
#endif

#include "carbonmesh/remesh/atomic_file.hpp"
#include "carbonmesh/remesh/error.hpp"
#include "commands.hpp"

namespace {

#if defined(__GLIBC__) && defined(__linux__) && !defined(__SANITIZE_ADDRESS__)
// Transparent huge pages for the heap: with the tunable glibc.malloc.hugetlb=1 glibc asks the kernel to back its
// heap with 2 MB pages (kernels with THP in "madvise" mode, the Debian default, give them only when asked). Fewer
// page faults and TLB misses on the large vectors of the dual optimisation: the built-in sphere at 10^6 atoms
// 45.8 -> 41.5 s, fertility at 250000 atoms 12.8 -> 12.4 s, the same output. glibc reads its tunables only at
// start-up, so the program starts itself once more with the tunable set. Not when GLIBC_TUNABLES is set already
// (set it empty to run without) or under valgrind (which would then lose the restarted process).
void restart_with_huge_pages(char** argv) {
  if (std::getenv("GLIBC_TUNABLES") != nullptr) return;
  if (const char* preload = std::getenv("LD_PRELOAD"); preload != nullptr && std::strstr(preload, "vgpreload"))
    return;
  setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=1", 1);
  execv("/proc/self/exe", argv);
  unsetenv("GLIBC_TUNABLES");  // the restart failed (no /proc): go on without
}
#else
void restart_with_huge_pages(char**) {}
#endif

}  // namespace

int main(int argc, char** argv) {
  restart_with_huge_pages(argv);
#if defined(__GLIBC__)
  // Large structures allocate and free meshes and vectors of tens of MB over and over (mesh copies, L-BFGS
  // vectors). glibc's defaults give blocks above its adaptive threshold back to the kernel at once, so each new one
  // is faulted in again page by page (10^6 atoms: 610000 page faults). Blocks up to 32 MB (the largest mallopt
  // allows) now come from the heap and the heap is not trimmed: 410000 faults, peak RSS 1.51 -> 1.65 GB.
  mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024);
  mallopt(M_TRIM_THRESHOLD, INT_MAX);
#endif
  carbonmesh::remove_partial_files_on_interrupt();
  auto logger = spdlog::stderr_color_mt("carbonmesh");
  spdlog::set_default_logger(logger);
  spdlog::set_pattern("[%H:%M:%S.%e] [%^%l%$] %v");

  CLI::App app{"carbonmesh: turns a triangle surface into an sp2 carbon nanostructure for LAMMPS"};
  app.set_version_flag("--version", std::string("carbonmesh ") + CARBONMESH_VERSION);
  app.require_subcommand(1);
  int verbosity = 0;
  bool quiet = false;
  app.add_flag("-v,--verbose", verbosity, "more log output (-vv for debug)");
  app.add_flag("-q,--quiet", quiet, "only warnings and errors");

  carbonmesh::cli::Action action;
  carbonmesh::cli::add_stats_command(app, action);
  carbonmesh::cli::add_shape_command(app, action);
  carbonmesh::cli::add_analyze_command(app, action);
  carbonmesh::cli::add_build_command(app, action);
  carbonmesh::cli::add_remesh_command(app, action);
  carbonmesh::cli::add_simulate_command(app, action);
  carbonmesh::cli::add_help_command(app, action);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "carbonmesh: error: " << e.what() << " (see carbonmesh --help or carbonmesh COMMAND --help)\n";
    return carbonmesh::kExitBadInput;
  }
  spdlog::set_level(quiet ? spdlog::level::warn
                          : verbosity >= 2 ? spdlog::level::trace
                          : verbosity == 1 ? spdlog::level::debug
                                           : spdlog::level::info);
  try {
    return action ? action() : 0;
  } catch (const carbonmesh::InputError& e) {
    std::cerr << "carbonmesh: error: " << e.what() << "\n";
    return carbonmesh::kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "carbonmesh: internal error: " << e.what() << "\n";
    return 1;
  }
}
