#include "carbonmesh/remesh/io.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include "carbonmesh/remesh/atomic_file.hpp"
#include "carbonmesh/remesh/error.hpp"
#include "binary_formats.hpp"
#include "orient_soup.hpp"
#include "t_junctions.hpp"
#include "triangulate_polygon.hpp"
#include "text_formats.hpp"

namespace carbonmesh {
namespace {

std::string lower_extension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

bool is_supported_input(const std::string& ext) {
  return ext == ".off" || ext == ".obj" || ext == ".ply" || ext == ".stl";
}

// FNV-1a over three 64-bit words.
std::uint64_t hash_words(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
  std::uint64_t h = 1469598103934665603ull;
  for (const std::uint64_t w : {a, b, c}) h = (h ^ w) * 1099511628211ull;
  return h;
}

struct PointHash {
  std::size_t operator()(const Vec3& p) const {
    std::array<std::uint64_t, 3> bits{};
    for (int i = 0; i < 3; ++i) {
      const double v = p[i] == 0.0 ? 0.0 : p[i];  // -0 == +0
      std::memcpy(&bits[static_cast<std::size_t>(i)], &v, sizeof(double));
    }
    return static_cast<std::size_t>(hash_words(bits[0], bits[1], bits[2]));
  }
};

// Vertices closer than `tolerance` to another but not at its position (those are the exact duplicates): a seam whose
// corners were computed twice and rounded apart (a tube's seam at angles 0 and 2 pi: sin(2 pi) is -2.4e-16, not 0),
// which would otherwise load as two borders lying on each other, a crack the remesh keeps open. Only the referenced
// representatives of the exact duplicates (remap[i] == i) are compared. The pairs within `tolerance` join groups,
// and every vertex of a group but its first (the lowest index) gets the first in `remap`: the same result in any
// order. The result counts them and names the pair within `tolerance` of the lowest larger index. The points are
// sorted by a hash of cells 64 tolerances wide (a collision only adds distances to compare): the box of half-width
// `tolerance` around a point lies in its own cell but where it is within `tolerance` of a cell's side.
struct NearDuplicates {
  std::size_t count = 0;
  std::array<int, 2> example{-1, -1};  // (lower, higher) index of one pair within the tolerance
  double example_distance = 0;
};

NearDuplicates near_duplicate_vertices(const std::vector<Vec3>& points, const std::vector<char>& referenced,
                                       double tolerance, std::vector<int>& remap) {
  NearDuplicates out;
  if (!(tolerance > 0)) return out;
  const double cell = 64.0 * tolerance;
  auto cell_of = [cell](double x) { return static_cast<std::int64_t>(std::floor(x / cell)); };
  auto hash = [](std::int64_t x, std::int64_t y, std::int64_t z) {
    return hash_words(static_cast<std::uint64_t>(x), static_cast<std::uint64_t>(y), static_cast<std::uint64_t>(z));
  };
  std::vector<std::pair<std::uint64_t, int>> cells;  // (hash of the cell, vertex), sorted
  for (std::size_t i = 0; i < points.size(); ++i)
    if (referenced[i] && remap[i] == static_cast<int>(i))
      cells.emplace_back(hash(cell_of(points[i][0]), cell_of(points[i][1]), cell_of(points[i][2])),
                         static_cast<int>(i));
  std::sort(cells.begin(), cells.end());
  std::vector<int> group(points.size());  // union-find; a group's root is its lowest index
  for (std::size_t i = 0; i < group.size(); ++i) group[i] = static_cast<int>(i);
  auto root = [&group](int i) {
    while (group[static_cast<std::size_t>(i)] != i)
      i = group[static_cast<std::size_t>(i)] = group[static_cast<std::size_t>(group[static_cast<std::size_t>(i)])];
    return i;
  };
  auto compare = [&](int i, int j) {
    if (i == j) return;
    const double d = (points[static_cast<std::size_t>(i)] - points[static_cast<std::size_t>(j)]).norm();
    if (d > tolerance) return;
    const auto [lower, higher] = std::minmax(i, j);
    auto& first = out.example;  // the pair with the lowest higher index
    if (first[1] < 0 || higher < first[1] || (higher == first[1] && lower < first[0])) {
      first = {lower, higher};
      out.example_distance = d;
    }
    const int ri = root(i), rj = root(j);
    if (ri != rj) group[static_cast<std::size_t>(std::max(ri, rj))] = std::min(ri, rj);
  };
  for (std::size_t a = 0; a < cells.size(); ++a) {
    const int i = cells[a].second;
    for (std::size_t b = a + 1; b < cells.size() && cells[b].first == cells[a].first; ++b) compare(i, cells[b].second);
    const Vec3& p = points[static_cast<std::size_t>(i)];
    std::array<std::int64_t, 3> lo{}, hi{}, own{};
    for (std::size_t c = 0; c < 3; ++c)
      lo[c] = cell_of(p[c] - tolerance), hi[c] = cell_of(p[c] + tolerance), own[c] = cell_of(p[c]);
    if (lo == own && hi == own) continue;  // the box inside its own cell
    for (auto x = lo[0]; x <= hi[0]; ++x)
      for (auto y = lo[1]; y <= hi[1]; ++y)
        for (auto z = lo[2]; z <= hi[2]; ++z) {
          if (std::array<std::int64_t, 3>{x, y, z} == own) continue;
          const std::uint64_t h = hash(x, y, z);
          for (auto it = std::lower_bound(cells.begin(), cells.end(), std::pair<std::uint64_t, int>{h, -1});
               it != cells.end() && it->first == h; ++it)
            compare(i, it->second);
        }
  }
  for (const auto& [h, i] : cells) {
    const int r = root(i);
    if (r == i) continue;
    remap[static_cast<std::size_t>(i)] = r;
    ++out.count;
  }
  return out;
}

}  // namespace

PolygonSoup read_polygon_soup(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw InputError(name + ": no such file");
  if (std::filesystem::is_directory(file, ec)) throw InputError(name + ": is a folder, not a mesh file");
  const std::string ext = lower_extension(file);
  if (!is_supported_input(ext))
    throw InputError(name + ": unsupported format '" + ext + "' (expected .off, .obj, .ply or .stl)");
  {
    std::ifstream probe(file, std::ios::binary);
    if (!probe) throw InputError(name + ": cannot be opened for reading");
    if (probe.peek() == std::ifstream::traits_type::eof()) throw InputError(name + ": empty file");
  }
  PolygonSoup soup;
  if (ext == ".off") {
    soup = detail::read_off(file);
  } else if (ext == ".obj") {
    soup = detail::read_obj(file);
  } else if (ext == ".ply") {
    soup = detail::read_ply(file);
  } else {
    soup = detail::read_stl(file);
  }
  if (soup.points.empty()) throw InputError(name + ": no vertices");
  if (soup.polygons.empty()) throw InputError(name + ": no faces");
  return soup;
}

TriMesh build_mesh(const PolygonSoup& soup, const std::string& source, const LoadSettings& settings,
                   LoadReport* report_out) {
  LoadReport report;
  report.input_vertices = soup.points.size();
  report.input_polygons = soup.polygons.size();
  const int n_points = static_cast<int>(soup.points.size());

  for (int i = 0; i < n_points; ++i) {
    const Vec3& p = soup.points[static_cast<std::size_t>(i)];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw InputError(source + ": vertex " + std::to_string(i) + " has a non-finite (NaN or Inf) coordinate");
  }
  if (soup.polygons.empty()) throw InputError(source + ": no faces");

  // Triangulate (the fan from the first corner, or ear clipping for a non-convex polygon), checking indices.
  std::vector<std::array<int, 3>> triangles;
  triangles.reserve(soup.polygons.size());
  for (std::size_t f = 0; f < soup.polygons.size(); ++f) {
    const auto& poly = soup.polygons[f];
    if (poly.size() < 3)
      throw InputError(source + ": face " + std::to_string(f) + " has " + std::to_string(poly.size()) +
                       " corners (at least 3 needed)");
    for (int v : poly)
      if (v < 0 || v >= n_points)
        throw InputError(source + ": face " + std::to_string(f) + " refers to vertex " + std::to_string(v) +
                         ", out of range (the file has " + std::to_string(n_points) + " vertices)");
    if (poly.size() == 3) {
      triangles.push_back({poly[0], poly[1], poly[2]});
      continue;
    }
    ++report.triangulated_polygons;
    report.nonconvex_polygons += triangulate_polygon(soup.points, poly, triangles) ? 1 : 0;
  }

  // Duplicate vertices: the same position as an earlier referenced vertex.
  std::vector<char> referenced(soup.points.size(), 0);
  for (const auto& t : triangles)
    for (int v : t) referenced[static_cast<std::size_t>(v)] = 1;
  std::vector<int> remap(soup.points.size());
  std::unordered_map<Vec3, int, PointHash> first_at;
  int dup_example_a = -1, dup_example_b = -1;
  for (int i = 0; i < n_points; ++i) {
    remap[static_cast<std::size_t>(i)] = i;
    if (!referenced[static_cast<std::size_t>(i)]) {
      ++report.unreferenced_vertices;
      continue;
    }
    Vec3 key = soup.points[static_cast<std::size_t>(i)];
    for (int c = 0; c < 3; ++c)
      if (key[c] == 0.0) key[c] = 0.0;
    auto [it, inserted] = first_at.emplace(key, i);
    if (!inserted) {
      ++report.duplicate_vertices;
      remap[static_cast<std::size_t>(i)] = it->second;
      if (dup_example_a < 0) dup_example_a = it->second, dup_example_b = i;
    }
  }
  if (report.duplicate_vertices > 0 && !settings.repair)
    throw InputError(source + ": " + std::to_string(report.duplicate_vertices) +
                     " duplicate vertices (e.g. vertices " + std::to_string(dup_example_a) + " and " +
                     std::to_string(dup_example_b) + " share a position); use --repair to merge them");
  // Nearly coincident vertices, and vertices inside border edges (T-junctions, below): within 4 float roundings of
  // the largest coordinate (a file's float coordinates computed twice differ by about that), far below any length the
  // remesh works at.
  double largest = 0;
  for (std::size_t i = 0; i < soup.points.size(); ++i)
    if (referenced[i])
      for (int c = 0; c < 3; ++c) largest = std::max(largest, std::abs(soup.points[i][c]));
  const double tolerance = 4.0 * std::numeric_limits<float>::epsilon() * largest;
  {
    const NearDuplicates near = near_duplicate_vertices(soup.points, referenced, tolerance, remap);
    report.near_duplicate_vertices = near.count;
    for (auto& r : remap) r = remap[static_cast<std::size_t>(r)];  // exact duplicates of a merged vertex follow it
    if (report.near_duplicate_vertices > 0 && !settings.repair)
      throw InputError(fmt::format("{}: {} {} closer than {:.3g} to another (e.g. vertices {} and {}, {:.3g} apart): "
                                   "an unwelded seam or crack; use --repair to merge them",
                                   source, report.near_duplicate_vertices,
                                   report.near_duplicate_vertices == 1 ? "vertex" : "vertices", tolerance,
                                   near.example[0], near.example[1], near.example_distance));
  }

  // Degenerate and duplicate faces.
  std::vector<std::array<int, 3>> kept;
  kept.reserve(triangles.size());
  std::map<std::array<int, 3>, std::size_t> seen;
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    std::array<int, 3> t = triangles[f];
    for (int& v : t) v = remap[static_cast<std::size_t>(v)];
    const Vec3& a = soup.points[static_cast<std::size_t>(t[0])];
    const Vec3& b = soup.points[static_cast<std::size_t>(t[1])];
    const Vec3& c = soup.points[static_cast<std::size_t>(t[2])];
    const double longest2 = std::max({(b - a).sqrnorm(), (c - b).sqrnorm(), (a - c).sqrnorm()});
    const double area2 = OpenMesh::cross(b - a, c - a).norm();
    const bool degenerate = t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || area2 <= 1e-12 * longest2;
    if (degenerate) {
      ++report.degenerate_faces;
      if (!settings.repair)
        throw InputError(source + ": triangle " + std::to_string(f) + " (vertices " + std::to_string(t[0]) +
                         ", " + std::to_string(t[1]) + ", " + std::to_string(t[2]) +
                         ") is degenerate (zero area); use --repair to remove degenerate faces");
      continue;
    }
    std::array<int, 3> key = t;
    std::sort(key.begin(), key.end());
    auto [it, inserted] = seen.emplace(key, f);
    if (!inserted) {
      ++report.duplicate_faces;
      if (!settings.repair)
        throw InputError(source + ": triangle " + std::to_string(f) + " duplicates triangle " +
                         std::to_string(it->second) + "; use --repair to remove duplicate faces");
      continue;
    }
    kept.push_back(t);
  }
  if (kept.empty()) throw InputError(source + ": no faces left (all are degenerate)");

  // Edge manifoldness and orientation, before OpenMesh sees the faces. Returns the border edges, (face, corner k) for
  // the edge from corner k to corner k + 1, in the order of their ends.
  auto check_edges = [&source](const std::vector<std::array<int, 3>>& faces) {
    std::map<std::pair<int, int>, std::array<int, 3>> edge_use;  // (min,max) -> {count, first dir, first face}
    for (std::size_t f = 0; f < faces.size(); ++f) {
      for (int k = 0; k < 3; ++k) {
        const int a = faces[f][static_cast<std::size_t>(k)], b = faces[f][static_cast<std::size_t>((k + 1) % 3)];
        const auto key = std::minmax(a, b);
        const int dir = a < b ? 1 : -1;
        auto [it, inserted] = edge_use.emplace(std::pair<int, int>(key.first, key.second),
                                               std::array<int, 3>{0, dir, static_cast<int>(f)});
        auto& use = it->second;
        ++use[0];
        if (use[0] > 2)
          throw InputError(source + ": non-manifold edge between vertices " + std::to_string(key.first) +
                           " and " + std::to_string(key.second) +
                           " (shared by more than two faces); use --repair to cut the surface open there");
        if (!inserted && use[1] == dir)
          throw InputError(source + ": inconsistent orientation between faces " + std::to_string(use[2]) +
                           " and " + std::to_string(f) + " at the edge between vertices " +
                           std::to_string(key.first) + " and " + std::to_string(key.second) +
                           "; use --repair to orient the faces alike");
      }
    }
    std::vector<std::pair<int, int>> border;
    for (const auto& [key, use] : edge_use) {
      if (use[0] != 1) continue;
      const auto& t = faces[static_cast<std::size_t>(use[2])];
      const int from = use[1] == 1 ? key.first : key.second;
      border.emplace_back(use[2], static_cast<int>(std::find(t.begin(), t.end(), from) - t.begin()));
    }
    return border;
  };
  // Vertex manifoldness, before OpenMesh sees the faces (its add_face prints "complex vertex" to stderr and
  // fails for a vertex where two closed fans meet). With manifold, consistently oriented edges the link of a
  // vertex (the edges opposite it) is a union of paths and cycles; a manifold vertex has exactly one.
  auto check_vertices = [&source](const std::vector<std::array<int, 3>>& faces, std::size_t n) {
    std::vector<std::vector<std::pair<int, int>>> link(n);
    for (const auto& t : faces)
      for (std::size_t k = 0; k < 3; ++k)
        link[static_cast<std::size_t>(t[k])].emplace_back(t[(k + 1) % 3], t[(k + 2) % 3]);
    std::vector<int> labels, parent;
    for (std::size_t v = 0; v < link.size(); ++v) {
      if (link[v].size() < 2) continue;
      labels.clear();
      for (const auto& [a, b] : link[v]) labels.push_back(a), labels.push_back(b);
      std::sort(labels.begin(), labels.end());
      labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
      parent.resize(labels.size());
      for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = static_cast<int>(i);
      auto find = [&parent](int i) {
        while (parent[static_cast<std::size_t>(i)] != i)
          i = parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
        return i;
      };
      auto index = [&labels](int label) {
        return static_cast<int>(std::lower_bound(labels.begin(), labels.end(), label) - labels.begin());
      };
      std::size_t fans = labels.size();
      for (const auto& [a, b] : link[v]) {
        const int ra = find(index(a)), rb = find(index(b));
        if (ra != rb) parent[static_cast<std::size_t>(ra)] = rb, --fans;
      }
      if (fans > 1)
        throw InputError(source + ": non-manifold (pinched) vertex " + std::to_string(v) + " (" +
                         std::to_string(fans) + " fans of faces meet there); use --repair to split it");
    }
  };

  // With --repair, faces that disagree in orientation and edges and vertices where the surface is not a disk: the faces
  // oriented alike and those vertices duplicated (orient_soup.hpp). Only where the checks find such a place: edges
  // before the T-junctions (whose search needs the border), vertices after them (a T-junction crack pinches the
  // vertices at its ends, which its repair mends).
  const std::vector<Vec3>* points = &soup.points;
  std::vector<Vec3> owned_points;  // the soup's points and those the repairs add
  auto own_points = [&] {
    if (points != &owned_points) owned_points = soup.points;
    points = &owned_points;
  };
  // `check()`'s result; with --repair, if it fails, the soup is oriented and it is checked again.
  auto repaired_where = [&](const auto& check) {
    if (settings.repair) {
      try {
        return check();
      } catch (const InputError&) {
        own_points();
        const OrientedSoup oriented = orient_soup(owned_points, kept);
        report.reversed_faces += oriented.reversed_faces;
        report.split_vertices += oriented.duplicated_vertices;
      }
    }
    return check();
  };
  const std::vector<std::pair<int, int>> border = repaired_where([&] { return check_edges(kept); });

  // T-junctions: border vertices inside other border edges (t_junctions.hpp), a crack that welding cannot close;
  // --repair splits the faces there, so the two sides share their vertices.
  {
    const TJunctions junctions = find_t_junctions(*points, kept, border, tolerance);
    report.t_junctions = junctions.vertices;
    if (junctions.vertices > 0 && !settings.repair)
      throw InputError(fmt::format("{}: {} border {} inside another border edge (e.g. vertex {}, {:.3g} from the edge "
                                   "between vertices {} and {}): a T-junction crack, two sides of a seam that do not "
                                   "share their vertices; use --repair to split the edges there",
                                   source, junctions.vertices, junctions.vertices == 1 ? "vertex lies" : "vertices lie",
                                   junctions.example[0], junctions.example_distance, junctions.example[1],
                                   junctions.example[2]));
    if (junctions.vertices > 0) {
      own_points();
      kept = split_at_t_junctions(owned_points, kept, junctions);
      check_edges(kept);
    }
  }
  repaired_where([&] {
    check_vertices(kept, points->size());
    return 0;
  });

  // Build the half-edge mesh; vertices no kept face uses are dropped.
  std::vector<char> used(points->size(), 0);
  for (const auto& t : kept)
    for (int v : t) used[static_cast<std::size_t>(v)] = 1;
  TriMesh mesh;
  std::vector<TriMesh::VertexHandle> handle(points->size());
  std::vector<int> original_index;
  for (std::size_t i = 0; i < points->size(); ++i) {
    if (!used[i]) continue;
    handle[i] = mesh.add_vertex((*points)[i]);
    original_index.push_back(static_cast<int>(i));
  }
  for (const auto& t : kept) {
    const auto fh = mesh.add_face(handle[static_cast<std::size_t>(t[0])], handle[static_cast<std::size_t>(t[1])],
                                  handle[static_cast<std::size_t>(t[2])]);
    if (!fh.is_valid())
      throw InputError(source + ": non-manifold vertex at one of vertices " + std::to_string(t[0]) + ", " +
                       std::to_string(t[1]) + ", " + std::to_string(t[2]) +
                       " (its faces do not form a single fan)");
  }
  for (auto vh : mesh.vertices()) {
    if (!mesh.is_manifold(vh))
      throw InputError(source + ": non-manifold (pinched) vertex " +
                       std::to_string(original_index[static_cast<std::size_t>(vh.idx())]) +
                       " (two or more fans meet there)");
  }
  mesh.update_normals();

  report.repaired = settings.repair && (report.duplicate_vertices + report.near_duplicate_vertices +
                                        report.reversed_faces + report.split_vertices + report.t_junctions +
                                        report.degenerate_faces + report.duplicate_faces) > 0;
  if (report.triangulated_polygons > 0)
    spdlog::info("{}: triangulated {} polygons with more than three corners{}", source, report.triangulated_polygons,
                 report.nonconvex_polygons > 0
                     ? fmt::format(" ({} non-convex, by ear clipping)", report.nonconvex_polygons)
                     : std::string());
  if (report.unreferenced_vertices > 0)
    spdlog::warn("{}: removed {} vertices used by no face", source, report.unreferenced_vertices);
  if (report.repaired) {
    std::vector<std::string> done{fmt::format("merged {} duplicate and {} nearly coincident vertices",
                                              report.duplicate_vertices, report.near_duplicate_vertices)};
    if (report.reversed_faces > 0)
      done.push_back(fmt::format("reversed {} face{} to orient the faces alike", report.reversed_faces,
                                 report.reversed_faces == 1 ? "" : "s"));
    if (report.split_vertices > 0)
      done.push_back(fmt::format("split {} {} where the surface was not a disk (non-manifold)", report.split_vertices,
                                 report.split_vertices == 1 ? "vertex" : "vertices"));
    if (report.t_junctions > 0)
      done.push_back(fmt::format("split the faces at {} T-junction vertices", report.t_junctions));
    done.push_back(fmt::format("removed {} degenerate and {} duplicate faces", report.degenerate_faces,
                               report.duplicate_faces));
    spdlog::warn("{}: repaired: {}", source, fmt::join(done, ", "));
  }
  if (report_out) *report_out = report;
  return mesh;
}

TriMesh load_mesh(const std::filesystem::path& file, const LoadSettings& settings, LoadReport* report) {
  const PolygonSoup soup = read_polygon_soup(file);
  TriMesh mesh = build_mesh(soup, file.string(), settings, report);
  spdlog::debug("{}: loaded {} vertices, {} faces", file.string(), mesh.n_vertices(), mesh.n_faces());
  return mesh;
}

void save_mesh(const TriMesh& mesh, const std::filesystem::path& file) {
  const std::string ext = lower_extension(file);
  if (!(ext == ".off" || ext == ".obj" || ext == ".ply" || ext == ".stl"))
    throw InputError(file.string() + ": unsupported output format '" + ext +
                     "' (expected .off, .obj, .ply or .stl)");
  if (file.has_parent_path() && !std::filesystem::is_directory(file.parent_path()))
    throw InputError(file.string() + ": folder " + file.parent_path().string() + " does not exist");
  write_atomically(file, [&](const std::filesystem::path& tmp) {
    bool ok = false;
    if (ext == ".off") {
      ok = detail::write_off(mesh, tmp);
    } else if (ext == ".obj") {
      ok = detail::write_obj(mesh, tmp);
    } else if (ext == ".ply") {
      ok = detail::write_ply(mesh, tmp);
    } else {  // STL stores single precision by definition; OpenMesh's writer
      OpenMesh::IO::Options options;
      ok = OpenMesh::IO::write_mesh(mesh, tmp.string(), options, 9);
    }
    if (!ok) throw InputError(file.string() + ": could not be written");
  });
}

}  // namespace carbonmesh
