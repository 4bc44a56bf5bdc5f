// `carbonmesh build [IN] -o DIR [--bond 1.42] [--size L | --scale s | --atoms N] [--emin A --emax B]
//  [remesh options] [--passivate] [--topology]`: load, scale, remesh, dual, optimise, write LAMMPS/REBO2 input.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "carbonmesh/carbon/output_files.hpp"
#include "carbonmesh/carbon/passivate.hpp"
#include "carbonmesh/carbon/structure.hpp"
#include "carbonmesh/carbon/structure_scale.hpp"
#include "carbonmesh/dual/coarse_start.hpp"
#include "carbonmesh/dual/dual_mesh.hpp"
#include "carbonmesh/dual/ears.hpp"
#include "carbonmesh/dual/optimize.hpp"
#include "carbonmesh/remesh/atomic_file.hpp"
#include "carbonmesh/remesh/components.hpp"
#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/io.hpp"
#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/remesher.hpp"
#include "carbonmesh/remesh/shapes.hpp"
#include "commands.hpp"
#include "number_checks.hpp"
#include "defect_report.hpp"
#include "lattice_step.hpp"
#include "surface_checks.hpp"

namespace carbonmesh::cli {
namespace {

struct BuildOptions {
  std::string in, out;
  double bond = 1.42;
  std::optional<double> size, scale, atoms, emin, emax;
  std::optional<int> coarse_levels;
  RemeshSettings remesh;
  DualOptimizeSettings optimize;
  bool passivate = false, topology = false, repair = false, no_report = false, lattice = false;
  std::optional<double> lattice_turn;
  std::vector<int> chirality;  // --chirality N,M (empty: the nearest to the input's radius)
  long steps = 10000;
  double temperature = 300.0;
  int np = 4;
};

// Wall-clock seconds per stage, in order.
class StageClock {
 public:
  void stop(const std::string& stage) {
    const auto now = std::chrono::steady_clock::now();
    seconds_[stage] = std::chrono::duration<double>(now - last_).count();
    last_ = now;
  }
  nlohmann::json to_json() const {
    nlohmann::json j = nlohmann::json::object();
    double total = 0;
    for (const auto& [stage, s] : seconds_) j[stage] = s, total += s;
    j["total"] = total;
    return j;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
  std::map<std::string, double> seconds_;
};

// The largest structure `build` makes (documented in README and docs/reliability.md): 1e8 atoms is about
// 1e8 primal triangles, far beyond what the remesher and LAMMPS handle on one machine.
constexpr double kMaxAtoms = 1e8;
constexpr double kCoarseAtoms = 50000;  // a coarse level for each factor 4 from this structure size on (run_build)
constexpr int kMaxCoarseLevels = 4;

// The default coarse levels: one per factor 4 from kCoarseAtoms on, so that the coarsest level keeps at least
// kCoarseAtoms / 4 atoms, at most kMaxCoarseLevels: 1 from 50000 atoms, 2 from 200000, 3 from 800000, 4 from 3200000.
int default_coarse_levels(double atoms) {
  int levels = 0;
  while (levels < kMaxCoarseLevels && atoms >= kCoarseAtoms) ++levels, atoms /= 4;
  return levels;
}

// Option values CLI11 lets through (0, negative, nan, inf) are refused before any work, one line, exit 2.
void check_options(const BuildOptions& o) {
  auto positive = [](const char* name, double v) {
    if (!(v > 0) || !std::isfinite(v)) throw InputError(fmt::format("{} {} must be a positive number", name, v));
  };
  positive("--bond", o.bond);
  positive("--temperature", o.temperature);
  if (o.size) positive("--size", *o.size);
  if (o.scale) positive("--scale", *o.scale);
  if (o.atoms) {
    positive("--atoms", *o.atoms);
    if (*o.atoms < 1 || *o.atoms > kMaxAtoms)
      throw InputError(fmt::format("--atoms {:g} is outside [1, {:.0e}] (the largest structure carbonmesh builds)",
                                   *o.atoms, kMaxAtoms));
  }
  if (o.emin) positive("--emin", *o.emin);
  if (o.emax) positive("--emax", *o.emax);
}

int run_build(BuildOptions& o) {
  check_options(o);
  StageClock clock;
  ScaleSettings scale;
  scale.bond = o.bond;
  if (o.size) scale.mode = ScaleMode::Size, scale.value = *o.size;
  if (o.scale) scale.mode = ScaleMode::Factor, scale.value = *o.scale;
  if (o.atoms) scale.mode = ScaleMode::Atoms, scale.value = *o.atoms;
  // Load (validated) or the built-in sphere: the geodesic sphere whose dual, the icosahedral fullerene C_20T
  // (12 pentagons, no heptagons), is nearest in size to the structure asked for; with --atoms it is built
  // at exactly 20 T atoms (C60, C240, C540, C960 at --atoms 60, 240, 540, 960).
  TriMesh mesh;
  std::string source;
  if (o.in.empty()) {
    const double asked = structure_scale(make_geodesic_sphere({10.0, 4, true}), scale).expected_atoms;
    const GeodesicSphereShape shape = geodesic_sphere_for_faces(asked, 10.0);
    mesh = make_geodesic_sphere(shape);
    const long fullerene = static_cast<long>(mesh.n_faces());
    if (o.atoms) scale.value = static_cast<double>(fullerene);
    source = fmt::format("built-in sphere (geodesic, frequency {}{}: C{})", shape.frequency,
                         shape.sqrt3 ? " + sqrt(3)" : "", fullerene);
  } else {
    LoadSettings load;
    load.repair = o.repair;
    mesh = load_mesh(o.in, load);
    source = o.in;
  }
  const Topology input_topology = topology(mesh);
  const SelfIntersections input_crossings =
      o.in.empty() ? SelfIntersections{} : check_input_self_intersections(mesh, source);
  clock.stop("load");

  // Scale.
  StructureScale scaled = structure_scale(mesh, scale);
  if (o.emin) scaled.emin = *o.emin;
  if (o.emax) scaled.emax = *o.emax;
  if (o.in.empty()) {
    // The geodesic sphere keeps its 12 pentagons only if the remesher has nothing to change: its edges are
    // centred in the interval (geometric mean) when their spread fits. The dual optimisation's free scale
    // then sets the size from the bond length.
    const EdgeStats edges = edge_stats(mesh);
    const double shortest = edges.min * scaled.factor, longest = edges.max * scaled.factor;
    if (longest / shortest < scaled.emax / scaled.emin) {
      const double emin = scaled.emin, emax = scaled.emax;
      ScaleSettings centred = scale;
      centred.mode = ScaleMode::Factor;
      centred.value = scaled.factor * std::sqrt(emin * emax / (shortest * longest));
      scaled = structure_scale(mesh, centred);
      scaled.emin = emin, scaled.emax = emax;
    }
  }
  if (!(scaled.emin > 0) || !(scaled.emin < scaled.emax))
    throw InputError(fmt::format("edge interval [{}, {}] must satisfy 0 < emin < emax", scaled.emin, scaled.emax));
  if (!(scaled.expected_atoms >= 1))
    throw InputError(fmt::format("{}: the surface (area {:.6g} A^2) would hold about {:.3g} atoms, less than one: "
                                 "the coordinates are taken as Angstrom; scale it with --size, --scale or --atoms",
                                 source, scaled.area, scaled.expected_atoms));
  if (!(scaled.expected_atoms <= kMaxAtoms))
    throw InputError(fmt::format("{}: the surface (area {:.6g} A^2) would hold about {:.3g} atoms, more than the "
                                 "limit {:.0e}: scale it with --size, --scale or --atoms",
                                 source, scaled.area, scaled.expected_atoms, kMaxAtoms));
  if ((o.emin || o.emax) && scaled.emin > 2.0 / 3.0 * scaled.emax * (1 + 1e-12))
    spdlog::warn("interval [{}, {}] is too tight: emin > 2/3 emax (dissertation Ineq 5.1), long and short edges may "
                 "remain", scaled.emin, scaled.emax);
  scale_mesh(mesh, scaled.factor);
  spdlog::info("{}: scaled by {:.6g} to area {:.1f} A^2 (about {:.0f} atoms), edges in [{:.4f}, {:.4f}] A", source,
               scaled.factor, scaled.area, scaled.expected_atoms, scaled.emin, scaled.emax);
  // Components with less area than the smallest fullerene (C20) can hold no carbon net: scan debris, a stray
  // triangle. Kept, they leave edges outside the interval (the remesher runs all its iterations) and atoms
  // bonded at zero distance in the structure. The largest component always stays.
  const SmallComponents debris = remove_small_components(mesh, 20 * area_per_atom(o.bond));
  if (debris.removed > 0)
    spdlog::warn("{}: removed {} component{} smaller than a C20 cage ({:.1f} A^2): {} faces, {:.3g} A^2 in all",
                 source, debris.removed, debris.removed == 1 ? "" : "s", 20 * area_per_atom(o.bond), debris.faces,
                 debris.area);
  TriMesh surface = mesh;  // the surface the atoms stay on (a lattice tube's: its cylinder)
  clock.stop("scale");

  // Remesh.
  o.remesh.emin = scaled.emin;
  // The dual optimisation puts the atoms on the input surface itself: the remesh's surface fit would only
  // move the starting points, at the cost of closest-point queries on every face.
  o.remesh.fit_surface = false;
  o.remesh.minimax_fit = false;  // likewise
  o.remesh.snap_features = false;  // likewise, and its distance trees over the whole mesh cost most at 1M atoms
  o.remesh.flip_toward_input = false;  // likewise (and a flip may cost a hexagon)
  o.remesh.emax = scaled.emax;
  // The mean edge sets the atom count: an input already inside the interval is remeshed unless its mean is near a.
  // Not the built-in sphere, whose edges are centred in the interval and whose pentagons the remesher would move.
  if (!o.in.empty()) o.remesh.target_mean = scaled.edge;
  // Coarse levels for large structures: remeshed at 2^k times the interval, every edge then halved k times (springs
  // evening out the triangles after each halving), and the dual optimisation started from the optimised coarse
  // duals, coarsest first. One level (bunny, fertility and a torus at 24000-80000 atoms): a REBO2 energy 34-49
  // meV/atom lower after minimisation than the direct remesh, with a quarter of the 5-7 pairs. Fertility at 10^6
  // atoms with three levels against one: 5:754 7:790 rings instead of 5:5138 7:5174, 0.50% strained atoms instead
  // of 0.94%, 46.7-57.8 s end to end. A level has a quarter of the triangles of the next finer one: at 20000 atoms
  // neither bunny's nor fertility's level 1 converged (ears, handles) and the fallback to the direct remesh only
  // cost time, so the coarsest level keeps kCoarseAtoms / 4 atoms or more (docs/algorithm.md).
  o.remesh.coarse_levels = o.coarse_levels.value_or(default_coarse_levels(scaled.expected_atoms));
  o.remesh.on_iteration = [](const IterationLog& l) {
    spdlog::info("remesh {}iteration {:3d}  long {:6d}  short {:6d}  regular {:6.2f}%  mean {:.4f}  {:.2f}s{}",
                 l.level > 0 ? fmt::format("level {} ", l.level) : "", l.iteration, l.long_edges, l.short_edges,
                 l.percent_regular, l.mean, l.seconds,
                 l.nonlinear ? "  (nonlinear)" : "");
  };
  std::vector<CoarseLevel> coarse_meshes;  // the levels that converged, for the coarse start of the optimisation
  o.remesh.on_coarse_mesh = [&coarse_meshes](const TriMesh& m, int level) { coarse_meshes.push_back({level, m}); };
  RemeshResult remeshed;
  nlohmann::json lattice;  // summary.json's "lattice" (--lattice)
  if (o.lattice) {
    LatticeOptions options{o.lattice_turn, std::nullopt};
    if (!o.chirality.empty()) options.chirality = Chirality{o.chirality[0], o.chirality[1]};
    LatticeStep step = cut_lattice(mesh, source, scaled.edge, options, EdgeInterval{scaled.emin, scaled.emax},
                                   20 * area_per_atom(o.bond));
    remeshed = step.result;
    lattice = std::move(step.json);
    if (step.surface) surface = std::move(*step.surface);
  } else {
    if (!o.in.empty() && is_flat(flatness(mesh), scaled.edge))
      spdlog::info("{}: the surface is flat: --lattice cuts it from a triangular lattice instead of remeshing it (a "
                   "graphene sheet of hexagons only, no 5-7 pairs)",
                   source);
    else if (!o.in.empty() && has_border(mesh) && is_cylinder(cylinder_fit(mesh), scaled.edge))
      spdlog::info("{}: the surface lies on a cylinder: --lattice rolls a triangular lattice onto it instead of "
                   "remeshing it (hexagons only, no 5-7 pairs; an open tube becomes a nanotube, --chirality N,M "
                   "sets its indices)",
                   source);
    else if (!o.in.empty() && is_whole_sphere(mesh, scaled.edge))
      spdlog::info("{}: the surface is a sphere: --lattice folds a triangular lattice onto an icosahedron instead of "
                   "remeshing it (the icosahedral fullerene nearest its size: 12 pentagons, no heptagons; --chirality "
                   "H,K sets its Goldberg-Coxeter indices)",
                   source);
    else if (!o.in.empty() && is_whole_capsule(mesh, scaled.edge))
      spdlog::info("{}: the surface is a capsule: --lattice folds a triangular lattice onto an icosahedron lengthened "
                   "along a five-fold axis instead of remeshing it (a capped nanotube, its caps the halves of an "
                   "icosahedral fullerene: 12 pentagons, no heptagons; --chirality N,M sets its indices, any but the "
                   "thinnest: N and M not both multiples of 5 give apex caps, a pentagon at the tip and five around it)",
                   source);
    try {
      remeshed = remesh(mesh, o.remesh);
    } catch (const InputError& e) {  // name the input
      throw InputError(source + ": " + e.what());
    }
  }
  if (!remeshed.converged)
    spdlog::warn("{} long and {} short edges remain outside [{:.4f}, {:.4f}]", remeshed.long_edges,
                 remeshed.short_edges, scaled.emin, scaled.emax);
  mesh.garbage_collection();
  // Triangles with two border edges (whose atoms would have one bond) off before the dual (carbonmesh/dual/ears.hpp).
  const EarRemoval ears = remove_ears(mesh);
  if (ears.faces > 0)
    spdlog::info("{}: {} triangles with two border edges removed (area {:.2f} A^2; at corners sharper than the "
                 "triangles can follow, or teeth of a lattice row the outline cuts): their atoms would have had one "
                 "bond",
                 source, ears.faces, ears.area);
  if (mesh.n_faces() == 0)
    throw InputError(source + ": every triangle of the surface has two border edges (a strip one triangle wide): no "
                              "carbon net is left; build it larger (--atoms, --size)");
  // A flat lattice sheet's triangles are cells of one plane lattice: they cannot overlap, and CGAL's search on a
  // plane is slow (10 of the 15 s of a 10^6-atom flake).
  const bool flat_lattice = o.lattice && lattice.value("kind", "") == "sheet";
  const MeshStats remeshed_stats = mesh_stats(mesh, EdgeInterval{scaled.emin, scaled.emax}, !flat_lattice);
  check_remesh_self_intersections(remeshed_stats.self_intersections, source,
                                  (std::filesystem::path(o.out) / "remeshed.off").string());
  clock.stop("remesh");

  // Dual and its optimisation.
  Dual dual = build_dual(mesh);
  clock.stop("dual");
  // One atom per triangle of area about (sqrt(3)/4) a^2: a remeshed surface with less area than the input (detail
  // finer than the edges, such as a scan's noise, is bridged) or with a mean edge away from a (the interval allows
  // 0.8 a to 1.2 a) holds another number of atoms than the scale promised.
  if (const double atoms = static_cast<double>(dual.atoms());
      !o.in.empty() && std::abs(atoms - scaled.expected_atoms) > 0.1 * scaled.expected_atoms) {
    if (o.lattice)
      spdlog::warn("{}: {:.0f} atoms where the area promised about {:.0f}: {}", source, atoms, scaled.expected_atoms,
                   lattice_shortfall(lattice, 100 * surface_area(mesh) / scaled.area));
    else
      spdlog::warn("{}: {:.0f} atoms where the area promised about {:.0f}: the remeshed surface has {:.0f}% of the "
                   "input's area (detail finer than the edges, such as noise, is bridged) and a mean edge of {:.3f} A "
                   "(target {:.3f} A)",
                   source, atoms, scaled.expected_atoms, 100 * surface_area(mesh) / scaled.area,
                   remeshed_stats.edges.mean, scaled.edge);
  }
  o.optimize.bond = o.bond;
  // Coarse start: the duals of the coarse levels, optimised coarsest first at 2^k times the bond (and window), give
  // the fine atoms their long-range displacements first (carbonmesh/dual/coarse_start.hpp).
  std::vector<CoarseStartResult> started;
  if (!coarse_meshes.empty() && o.optimize.max_iterations > 0) {
    started = coarse_start(dual, coarse_meshes, surface, o.optimize);
    coarse_meshes.clear();
    for (const CoarseStartResult& r : started)
      spdlog::info("coarse start, level {}: {} atoms optimised in {} iterations ({:.2f} s); the next finer atoms "
                   "moved by {:.4f} A on average, {:.4f} A at most",
                   r.level, r.coarse_atoms, r.coarse.iterations, r.coarse.seconds, r.transfer.mean_shift,
                   r.transfer.max_shift);
    clock.stop("coarse optimize");
  }
  const DualOptimizeResult optimized = optimize_dual(dual, surface, o.optimize);
  clock.stop("optimize");
  std::size_t small_rings = 0;  // rings of 3 or 4 atoms: no place in an sp2 carbon net
  for (const auto& [size, n] : dual.counts.ring_sizes)
    if (size < 5) small_rings += n;
  // Angles beyond 90..150 degrees at a few 5-7 pairs are normal; more than 1% of the atoms is not.
  const bool strained = 100 * optimized.strained_after > dual.atoms();
  if (strained || small_rings > 0)
    spdlog::warn("{}: {} atoms with a bond angle outside 90..150 degrees, {} rings of fewer than 5 atoms: the "
                 "surface may have features thinner than the bond scale (docs/algorithm.md, known limitations); "
                 "inspect rings.ply, or build larger (--atoms, --size)",
                 source, optimized.strained_after, small_rings);

  // Carbon structure and files.
  CarbonStructure structure = carbon_structure(dual);
  std::optional<PassivationResult> passivation;
  if (o.passivate) passivation = passivate(structure);
  clock.stop("passivate");
  OutputSettings output;
  output.data.topology = o.topology;
  output.deck.steps = o.steps;
  output.deck.temperature = o.temperature;
  output.deck.mpi_ranks = o.np;
  const std::filesystem::path dir(o.out);
  const OutputFiles files = write_structure_files(dir, structure, dual.mesh, output);
  save_mesh(mesh, dir / "remeshed.off");
  clock.stop("write");

  nlohmann::json summary;
  summary["input"] = source;
  summary["bond"] = o.bond;
  summary["scale"] = to_json(scaled);
  summary["input_topology"] = to_json(input_topology);
  summary["input_self_intersections"] = to_json(input_crossings);
  summary["removed_components"] = to_json(debris);
  summary["removed_ears"] = {{"faces", ears.faces}, {"area", ears.area}};
  summary["genus"] = remeshed.after.genus;
  summary["borders"] = remeshed.after.boundary_loops;
  summary["remesh"] = to_json(remeshed);
  summary["remesh"].erase("log");
  if (o.lattice) summary["lattice"] = lattice;
  summary["remeshed_mesh"] = to_json(remeshed_stats);
  summary["dual"] = to_json(dual.counts);
  summary["atoms"] = structure.atoms();
  summary["carbon_atoms"] = structure.count(Element::C);
  summary["hydrogen_atoms"] = structure.count(Element::H);
  summary["bonds"] = structure.bonds.size();
  summary["rings_by_size"] = to_json(dual.counts)["rings_by_size"];
  summary["percent_three_bonds"] = dual.counts.percent_three_bonds;
  summary["optimization"] = to_json(optimized);
  if (!started.empty()) summary["coarse_start"] = to_json(started);
  if (passivation) summary["passivation"] = to_json(*passivation);
  summary["files"] = to_json(files);
  summary["files"]["remeshed_mesh"] = (dir / "remeshed.off").string();
  summary["files"]["summary"] = (dir / "summary.json").string();
  summary["seconds"] = clock.to_json();
  write_atomically(dir / "summary.json", [&summary](const std::filesystem::path& tmp) {
    std::ofstream file(tmp);
    file << summary.dump(2) << "\n";
    if (!file) throw std::runtime_error("cannot write " + tmp.string());
  });

  // The defect report (as `carbonmesh analyze DIR`), unless --no-report. The structure is written either way.
  if (!o.no_report) {
    try {
      const DefectReportOptions report;  // the defaults, as `carbonmesh analyze DIR`
      write_defect_report(dir, dir / "analysis", report);
      clock.stop("report");
    } catch (const std::exception& e) {
      spdlog::warn("defect report not written: {}", e.what());
    }
  }

  std::string rings;
  for (const auto& [size, n] : dual.counts.ring_sizes) rings += fmt::format(" {}:{}", size, n);
  std::cout << fmt::format(
      "{} -> {}\n"
      "remesh: long {} short {} regular {:.2f}% iterations {} genus {} borders {}\n"
      "atoms {} ({} C, {} H)  bonds {}  rings{}  open rings {}  three-bonded {:.2f}%\n"
      "bonds before  min {:.4f} mean {:.4f} std {:.4f} max {:.4f}  angles {:.2f}..{:.2f} (mean {:.2f})\n"
      "bonds after   min {:.4f} mean {:.4f} std {:.4f} max {:.4f}  angles {:.2f}..{:.2f} (mean {:.2f})\n"
      "strained atoms (a bond angle outside 90..150 degrees): {} before, {} after ({:.3f}%)\n"
      "run: cd {} && lmp -in in.rebo   (or mpirun -np {} lmp -in in.rebo)\n",
      source, dir.string(), remeshed.long_edges, remeshed.short_edges, remeshed.percent_regular, remeshed.iterations,
      remeshed.after.genus, remeshed.after.boundary_loops, structure.atoms(), structure.count(Element::C),
      structure.count(Element::H), structure.bonds.size(), rings, dual.counts.open_rings,
      dual.counts.percent_three_bonds, optimized.bonds_before.min, optimized.bonds_before.mean,
      optimized.bonds_before.std, optimized.bonds_before.max, optimized.angles_before.min,
      optimized.angles_before.max, optimized.angles_before.mean, optimized.bonds_after.min,
      optimized.bonds_after.mean, optimized.bonds_after.std, optimized.bonds_after.max, optimized.angles_after.min,
      optimized.angles_after.max, optimized.angles_after.mean, optimized.strained_before, optimized.strained_after,
      structure.atoms() ? 100.0 * static_cast<double>(optimized.strained_after) / static_cast<double>(structure.atoms())
                        : 0.0,
      dir.string(), o.np);
  if (remeshed.topology_violation) {
    std::cerr << fmt::format("carbonmesh: error: {}: remeshing changed the surface type (genus {} components {} "
                             "borders {} -> genus {} components {} borders {}); the structure in {} is built on "
                             "the best mesh with the input's surface type\n",
                             source, remeshed.before.genus, remeshed.before.components,
                             remeshed.before.boundary_loops, remeshed.changed.genus, remeshed.changed.components,
                             remeshed.changed.boundary_loops, dir.string());
    return kExitTopologyViolation;
  }
  return 0;
}

}  // namespace

void add_build_command(CLI::App& app, Action& action) {
  auto opt = std::make_shared<BuildOptions>();
  auto* cmd = app.add_subcommand(
      "build", "surface -> remesh -> dual -> optimised sp2 carbon: LAMMPS data, REBO2 deck, XYZ, PDB, ring PLY");
  cmd->add_option("in", opt->in, "input mesh (.off .obj .ply .stl); default: the built-in sphere");
  cmd->add_option("-o,--output", opt->out, "output folder")->required();
  cmd->add_option("--bond", opt->bond, "C-C bond length b in A (primal edge sqrt(3) b)")->capture_default_str();
  auto* size = cmd->add_option("--size", opt->size, "scale so the longest bounding-box side is L (A; default: none of --size/--scale/--atoms: input units are A)");
  auto* scale = cmd->add_option("--scale", opt->scale, "multiply the input coordinates by s (dimensionless; the result is in A; default: none)");
  auto* atoms = cmd->add_option("--atoms", opt->atoms, "scale to about N atoms (count; area = N (sqrt(3)/4) a^2, 2.62 A^2 per atom at b = 1.42; default: none)");
  size->excludes(scale)->excludes(atoms);
  scale->excludes(atoms);
  cmd->add_option("--emin", opt->emin, "lower edge bound of the remesh, A (default 0.8 sqrt(3) b = 1.968 at b = 1.42)");
  cmd->add_option("--emax", opt->emax, "upper edge bound of the remesh, A (default 1.2 sqrt(3) b = 2.951 at b = 1.42)");
  cmd->add_option("--iterations,-n", opt->remesh.iterations, "remesh: maximum iterations")->capture_default_str()
      ->check(non_negative_number());
  cmd->add_option("--kl", opt->remesh.kl, "remesh: star number of the low-pass filter")->capture_default_str()
      ->check(positive_number());
  cmd->add_option("--kn", opt->remesh.kn, "remesh: star number of the nonlinear optimizer")->capture_default_str()
      ->check(positive_number());
  cmd->add_option("--p", opt->remesh.p, "remesh: replace the projection mesh every p iterations (0: never)")
      ->capture_default_str()->check(non_negative_number());
  cmd->add_option("--l", opt->remesh.l, "remesh: percent of long+short edges that starts the nonlinear optimizer")
      ->capture_default_str()->check(non_negative_number());
  cmd->add_option("--stall-limit", opt->remesh.stall_limit,
                  "remesh: stop after this many iterations without a better mesh (0: never)")
      ->capture_default_str()->check(non_negative_number());
  const std::map<std::string, ParametrizationWeights> weights{{"mean-value", ParametrizationWeights::MeanValue},
                                                             {"shape-preserving", ParametrizationWeights::ShapePreserving}};
  cmd->add_option("--weights", opt->remesh.weights, "remesh: mean-value or shape-preserving")
      ->transform(CLI::CheckedTransformer(weights, CLI::ignore_case))->default_str("mean-value");
  cmd->add_option("--coarse-levels", opt->coarse_levels,
                  "remesh: remesh at 2^k times the interval first, then halve every edge k times (default: 1 from "
                  "50000 atoms on, 2 from 200000, 3 from 800000, 4 from 3200000, else 0; the dual optimisation "
                  "starts from every level, coarsest first)")
      ->check(non_negative_number());
  cmd->add_option("--optimize-iterations", opt->optimize.max_iterations, "dual optimisation: L-BFGS iterations (0: off)")
      ->capture_default_str()->check(non_negative_number());
  cmd->add_option("--angle-weight", opt->optimize.angle_weight, "dual optimisation: weight w_a of the angle term (dimensionless, relative to the bond term)")
      ->capture_default_str()->check(non_negative_number());
  cmd->add_option("--contact-weight", opt->optimize.contact_weight,
                  "dual optimisation: weight w_c of the contact term on non-bonded atoms closer than sqrt(2) b (per A^2; 0: off)")
      ->capture_default_str()->check(non_negative_number());
  cmd->add_option("--surface-weight", opt->optimize.surface_weight, "dual optimisation: weight w_s of the surface-distance term (per A^2)")
      ->capture_default_str()->check(non_negative_number());
  cmd->add_flag("--passivate", opt->passivate, "hydrogen on two-coordinated border carbons (C-H 1.09 A)");
  cmd->add_flag("--topology", opt->topology, "also write structure-full.data: atom_style full with Bonds and Angles (other force fields)");
  cmd->add_flag("--no-report", opt->no_report, "skip the defect report (DIR/analysis: report.json, plots, report.html)");
  cmd->add_flag("--lattice", opt->lattice,
                "flat, cylindrical, spherical or capsule-shaped input: cut it from a triangular lattice of edge "
                "sqrt(3) b, flat or rolled into a tube, or fold that lattice onto an icosahedron, round or lengthened, "
                "instead of remeshing it (graphene or a nanotube: hexagons only; a sphere: the icosahedral fullerene "
                "C_20T nearest its size, 12 pentagons and hexagons; a capsule: the capped (5h, 5k) tube nearest its "
                "size, the same; a flat sheet has one lattice line along the longest straight side of its outline: a "
                "zigzag edge there)");
  cmd->add_option("--lattice-turn", opt->lattice_turn,
                  "with --lattice on a flat input or a part of a cylinder that does not go around its axis: turn the "
                  "lattice by this many degrees from the longest straight side (0: a zigzag edge there, 30: an "
                  "armchair edge; default 0)")
      ->needs("--lattice");
  cmd->add_option("--chirality", opt->chirality,
                  "with --lattice on an open tube: its chiral indices N,M (N,0 zigzag, N,N armchair; "
                  "radius sqrt(3) b sqrt(N^2 + NM + M^2) / (2 pi)); on a sphere: the fullerene's Goldberg-Coxeter "
                  "indices N,M (C_20T, T = N^2 + NM + M^2; 1,1 is C60; N,0 and N,N symmetry Ih, others chiral); on a "
                  "capsule: the capped tube's chiral indices N,M (both multiples of 5: its caps the halves of C_20T, T "
                  "= (N^2 + NM + M^2) / 25; otherwise apex caps: a pentagon at the tip, five around it); "
                  "default: the indices nearest the input's radius (on a capsule: of the multiples of 5)")
      ->delimiter(',')
      ->expected(2)
      ->check(non_negative_number())
      ->needs("--lattice");
  cmd->add_flag("--repair", opt->repair, "merge duplicate and nearly coincident vertices, orient faces alike, split non-manifold edges and vertices and faces at T-junctions, drop degenerate/duplicate faces");
  cmd->add_option("--steps", opt->steps, "deck: NVT steps of 1 fs")->capture_default_str()->check(non_negative_number());
  cmd->add_option("--temperature", opt->temperature, "deck: temperature (K)")->capture_default_str();
  cmd->add_option("--np", opt->np, "deck: MPI ranks in the mpirun comment line (count)")->capture_default_str()
      ->check(positive_number());
  cmd->callback([&action, opt] { action = [opt]() -> int { return run_build(*opt); }; });
}

}  // namespace carbonmesh::cli
