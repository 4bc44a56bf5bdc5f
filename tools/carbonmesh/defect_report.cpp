#include "defect_report.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <stdexcept>

#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/simulations/report_files.hpp"

namespace carbonmesh::cli {
namespace fs = std::filesystem;
namespace {

// tools/analysis_report.py: installed next to the binary (../share/carbonmesh), else the source tree.
fs::path find_report_script(const std::string& given) {
  if (!given.empty()) return given;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path().parent_path() / "share" / "carbonmesh" / "analysis_report.py";
    if (fs::exists(installed, ec)) return installed;
  }
  return CARBONMESH_REPORT_SCRIPT;
}

}  // namespace

Analysis write_defect_report(const fs::path& input, const fs::path& out, const DefectReportOptions& options) {
  const Analysis a = analyze(input, options.settings);
  const auto files = write_report_files(out, a);
  spdlog::info("wrote {} files to {}", files.size(), out.string());
  if (options.plots) {
    const fs::path script = find_report_script(options.script);
    if (!fs::exists(script))
      throw InputError(fmt::format("report script {} not found (--report-script, or --no-plots)", script.string()));
    if (access(options.python.c_str(), X_OK) != 0)
      throw InputError(fmt::format("{} is not executable (--python, or --no-plots)", options.python));
    const int rc = run_report_script(options.python, script, out);
    if (rc != 0)
      throw std::runtime_error(
          fmt::format("{} {} {} failed (exit {})", options.python, script.string(), out.string(), rc));
    spdlog::info("plots and {}", (out / "report.html").string());
  }
  return a;
}

}  // namespace carbonmesh::cli
