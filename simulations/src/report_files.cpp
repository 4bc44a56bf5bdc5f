#include "carbonmesh/simulations/report_files.hpp"

#include <fmt/format.h>
#include <fmt/os.h>
#include <spdlog/spdlog.h>
#include <spawn.h>
#include <sys/wait.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "carbonmesh/remesh/atomic_file.hpp"
#include "carbonmesh/remesh/error.hpp"

extern char** environ;

namespace carbonmesh {
namespace fs = std::filesystem;
namespace {

void write_text(const fs::path& target, const std::function<void(std::ofstream&)>& body) {
  write_atomically(target, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw InputError(target.string() + ": cannot be written");
    body(out);
    out.flush();
    if (!out) throw InputError(target.string() + ": write failed");
  });
}

}  // namespace

std::array<unsigned char, 3> defect_ring_colour(int size) {
  switch (size) {
    case 3: return {255, 215, 0};    // gold
    case 4: return {255, 127, 14};   // orange
    case 5: return {214, 39, 40};    // red
    case 6: return {200, 200, 200};  // light grey
    case 7: return {31, 119, 180};   // blue
    case 8: return {44, 160, 44};    // green
    default: return {148, 103, 189};  // purple
  }
}

std::vector<std::string> write_report_files(const fs::path& dir, const Analysis& a, const ReportFilesSettings& settings) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) throw InputError(dir.string() + ": cannot create the output folder");
  std::vector<std::string> written;
  const RingStructure& rs = a.structure;

  write_text(dir / "report.json", [&](std::ofstream& out) { out << to_json(a).dump(2) << "\n"; });
  written.push_back("report.json");

  write_text(dir / "ring_sizes.csv", [&](std::ofstream& out) {
    out << "size,closed,open\n";
    std::map<int, std::pair<std::size_t, std::size_t>> m;
    for (const auto& [k, v] : a.sizes.closed) m[k].first = v;
    for (const auto& [k, v] : a.sizes.open) m[k].second = v;
    for (const auto& [k, v] : m) out << k << "," << v.first << "," << v.second << "\n";
  });
  written.push_back("ring_sizes.csv");

  write_text(dir / "rings.csv", [&](std::ofstream& out) {
    std::vector<std::string> nearest(rs.size());
    for (const auto* d : {&a.pentagons, &a.heptagons})
      for (std::size_t k = 0; k < d->rings.size(); ++k)
        if (d->distance[k]) nearest[d->rings[k]] = std::to_string(*d->distance[k]);
    out << "ring,size,open,cx,cy,cz,nearest_same_size\n";
    for (std::size_t r = 0; r < rs.size(); ++r)
      out << fmt::format("{},{},{},{:.6g},{:.6g},{:.6g},{}\n", r, rs.sizes[r], rs.open[r] ? 1 : 0, rs.centers[r][0],
                         rs.centers[r][1], rs.centers[r][2], nearest[r]);
  });
  written.push_back("rings.csv");

  write_text(dir / "defect_distances.csv", [&](std::ofstream& out) {
    out << "kind,ring,distance\n";
    for (const auto* d : {&a.pentagons, &a.heptagons})
      for (std::size_t k = 0; k < d->rings.size(); ++k)
        out << (d->size == 5 ? "pentagon" : "heptagon") << "," << d->rings[k] << ","
            << (d->distance[k] ? std::to_string(*d->distance[k]) : std::string()) << "\n";
  });
  written.push_back("defect_distances.csv");

  write_text(dir / "distance_histogram.csv", [&](std::ofstream& out) {
    out << "kind,distance,count\n";
    for (const auto* d : {&a.pentagons, &a.heptagons})
      for (const auto& [k, v] : d->histogram) out << (d->size == 5 ? "pentagon" : "heptagon") << "," << k << "," << v << "\n";
  });
  written.push_back("distance_histogram.csv");

  write_text(dir / "pentagon_heptagon_pairs.csv", [&](std::ofstream& out) {
    out << "pentagon_ring,heptagon_ring\n";
    for (const auto& [p, h] : a.pairs.matching) out << p << "," << h << "\n";
  });
  written.push_back("pentagon_heptagon_pairs.csv");

  if (a.plane) {
    write_text(dir / "sides.csv", [&](std::ofstream& out) {
      out << "size,positive,negative,on_plane\n";
      std::map<int, std::array<std::size_t, 3>> m;
      for (const auto& [k, v] : a.plane->sides.positive) m[k][0] = v;
      for (const auto& [k, v] : a.plane->sides.negative) m[k][1] = v;
      for (const auto& [k, v] : a.plane->sides.on_plane) m[k][2] = v;
      for (const auto& [k, v] : m) out << k << "," << v[0] << "," << v[1] << "," << v[2] << "\n";
    });
    written.push_back("sides.csv");
  }

  // defects.ply: atoms as vertices, closed rings as faces coloured by size.
  write_text(dir / "defects.ply", [&](std::ofstream& out) {
    std::size_t faces = 0;
    for (std::size_t r = 0; r < rs.size(); ++r) faces += !rs.open[r];
    out << "ply\nformat ascii 1.0\ncomment carbonmesh analyze: rings coloured by size (5 red, 6 grey, 7 blue)\n"
        << "element vertex " << rs.atoms.positions.size() << "\nproperty float x\nproperty float y\nproperty float z\n"
        << "element face " << faces << "\nproperty list uchar int vertex_indices\n"
        << "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty int ring_size\nend_header\n";
    for (const auto& p : rs.atoms.positions) out << fmt::format("{:.6g} {:.6g} {:.6g}\n", p[0], p[1], p[2]);
    for (std::size_t r = 0; r < rs.size(); ++r) {
      if (rs.open[r]) continue;
      out << rs.rings[r].size();
      for (int v : rs.rings[r]) out << ' ' << v;
      const auto c = defect_ring_colour(rs.sizes[r]);
      out << ' ' << int(c[0]) << ' ' << int(c[1]) << ' ' << int(c[2]) << ' ' << rs.sizes[r] << '\n';
    }
  });
  written.push_back("defects.ply");

  // view.json for the interactive 3D view.
  write_text(dir / "view.json", [&](std::ofstream& out) {
    const std::size_t n = rs.atoms.positions.size();
    const bool full = n <= settings.max_view_atoms;
    std::vector<int> keep(n, full ? 0 : -1);
    std::vector<int> kept;
    if (full) {
      kept.resize(n);
      for (std::size_t i = 0; i < n; ++i) kept[i] = keep[i] = static_cast<int>(i);
    } else {
      for (std::size_t r = 0; r < rs.size(); ++r)
        if (!rs.open[r] && rs.sizes[r] != 6)
          for (int v : rs.rings[r])
            if (keep[v] < 0) {
              keep[v] = static_cast<int>(kept.size());
              kept.push_back(v);
            }
    }
    out << "{\"complete\":" << (full ? "true" : "false") << ",\"atoms\":[";
    for (std::size_t k = 0; k < kept.size(); ++k) {
      const auto& p = rs.atoms.positions.empty() ? Vec3(0, 0, 0) : rs.atoms.positions[kept[k]];
      out << (k ? "," : "") << fmt::format("{:.3f},{:.3f},{:.3f}", p[0], p[1], p[2]);
    }
    out << "],\"bonds\":[";
    bool first = true;
    for (const auto& b : rs.atoms.bonds) {
      if (keep[b[0]] < 0 || keep[b[1]] < 0) continue;
      out << (first ? "" : ",") << keep[b[0]] << "," << keep[b[1]];
      first = false;
    }
    out << "],\"defects\":[";
    first = true;
    for (std::size_t r = 0; r < rs.size(); ++r) {
      if (rs.open[r] || rs.sizes[r] == 6) continue;
      out << (first ? "" : ",") << "{\"size\":" << rs.sizes[r] << ",\"atoms\":[";
      for (std::size_t k = 0; k < rs.rings[r].size(); ++k) out << (k ? "," : "") << keep[rs.rings[r][k]];
      out << "]}";
      first = false;
    }
    out << "],\"rings\":[";  // the other closed rings, drawn as an opaque light surface
    first = true;
    if (full)
      for (std::size_t r = 0; r < rs.size(); ++r) {
        if (rs.open[r] || rs.sizes[r] != 6) continue;
        out << (first ? "[" : ",[");
        for (std::size_t k = 0; k < rs.rings[r].size(); ++k) out << (k ? "," : "") << rs.rings[r][k];
        out << "]";
        first = false;
      }
    out << "]";
    if (a.plane)
      out << fmt::format(",\"plane\":{{\"normal\":[{},{},{}],\"offset\":{}}}", a.plane->plane.normal[0],
                         a.plane->plane.normal[1], a.plane->plane.normal[2], a.plane->plane.offset);
    out << "}\n";
  });
  written.push_back("view.json");
  return written;
}

int run_report_script(const fs::path& python, const fs::path& script, const fs::path& dir) {
  const std::string py = python.string(), sc = script.string(), d = dir.string();
  std::vector<char*> argv{const_cast<char*>(py.c_str()), const_cast<char*>(sc.c_str()), const_cast<char*>(d.c_str()),
                          nullptr};
  pid_t pid = 0;
  if (posix_spawn(&pid, py.c_str(), nullptr, nullptr, argv.data(), environ) != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace carbonmesh
