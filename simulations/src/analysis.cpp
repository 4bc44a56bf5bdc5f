#include "carbonmesh/simulations/analysis.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <nlohmann/json.hpp>

#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/io.hpp"
#include "carbonmesh/simulations/lammps_atoms.hpp"

namespace carbonmesh {
namespace fs = std::filesystem;
namespace {

std::string lower_ext(const fs::path& p) {
  std::string e = p.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e;
}
bool is_mesh_ext(const std::string& e) { return e == ".off" || e == ".obj" || e == ".ply" || e == ".stl"; }

class Timer {
 public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return s;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

nlohmann::json counts_json(const std::map<int, std::size_t>& m) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [k, v] : m) j[std::to_string(k)] = v;
  return j;
}

nlohmann::json plane_json(const Plane& p) {
  return {{"normal", {p.normal[0], p.normal[1], p.normal[2]}}, {"offset", p.offset}};
}

nlohmann::json distances_json(const NearestDistances& d) {
  nlohmann::json per = nlohmann::json::array();
  for (std::size_t k = 0; k < d.rings.size(); ++k)
    per.push_back({{"ring", d.rings[k]}, {"distance", d.distance[k] ? nlohmann::json(*d.distance[k]) : nlohmann::json()}});
  std::optional<int> lo, hi;
  double sum = 0;
  std::size_t n = 0;
  for (const auto& x : d.distance)
    if (x) {
      lo = lo ? std::min(*lo, *x) : *x;
      hi = hi ? std::max(*hi, *x) : *x;
      sum += *x;
      ++n;
    }
  return {{"ring_size", d.size},
          {"count", d.rings.size()},
          {"histogram", counts_json(d.histogram)},
          {"unreachable", d.unreachable},
          {"min", lo ? nlohmann::json(*lo) : nlohmann::json()},
          {"max", hi ? nlohmann::json(*hi) : nlohmann::json()},
          {"mean", n ? nlohmann::json(sum / static_cast<double>(n)) : nlohmann::json()},
          {"per_ring", per}};
}

}  // namespace

ResolvedInput resolve_input(const fs::path& input) {
  std::error_code ec;
  if (!fs::exists(input, ec)) throw InputError(input.string() + ": no such file or folder");
  ResolvedInput r;
  if (fs::is_directory(input, ec)) {
    r.from_folder = true;
    std::vector<fs::path> data, dual;
    for (const auto& entry : fs::directory_iterator(input, ec)) {
      if (!entry.is_regular_file()) continue;
      const auto name = entry.path().filename().string();
      if (name.find(".partial-") != std::string::npos) continue;
      if (lower_ext(entry.path()) == ".data") data.push_back(entry.path());
      if (lower_ext(entry.path()) == ".ply" && (name == "rings.ply" || name.find("dual") != std::string::npos))
        dual.push_back(entry.path());
    }
    std::sort(data.begin(), data.end());
    // `carbonmesh build` writes rings.ply (the dual: one polygon per ring) next to structure.data.
    std::sort(dual.begin(), dual.end(), [](const fs::path& a, const fs::path& b) {
      const bool ra = a.filename() == "rings.ply", rb = b.filename() == "rings.ply";
      return ra != rb ? ra : a < b;
    });
    if (!dual.empty()) {
      r.kind = "polygon mesh";
      r.file = dual.front();
      return r;
    }
    if (data.empty())
      throw InputError(input.string() + ": folder has no rings.ply or *dual*.ply and no LAMMPS data file (*.data)");
    auto structure = std::find_if(data.begin(), data.end(), [](const fs::path& p) { return p.filename() == "structure.data"; });
    if (structure == data.end() && data.size() > 1)
      throw InputError(fmt::format("{}: folder has {} data files and none is structure.data; name one", input.string(),
                                   data.size()));
    r.kind = "lammps data";
    r.file = structure != data.end() ? *structure : data.front();
    return r;
  }
  r.file = input;
  r.kind = is_mesh_ext(lower_ext(input)) ? "mesh" : "lammps data";
  return r;
}

RingStructure load_ring_structure(const ResolvedInput& in, const AnalysisSettings& settings,
                                  std::optional<SpRingResult>* sp) {
  if (in.kind == "lammps data") {
    if (!(settings.cutoff > 0 && settings.cutoff < 1e6)) throw InputError(fmt::format("--cutoff {} must be positive", settings.cutoff));
    Timer t;
    LammpsAtoms data = read_lammps_atoms(in.file);
    spdlog::info("{}: {} atoms (style {})", in.file.string(), data.positions.size(), data.atom_style);
    // Hydrogen (passivated borders; mass below 1.5) takes no part in rings: drop it.
    std::size_t hydrogen = 0;
    if (!settings.data_bonds) {
      std::vector<Vec3> carbon;
      carbon.reserve(data.positions.size());
      for (std::size_t i = 0; i < data.positions.size(); ++i) {
        const double mass = data.masses[data.types[i] - 1];
        if (mass > 0 && mass < 1.5)
          ++hydrogen;
        else
          carbon.push_back(data.positions[i]);
      }
      if (hydrogen) {
        spdlog::info("{} hydrogen atoms (mass < 1.5) left out of the ring analysis", hydrogen);
        data.positions = std::move(carbon);
      }
    }
    std::vector<Bond> bonds;
    if (settings.data_bonds) {
      if (data.bonds.empty()) throw InputError(in.file.string() + ": --data-bonds given but the file has no Bonds");
      bonds = std::move(data.bonds);
    } else {
      bonds = bonds_by_cutoff(data.positions, settings.cutoff);
    }
    const std::size_t n = data.positions.size();
    AtomGraph graph = make_atom_graph(n, std::move(bonds), std::move(data.positions));
    spdlog::info("{} bonds ({}), {:.2f} s", graph.bonds.size(),
                 settings.data_bonds ? "from the Bonds section" : fmt::format("cutoff {} A", settings.cutoff), t.lap());
    std::size_t overbonded = 0;
    for (std::size_t i = 0; i < n; ++i) overbonded += graph.degree(static_cast<int>(i)) > 4;
    if (overbonded > n / 10)
      spdlog::warn("{} of {} atoms have more than 4 bonds: is the cutoff ({} A) too large or the unit not Angstrom?",
                   overbonded, n, settings.cutoff);
    SpRingResult rings = find_sp_rings(graph, settings.rings);
    spdlog::info("{} SP rings (max size {}) from {} candidates, {:.2f} s", rings.rings.size(), settings.rings.max_size,
                 rings.candidates, t.lap());
    if (rings.truncated_atoms)
      spdlog::warn("{} atoms had more than {} ring candidates (over-bonded? check --cutoff): some rings may be missing",
                   rings.truncated_atoms, settings.rings.max_candidates_per_atom);
    if (rings.truncated_ends)
      spdlog::warn("{} ring ends had more than {} shortest paths: some rings may be missing", rings.truncated_ends,
                   settings.rings.max_paths_per_end);
    RingStructure rs = rings_from_graph(std::move(graph), std::move(rings.rings));
    if (sp) {
      rings.rings.clear();
      *sp = std::move(rings);
    }
    return rs;
  }
  const PolygonSoup soup = read_polygon_soup(in.file);
  const bool triangles = std::all_of(soup.polygons.begin(), soup.polygons.end(), [](const auto& p) { return p.size() == 3; });
  if (in.kind == "polygon mesh" || !triangles) {
    RingStructure rs = rings_from_polygons(soup, in.file.string());
    return rs;
  }
  return rings_from_mesh(build_mesh(soup, in.file.string()));
}

Analysis analyze(const fs::path& input, const AnalysisSettings& settings) {
  Analysis a;
  Timer t;
  a.input = input.string();
  a.resolved = resolve_input(input);
  a.structure = load_ring_structure(a.resolved, settings, &a.sp);
  if (a.resolved.kind == "mesh") a.resolved.kind = a.structure.source;
  a.seconds["rings"] = t.lap();
  for (std::size_t i = 0; i < a.structure.atoms.atoms(); ++i) ++a.coordination[a.structure.atoms.degree(static_cast<int>(i))];
  a.sizes = ring_size_counts(a.structure);
  a.pentagons = nearest_same_size(a.structure, 5);
  a.heptagons = nearest_same_size(a.structure, 7);
  a.pairs = pentagon_heptagon_pairs(a.structure);
  a.floor = topological_floor(a.structure);
  a.seconds["defects"] = t.lap();
  if (!settings.plane.empty()) {
    PlaneAnalysis p;
    p.requested = settings.plane;
    // The shape: the input mesh itself for a triangle mesh (its vertices are the ring centres), otherwise the
    // rings fanned into triangles.
    TriMesh shape;
    if (a.structure.source == "triangle mesh") {
      const PolygonSoup soup = read_polygon_soup(a.resolved.file);
      shape = build_mesh(soup, a.resolved.file.string());
    } else {
      shape = surface_of(a.structure);
    }
    if (shape.n_faces() == 0) throw InputError(a.input + ": no closed rings to build a surface for --plane");
    if (settings.plane == "auto") {
      p.search = find_mirror_plane(shape, settings.mirror);
      p.plane = p.search->plane;
      p.residual = p.search->residual;
      p.diagonal = p.search->diagonal;
    } else {
      Vec3 center(0, 0, 0);
      std::size_t n = 0;
      for (auto v : shape.vertices()) {
        center += shape.point(v);
        ++n;
      }
      center /= static_cast<double>(std::max<std::size_t>(n, 1));
      p.plane = parse_plane(settings.plane, center);
      p.residual = mirror_residual(shape, p.plane, settings.mirror.final_samples);
      Vec3 lo = shape.point(*shape.vertices_begin()), hi = lo;
      for (auto v : shape.vertices()) {
        lo.minimize(shape.point(v));
        hi.maximize(shape.point(v));
      }
      p.diagonal = (hi - lo).norm();
    }
    p.sides = count_sides(a.structure, p.plane, 1e-9 * std::max(p.diagonal, 1.0));
    a.plane = std::move(p);
    a.seconds["plane"] = t.lap();
  }
  return a;
}

nlohmann::json to_json(const Analysis& a) {
  nlohmann::json j;
  j["input"] = a.input;
  j["resolved"] = {{"kind", a.resolved.kind}, {"file", a.resolved.file.string()}, {"from_folder", a.resolved.from_folder}};
  j["rings_from"] = a.structure.source;
  j["atoms"] = a.structure.atoms.atoms();
  j["bonds"] = a.structure.atoms.bonds.size();
  j["coordination"] = counts_json(a.coordination);
  if (a.sp)
    j["sp_rings"] = {{"candidates", a.sp->candidates}, {"truncated_ends", a.sp->truncated_ends},
                     {"truncated_atoms", a.sp->truncated_atoms}};
  std::size_t closed = 0, open = 0;
  for (const auto& [k, v] : a.sizes.closed) closed += v;
  for (const auto& [k, v] : a.sizes.open) open += v;
  j["rings"] = {{"closed", closed}, {"open", open}, {"by_size", counts_json(a.sizes.closed)},
                {"open_by_size", counts_json(a.sizes.open)}};
  j["pentagon_distances"] = distances_json(a.pentagons);
  j["heptagon_distances"] = distances_json(a.heptagons);
  nlohmann::json matching = nlohmann::json::array();
  for (const auto& [p, h] : a.pairs.matching) matching.push_back({p, h});
  j["pentagon_heptagon"] = {{"pentagons", a.pairs.pentagons}, {"heptagons", a.pairs.heptagons},
                            {"adjacent_pairs", a.pairs.adjacent_pairs}, {"matched_pairs", a.pairs.matched_pairs},
                            {"matching", matching}};
  auto opt = [](const std::optional<long>& x) { return x ? nlohmann::json(*x) : nlohmann::json(); };
  j["topology"] = {{"euler", opt(a.floor.euler)}, {"closed", a.floor.closed},
                   {"sum_six_minus_size", a.floor.sum_six_minus_size}, {"six_chi", opt(a.floor.six_chi)},
                   {"floor_non_hexagons", opt(a.floor.floor)}, {"observed_non_hexagons", a.floor.non_hexagons}};
  if (a.plane) {
    const auto& p = *a.plane;
    nlohmann::json pj;
    pj["requested"] = p.requested;
    pj["plane"] = plane_json(p.plane);
    pj["residual"] = to_json(p.residual);
    pj["bbox_diagonal"] = p.diagonal;
    pj["relative_residual"] = p.diagonal > 0 ? p.residual.max / p.diagonal : 0.0;
    if (p.search) {
      nlohmann::json cands = nlohmann::json::array();
      for (const auto& c : p.search->candidates)
        cands.push_back({{"start", plane_json(c.start)}, {"refined", plane_json(c.refined)},
                         {"start_distance", c.start_distance}, {"refined_distance", c.refined_distance},
                         {"evaluations", c.evaluations}});
      pj["candidates"] = cands;
    }
    pj["sides"] = {{"positive", counts_json(p.sides.positive)}, {"negative", counts_json(p.sides.negative)},
                   {"on_plane", counts_json(p.sides.on_plane)}, {"positive_total", p.sides.positive_total},
                   {"negative_total", p.sides.negative_total}, {"on_plane_total", p.sides.on_plane_total}};
    j["symmetry"] = pj;
  }
  j["seconds"] = a.seconds;
  return j;
}

std::string to_text(const Analysis& a) {
  std::string s;
  s += fmt::format("{} ({}: {})\n", a.input, a.resolved.kind, a.resolved.file.string());
  s += fmt::format("atoms {}  bonds {}  rings {} ({})\n", a.structure.atoms.atoms(), a.structure.atoms.bonds.size(),
                   a.structure.size(), a.structure.source);
  s += "ring sizes:";
  for (const auto& [k, v] : a.sizes.closed) s += fmt::format("  {}:{}", k, v);
  if (!a.sizes.open.empty()) {
    s += "   open (border):";
    for (const auto& [k, v] : a.sizes.open) s += fmt::format("  {}:{}", k, v);
  }
  s += "\n";
  for (const auto* d : {&a.pentagons, &a.heptagons}) {
    s += fmt::format("nearest {} to {} (ring steps):", d->size == 5 ? "pentagon" : "heptagon",
                     d->size == 5 ? "pentagon" : "heptagon");
    if (d->rings.empty()) s += " none";
    for (const auto& [k, v] : d->histogram) s += fmt::format("  {}:{}", k, v);
    if (d->unreachable) s += fmt::format("  (alone: {})", d->unreachable);
    s += "\n";
  }
  s += fmt::format("5-7 pairs: {} adjacent, {} matched ({} pentagons, {} heptagons)\n", a.pairs.adjacent_pairs,
                   a.pairs.matched_pairs, a.pairs.pentagons, a.pairs.heptagons);
  if (a.floor.six_chi)
    s += fmt::format("topology: chi {}  sum(6 - size) {}  6 chi {}  floor {} non-hexagons, observed {}\n", *a.floor.euler,
                     a.floor.sum_six_minus_size, *a.floor.six_chi, *a.floor.floor, a.floor.non_hexagons);
  else
    s += fmt::format("topology: open surface; sum(6 - size) over closed rings {}, observed {} non-hexagons\n",
                     a.floor.sum_six_minus_size, a.floor.non_hexagons);
  if (a.plane) {
    const auto& p = *a.plane;
    s += fmt::format("plane ({}): n = ({:.4f}, {:.4f}, {:.4f}), d = {:.4f}; mirror residual max {:.4g} rms {:.4g} "
                     "({:.3g}% of the diagonal)\n",
                     p.requested, p.plane.normal[0], p.plane.normal[1], p.plane.normal[2], p.plane.offset,
                     p.residual.max, p.residual.rms, p.diagonal > 0 ? 100 * p.residual.max / p.diagonal : 0.0);
    s += fmt::format("irregular rings: {} on the + side, {} on the - side, {} on the plane\n", p.sides.positive_total,
                     p.sides.negative_total, p.sides.on_plane_total);
    std::map<int, int> sizes;
    for (const auto* m : {&p.sides.positive, &p.sides.negative, &p.sides.on_plane})
      for (const auto& [k, v] : *m) sizes[k] = 1;
    for (const auto& [k, unused] : sizes) {
      auto get = [k = k](const std::map<int, std::size_t>& m) { auto it = m.find(k); return it == m.end() ? 0 : it->second; };
      s += fmt::format("  size {}: + {}  - {}  on {}\n", k, get(p.sides.positive), get(p.sides.negative), get(p.sides.on_plane));
    }
  }
  return s;
}

}  // namespace carbonmesh
