// Algorithm 1 (UniformRemeshing): the interval-constraining remesher.
#include "carbonmesh/remesh/remesher.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <nlohmann/json.hpp>

#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/garbage_collection.hpp"
#include "carbonmesh/remesh/hausdorff.hpp"
#include "carbonmesh/remesh/remesh_steps.hpp"
#include "carbonmesh/remesh/triangle_tree.hpp"
#include "remesh_geometry.hpp"

namespace carbonmesh {
namespace {

void validate(const RemeshSettings& s) {
  if (!(s.emin > 0)) throw InputError(fmt::format("emin {} must be positive", s.emin));
  if (!(s.emin < s.emax)) throw InputError(fmt::format("emin {} must be smaller than emax {}", s.emin, s.emax));
  if (s.iterations < 0) throw InputError(fmt::format("iterations {} must not be negative", s.iterations));
  if (s.stall_limit < 0) throw InputError(fmt::format("stall limit {} must not be negative", s.stall_limit));
  if (s.kl < 1 || s.kn < 1) throw InputError(fmt::format("kl {} and kn {} must be at least 1", s.kl, s.kn));
  if (s.p < 0) throw InputError(fmt::format("p {} must not be negative", s.p));
  if (!(s.l >= 0)) throw InputError(fmt::format("l {} must not be negative", s.l));
  if (!std::isfinite(s.emax)) throw InputError(fmt::format("emax {} must be finite", s.emax));
  if (!(s.snap_tolerance >= 0 && std::isfinite(s.snap_tolerance)))
    throw InputError(fmt::format("snap tolerance {} must be finite and not negative", s.snap_tolerance));
}

// Whether every edge outside `interval` has an end on a border (where the post-processing cannot move the
// border vertex off its curve; a finer level has room to mend it).
bool outside_edges_touch_border(const TriMesh& mesh, const EdgeInterval& interval) {
  for (auto e : mesh.edges()) {
    const double length = geometry::edge_length(mesh, e);
    if (length >= interval.emin && length <= interval.emax) continue;
    const auto h = mesh.halfedge_handle(e, 0);
    if (!mesh.is_boundary(mesh.to_vertex_handle(h)) && !mesh.is_boundary(mesh.from_vertex_handle(h))) return false;
  }
  return true;
}

// About how many triangles the remeshed surface has: the area over an equilateral triangle of the mid edge.
double expected_faces(const TriMesh& mesh, const RemeshSettings& s) {
  const double m = 0.5 * (s.emin + s.emax);
  return surface_area(mesh) / (std::sqrt(3.0) / 4.0 * m * m);
}

void check_size(const TriMesh& mesh, const RemeshSettings& s) {
  const double faces = expected_faces(mesh, s);
  if (!(faces <= s.max_faces))
    throw InputError(fmt::format("the interval [{}, {}] would need about {:.3g} triangles on this surface (area "
                                 "{:.6g}), more than the limit {:.3g}: check the units or scale the model",
                                 s.emin, s.emax, faces, surface_area(mesh), s.max_faces));
}

constexpr int kStallIterations = 5;
constexpr int kRisingIterations = 3;
constexpr double kReorderShare = 0.2;
constexpr int kCoarseIterations = 50;
constexpr std::size_t kCoarseCheckSamples = 20000;  // input samples that check a post-processed coarse level
constexpr std::size_t kCoarseEdgesLeft = 10;  // edges outside a post-processed coarse level (and the finer level
constexpr std::size_t kCoarseEdgesLeftShare = 10000;  // it starts) that may be left, or one in this many
constexpr int kSubdivisionSprings = 4;  // spring_relaxation steps after each midpoint subdivision
constexpr double kRunawayFactor = 4.0;  // faces over the expected count that stop a diverging loop
constexpr double kVanishingShare = 0.5;  // a loop that erodes the surface stops below this share of the start area
constexpr int kErosionWindow = 10;       // ... if the area also fell by more than kErosionDrop over this many
constexpr double kErosionDrop = 0.15;    // iterations (after the first 2 windows, where noise is bridged)
constexpr double kTargetMeanTolerance = 0.05;  // settings.target_mean: a mean edge this share off it is remeshed

// How many edges outside the interval a post-processed coarse level (and the finer level started from it) may keep.
std::size_t few_edges(const TriMesh& mesh) {
  return std::max(kCoarseEdgesLeft, mesh.n_edges() / kCoarseEdgesLeftShare);
}

// The projection target's edges are bisected down to this many emax (ProjectionTarget): bunny.off at 250000 atoms
// (its filled base a fan of slivers with 35-50 A edges, emax 2.95 A) otherwise projected vertices onto faces
// beside theirs, collapsing edges to nothing, and ended after 150 iterations with 47 edges outside.
constexpr double kTargetEdgeFactor = 4.0;

// CalcEdgesPercent of Algorithm 1: long+short edges as a percentage of all edges.
double troubling_percent(const EdgeStats& e) {
  return e.count == 0 ? 0.0 : 100.0 * static_cast<double>(e.long_edges + e.short_edges) / static_cast<double>(e.count);
}

}  // namespace

BestMesh::BestMesh(const TriMesh& input, std::size_t troubling, double percent_regular)
    : input_(topology(input)), mesh_(input), troubling_(troubling), percent_regular_(percent_regular) {}

bool BestMesh::offer(const TriMesh& mesh, std::size_t troubling, double percent_regular) {
  if (!(troubling < troubling_ || (troubling == troubling_ && percent_regular > percent_regular_))) return false;
  if (!topology(mesh).same_type(input_)) {
    ++rejected_;
    return false;
  }
  mesh_ = mesh;
  forget_nearest_target_vertices(mesh_);  // its memory, not needed to restore it
  troubling_ = troubling;
  percent_regular_ = percent_regular;
  return true;
}

std::optional<Topology> enforce_surface_type(TriMesh& mesh, const BestMesh& best) {
  const Topology now = topology(mesh);
  if (now.same_type(best.input_topology())) return std::nullopt;
  mesh = best.mesh();
  return now;
}

void record_final_figures(RemeshResult& result, const TriMesh& mesh, const EdgeInterval& interval) {
  const EdgeStats edges = edge_stats(mesh, interval);
  const ValenceStats valence = valence_stats(mesh);
  result.long_edges = edges.long_edges;
  result.short_edges = edges.short_edges;
  result.converged = result.long_edges + result.short_edges == 0;
  result.percent_regular = valence.percent_regular;
  result.percent_eval_gt1 = valence.percent_eval_gt1;
  result.after = topology(mesh);
}

RemeshResult remesh(TriMesh& mesh, const RemeshSettings& s) {
  validate(s);
  check_size(mesh, s);
  const auto start = std::chrono::steady_clock::now();
  auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  RemeshResult result;
  result.before = topology(mesh);
  mesh.garbage_collection();
  const double m = 0.5 * (s.emin + s.emax);
  const EdgeInterval interval{s.emin, s.emax};

  spatial_order(mesh);  // the input's order may be arbitrary (see the loop)
  auto target = std::make_unique<TriMesh>(mesh);  // M: the projection mesh
  // The input for the final feature snap and surface fit (the projection mesh is the input too unless p
  // replaces it).
  std::unique_ptr<TriMesh> input =
      (s.fit_surface || s.snap_features || s.measure_cut_off) && s.p > 0 ? std::make_unique<TriMesh>(mesh) : nullptr;
  auto projection_target = std::make_unique<ProjectionTarget>(*target, kTargetEdgeFactor * s.emax);
  EdgeStats edges = edge_stats(mesh, interval);
  bool from_post_processed = false;  // the coarse start below is a post-processed coarse level
  // settings.target_mean: a mean edge inside the interval but away from the target would be kept (the loop only
  // mends the edges outside).
  const bool off_target = s.target_mean > 0 && edges.mean >= s.emin && edges.mean <= s.emax &&
                          std::abs(edges.mean - s.target_mean) > kTargetMeanTolerance * s.target_mean;
  // Coarse to fine: the coarser levels remesh this input (their own surface fit and snap off), then every edge
  // is halved and the midpoints are put on the input. Not for an input that has every edge inside already, unless
  // its mean edge is off the target.
  if (s.coarse_levels > 0 && (edges.long_edges + edges.short_edges > 0 || off_target)) {
    RemeshSettings coarse = s;
    coarse.emin = 2 * s.emin;
    coarse.emax = 2 * s.emax;
    coarse.coarse_levels = s.coarse_levels - 1;
    coarse.target_mean = 2 * s.target_mean;
    // A coarse level converges within kCoarseIterations where it is a good start (fertility at 10^6 atoms: 16);
    // one that has not by then is given up.
    coarse.iterations = std::min(s.iterations, kCoarseIterations);
    coarse.fit_surface = coarse.minimax_fit = coarse.snap_features = coarse.flip_toward_input = false;
    coarse.measure_cut_off = false;
    coarse.on_iteration = [&](const IterationLog& l) {
      IterationLog shifted = l;
      ++shifted.level;
      shifted.seconds = seconds();
      result.log.push_back(shifted);
      if (s.on_iteration) s.on_iteration(shifted);
    };
    if (s.on_coarse_mesh)
      coarse.on_coarse_mesh = [&](const TriMesh& m, int level) { s.on_coarse_mesh(m, level + 1); };
    const RemeshResult c = remesh(mesh, coarse);
    result.coarse_iterations = c.coarse_iterations + c.iterations;
    // A coarse level that needed the post-processing (a feature thinner than twice the interval, such as an ear
    // at a small structure size) is as a rule no starting point: the fine level then starts over from the input.
    bool usable = c.converged && !c.post_processed && !c.topology_violation;
    // One that needed the post-processing and is left with no edges outside, or a few, each with an end on a
    // border (a scan's hole; the finer levels mend them), is still a start if it lost no part of the surface: every
    // sampled input point within two of its longest edges (2 coarse emax) of it (a border of a scan cut across by
    // the coarse edges is farther than one). Edges left outside in the interior mean a feature too thin for the
    // level. A level kept this way can still be a poor start (a torus tube of radius 0.6 at [0.8, 1.2], 0 edges
    // outside after post-processing): see the retry at the end.
    const std::size_t left = c.long_edges + c.short_edges;
    if (c.post_processed && !c.topology_violation &&
        left <= few_edges(mesh) &&
        outside_edges_touch_border(mesh, EdgeInterval{coarse.emin, coarse.emax})) {
      HausdorffSettings sampling;
      sampling.samples = kCoarseCheckSamples;
      const double farthest = hausdorff_distance(mesh, *target, sampling).backward_max;
      usable = farthest <= 2 * coarse.emax;
      spdlog::info("coarse level [{:.4f}, {:.4f}] post-processed, {} edges outside; the input is {:.4f} from it at "
                   "most ({} samples): {}",
                   coarse.emin, coarse.emax, left, farthest, sampling.samples,
                   usable ? "kept as the start" : "farther than 2 emax, not kept");
    }
    from_post_processed = usable && c.post_processed;
    std::optional<TriMesh> coarse_mesh;
    if (usable && s.on_coarse_mesh) coarse_mesh = mesh;
    if (usable && midpoint_subdivision(mesh)) {
      if (coarse_mesh) s.on_coarse_mesh(*coarse_mesh, 1);
      result.coarse_levels = c.coarse_levels + 1;
      result.bisected_vertices = c.bisected_vertices;  // (the subdivision is in spatial memory order)
      projection(*projection_target, mesh, /*only_moved=*/false);
      // The four triangles of a coarse one are similar to it: springs even out the sheared patches a flat coarse
      // triangle leaves (fertility at 10^6 atoms with three levels: 0.50% strained atoms in the optimised dual
      // instead of 1.50%, 5:754 7:790 rings instead of 5:505 7:541).
      spring_relaxation(mesh, m, kSubdivisionSprings);
      projection(*projection_target, mesh, /*only_moved=*/false);
      edges = edge_stats(mesh, interval);
      spdlog::info("coarse level {} [{:.4f}, {:.4f}] converged in {} iterations, subdivided to {} vertices: {} long "
                   "and {} short edges in [{:.4f}, {:.4f}]",
                   result.coarse_levels, coarse.emin, coarse.emax, c.iterations, mesh.n_vertices(), edges.long_edges,
                   edges.short_edges, s.emin, s.emax);
    } else {
      const std::string why =
          usable ? "could not be subdivided (a non-manifold mesh)"
                 : fmt::format("did not converge within its iterations ({} long, {} short before post-processing)",
                               c.log.empty() ? 0 : c.log.back().long_edges,
                               c.log.empty() ? 0 : c.log.back().short_edges);
      spdlog::info("coarse level [{:.4f}, {:.4f}] {}: remeshing the input at [{:.4f}, {:.4f}] directly", coarse.emin,
                   coarse.emax, why, s.emin, s.emax);
      mesh = *target;
      edges = edge_stats(mesh, interval);
    }
  }
  // The input itself is to be remeshed here with its mean edge inside the interval but off the target: split into
  // four first, the loop then brings the mean to the middle as from any finer mesh.
  if (off_target && result.coarse_levels == 0 && midpoint_subdivision(mesh)) {
    spdlog::info("the mean edge {:.4f} is inside [{:.4f}, {:.4f}] but {:.1f}% off {:.4f}: split into four to remesh "
                 "from finer edges",
                 edges.mean, s.emin, s.emax, 100 * (edges.mean / s.target_mean - 1), s.target_mean);
    edges = edge_stats(mesh, interval);
  }
  // An input much coarser than the interval (a small model scaled up for a large structure): the first
  // iterations would split every edge once per pass and overshoot to many short edges. Longest-edge bisection
  // (OpenMesh's LongestEdgeT; new vertices at edge midpoints, so on the input) down to edges <= emax first:
  // fertility at 300000 atoms 19% less remeshing CPU time, 3 fewer iterations, 5% fewer non-hexagons.
  if (result.coarse_levels == 0 && edges.mean > 2 * s.emax) {
    const std::size_t before = mesh.n_vertices();
    longest_edge_bisection(mesh, s.emax);
    result.bisected_vertices = mesh.n_vertices() - before;
    spatial_order(mesh);
    edges = edge_stats(mesh, interval);
    spdlog::info("input much coarser than the interval: longest-edge bisection to edges <= emax, {} -> {} vertices",
                 before, mesh.n_vertices());
  }
  // A mesh with every edge inside but vertices two or more off their ideal valence (the valence-4/8 grid that the
  // bisection above makes of a cube's faces) gets one ordinary iteration anyway: flips and the low-pass filter,
  // which the interval test alone would skip. Then the loop goes on while edges are outside.
  const ValenceStats start_valence = valence_stats(mesh);
  const bool irregular = edges.long_edges + edges.short_edges == 0 && start_valence.percent_eval_gt1 > 0;
  // Such an input would be a best mesh that only a converged loop beats: the stall rule below would stop any loop
  // that is still converging after stall_limit iterations, and the post-processing would start from the input
  // again (cubes of side 44.6-47.2 for [1.9676, 2.9514]: 1 of 11 sizes). So the loop's own meshes compete
  // for the best (the input scores worse than any of them), and the input is the fallback at the end.
  const std::size_t worse_than_any = std::numeric_limits<std::size_t>::max();
  BestMesh best(mesh, irregular ? worse_than_any : edges.long_edges + edges.short_edges,
                start_valence.percent_regular);
  std::optional<TriMesh> restart_input;
  if (irregular) {
    restart_input = mesh;
    forget_nearest_target_vertices(*restart_input);  // (as in BestMesh: its memory, not needed to restore it)
  }
  std::vector<double> areas{surface_area(mesh)};  // areas[i]: after iteration i (0: the start)

  // The ceiling of the runaway guard below: kRunawayFactor times the faces the interval needs or the mesh has now,
  // whichever is more, plus a floor for tiny surfaces.
  const double faces_ceiling =
      kRunawayFactor * std::max(expected_faces(mesh, s), static_cast<double>(mesh.n_faces())) + 1000;
  int iteration = 0;
  std::size_t churn = 0;
  std::size_t lowest = std::numeric_limits<std::size_t>::max();
  int stalled = 0;
  int rising = 0;        // nonlinear iterations in a row that ended with more long+short edges than they began with
  bool guarded = false;  // projection(..., keep = interval) after the nonlinear optimizer
  int best_iteration = 0;  // the iteration that gave the best mesh (0: the start)
  double l = s.l;  // the share of long+short edges (percent) that starts the nonlinear phase; raised once on a stall
  while ((edges.long_edges + edges.short_edges > 0 || (iteration == 0 && irregular)) && iteration < s.iterations) {
    const bool restart = iteration == 0 && irregular;
    if (s.p > 0 && iteration > 0 && iteration % s.p == 0) {
      target = std::make_unique<TriMesh>(mesh);
      projection_target = std::make_unique<ProjectionTarget>(*target, kTargetEdgeFactor * s.emax);
      forget_projection(mesh);
    }
    // Few long and short edges left (the nonlinear phase): splitting an edge just above emax or collapsing
    // one just below emin only trades it for new short or long ones when emax < 2 emin, so edges within a
    // quarter interval width outside are left to the nonlinear optimizer, and flips keep edges inside.
    // When the count of long+short edges has not reached a new low for kStallIterations, one full stellar
    // step runs again (and the count starts over).
    const std::size_t troubling_now = edges.long_edges + edges.short_edges;
    if (troubling_now < lowest && !restart) {  // the restart's count (0) is no low to beat
      lowest = troubling_now;
      stalled = 0;
    } else {
      ++stalled;
    }
    const bool kick = stalled >= kStallIterations;
    if (kick) {
      lowest = std::numeric_limits<std::size_t>::max();
      stalled = 0;
      // A low-pass phase that stalls above l (noise or creases at the edge scale keep stirring up the same few
      // dozen edges) hands over to the nonlinear optimizer at twice the share. Once: doubled again (to 2-4%), it
      // also took over on a flat disc and a noisy sphere in `build`, which then had 26-44% more strained atoms.
      if (troubling_percent(edges) > l && l == s.l && s.l > 0) {
        l = 2 * s.l;
        spdlog::debug("iteration {}: no new low of long+short edges in {} iterations ({:.2f}%): the nonlinear "
                      "optimizer takes over from {:.2f}%",
                      iteration + 1, kStallIterations, troubling_percent(edges), l);
      }
    }
    const bool nonlinear_phase = troubling_percent(edges) <= l && !kick && !restart;
    IntermediateInterval step = intermediate_interval(edges.mean, s.emin, s.emax);
    if (nonlinear_phase) step = {s.emin - 0.25 * (s.emax - s.emin), s.emax + 0.25 * (s.emax - s.emin)};
    const double t_stellar = seconds();
    const StellarResult stellar = stellar_operations(mesh, step.emin, step.emax, m);
    const double t_gc = seconds();
    if (stellar.collapses > 0) collect_garbage(mesh);  // only collapses delete elements (OpenMesh's result, faster)
    const double t_order = seconds();
    // Splits append elements and garbage collection fills holes from the ends: once they have touched a
    // fifth of the vertices, the mesh is put back in spatial memory order (armadillo: 2x faster iterations).
    churn += stellar.splits + stellar.collapses;
    if (churn > kReorderShare * static_cast<double>(mesh.n_vertices())) {
      spatial_order(mesh);
      churn = 0;
    }
    const double t_flips = seconds();
    const std::size_t flips = correct_valence(mesh, m, nonlinear_phase ? &interval : nullptr);
    spdlog::debug("iteration {}: interval [{:.4f}, {:.4f}], {} splits, {} collapses, {} flips; stellar {:.3f}s, "
                  "garbage collection {:.3f}s, memory order {:.3f}s, flips {:.3f}s",
                  iteration + 1, step.emin, step.emax, stellar.splits, stellar.collapses, flips, t_gc - t_stellar,
                  t_order - t_gc, t_flips - t_order, seconds() - t_flips);
    edges = edge_stats(mesh, interval);
    const bool nonlinear = troubling_percent(edges) <= l && !restart;
    const double t_smooth = seconds();
    if (nonlinear)
      nonlinear_optimizer(mesh, s.kn, s.emin, s.emax);
    else
      low_pass_filter(mesh, s.kl, s.weights, m);
    const double t_project = seconds();
    projection(*projection_target, mesh, /*only_moved=*/true, nonlinear && guarded ? &interval : nullptr);
    spdlog::debug("iteration {}: {} {:.3f}s, projection {:.3f}s", iteration + 1,
                  nonlinear ? "nonlinear optimizer" : "low-pass filter", t_project - t_smooth, seconds() - t_project);
    ++iteration;

    edges = edge_stats(mesh, interval);
    if (!guarded) {
      rising = nonlinear && edges.long_edges + edges.short_edges > troubling_now ? rising + 1 : 0;
      if (rising >= kRisingIterations) {
        guarded = true;
        spdlog::info("remesh: long and short edges rose in {} nonlinear iterations in a row (to {}): from "
                     "iteration {} on, the projection keeps the nonlinear optimizer's edges inside the interval",
                     kRisingIterations, edges.long_edges + edges.short_edges, iteration + 1);
      }
    }
    const ValenceStats valence = valence_stats(mesh);
    IterationLog log;
    log.iteration = iteration;
    log.long_edges = edges.long_edges;
    log.short_edges = edges.short_edges;
    log.percent_regular = valence.percent_regular;
    log.mean = edges.mean;
    log.std = edges.std;
    log.seconds = seconds();
    log.nonlinear = nonlinear;
    log.l = l;
    result.log.push_back(log);
    if (s.on_iteration) s.on_iteration(log);
    // A surface thinner than the interval near its rims (a disc 1:20 at a few thousand atoms) loses them every
    // iteration and shrank to a tetrahedron, whose 6 short edges were the fewest of the run (the best mesh): its
    // area falls steadily, by 1-2% of the start each iteration. Bridged noise also takes area (a sphere with 15%
    // radial noise keeps 22-45%), but in the first iterations only. Below half the start area and still falling by
    // more than kErosionDrop per kErosionWindow iterations, the loop ends and that mesh is no candidate for the best.
    const double area = surface_area(mesh);
    areas.push_back(area);
    const double earlier =  // the area kErosionWindow iterations ago, once 2 windows have passed (0 before)
        iteration >= 2 * kErosionWindow ? areas[static_cast<std::size_t>(iteration - kErosionWindow)] : 0.0;
    if (area < kVanishingShare * areas[0] && area < (1 - kErosionDrop) * earlier) {
      spdlog::warn("remesh: the surface shrank to {:.0f}% of its area by iteration {}, {:.0f}% in the last {} (a part "
                   "thinner than the interval eroding): stopped and kept the best mesh",
                   100 * area / areas[0], iteration, 100 * (1 - area / earlier), kErosionWindow);
      result.vanished = true;
      break;
    }
    if (best.offer(mesh, edges.long_edges + edges.short_edges, valence.percent_regular)) best_iteration = iteration;
    // No better mesh for stall_limit iterations: the rest of the n seldom finds one (the longest wait seen before a
    // better one: 25 iterations, a grid cube before the raised l, and once 104, build's noisy sphere at 2000 atoms,
    // for one edge fewer outside; a flat disc whose rim is thinner than emin found its best in iteration 18 and none
    // in the 132 after it).
    if (s.stall_limit > 0 && iteration - best_iteration >= s.stall_limit && edges.long_edges + edges.short_edges > 0) {
      spdlog::info("remesh: no better mesh since iteration {} ({} long and short edges): stopped after iteration {} "
                   "and kept the best mesh",
                   best_iteration, best.troubling(), iteration);
      result.stalled = true;
      break;
    }
    // Section 4.1's intermediate interval follows the mean edge: once splits and collapses feed each other (the
    // mean falling, the interval with it), the mesh grows without bound. Far more faces than the interval needs
    // end the loop; the best mesh goes to the post-processing.
    if (static_cast<double>(mesh.n_faces()) > faces_ceiling) {
      spdlog::warn("remesh: {} faces where the interval needs about {:.0f}: the iterations diverge; stopped after "
                   "iteration {} and kept the best mesh",
                   mesh.n_faces(), expected_faces(mesh, s), iteration);
      result.diverged = true;
      break;
    }
  }
  result.iterations = iteration;
  RemeshStepSeconds& took = result.step_seconds;
  double lap = seconds();  // the end of the last step timed
  auto step_end = [&](double& step) {
    const double now = seconds();
    step = now - lap;
    lap = now;
  };
  took.iterations = lap;
  if (edges.long_edges + edges.short_edges > 0 || result.vanished) {
    mesh = best.mesh();
    post_process(mesh, s.kn, s.emin, s.emax);
    result.post_processed = true;
  }
  // Vertices of valence <= 4 that flips cannot repair are collapsed where that adds no edge outside (also on a
  // mesh that did not converge: a valence-4 vertex is a 4-ring in the carbon structure).
  spdlog::debug("valence defects: {} removed", remove_valence_defects(mesh, *projection_target, s.kn, s.emin, s.emax));
  EdgeStats after_loop = edge_stats(mesh, interval);
  if (after_loop.long_edges + after_loop.short_edges > 0) {
    // Edges neither the optimizer nor the stellar operations reach (a border vertex of valence 3 on a round border).
    // After the post-processing (4.6: the optimizer without projection) a change whose projected relaxation is
    // refused is relaxed in place too: onto an input rougher than the interval (a sphere with 4% radial noise) the
    // projection took the vertices back where the loop could not fit the interval, and 3 edges stayed outside where a
    // flip relaxed in place cleared them all.
    result.stuck_edges_cleared =
        clear_stuck_edges(mesh, *projection_target, s.kn, s.emin, s.emax, result.post_processed).cleared;
    spdlog::debug("stuck edges: {} changes kept", result.stuck_edges_cleared);
    if (result.stuck_edges_cleared > 0) after_loop = edge_stats(mesh, interval);
  }
  std::size_t outside = after_loop.long_edges + after_loop.short_edges;
  step_end(took.cleanup);
  if (restart_input && outside > 0) {
    spdlog::info("remesh: {} long and short edges left where the input had none: kept the input", outside);
    mesh = *restart_input;
    result.kept_input = true;
    outside = 0;  // the input has every edge inside
  }
  // Once every edge is inside: valence optimisation that keeps them inside (regularize in correct_valence.cpp),
  // then the feature snap and the surface fit, which keep them inside too.
  if (outside == 0) {
    spdlog::debug("regularize: {} flips", regularize(mesh, *projection_target, s.kn, s.emin, s.emax));
    step_end(took.regularize);
    // The steps below measure against the input: its tree is built once for all of them.
    const TriMesh& surface = input ? *input : *target;
    std::optional<triangle_tree::SurfaceTree> surface_tree;
    if (s.snap_features || s.flip_toward_input || s.fit_surface || s.minimax_fit) surface_tree.emplace(surface);
    const triangle_tree::SurfaceTree* tree = surface_tree ? &*surface_tree : nullptr;
    // Vertices onto the input points the surface cuts off, before the fit, which then keeps them there.
    SnapResult snap;
    double farthest_input = 0;  // the farthest interior input vertex, as the tip caps measured it
    if (s.snap_features) {
      snap = snap_to_features(mesh, surface, *projection_target, s.kn, s.emin, s.emax, s.snap_tolerance * s.emin,
                              tree);
      result.snapped = true;
      result.snapped_vertices = snap.snapped;
      result.inserted_vertices = snap.inserted;
      result.snap_max_before = snap.max_before;
      result.snap_max_after = snap.max_after;
      result.snapped_border_vertices = snap.border_snapped;
      result.snap_border_max_before = snap.border_max_before;
      result.snap_border_max_after = snap.border_max_after;
      const double caps_start = seconds();
      if (s.cap_tips) {
        const CapTipsResult caps = cap_tips(mesh, surface, *projection_target, s.kn, s.emin, s.emax,
                                            s.snap_tolerance * s.emin, snap.fixed, tree);
        result.capped_tips = caps.capped;
        farthest_input = caps.farthest;
        result.cap_vertices = caps.added;
        spdlog::debug("cap tips: {} of {} input vertices capped ({} tried), {} vertices added, {:.3f}s", caps.capped,
                      caps.candidates, caps.tries, caps.added, seconds() - caps_start);
      }
      step_end(took.snap);
      spdlog::debug("snap to features: {} of {} input vertices farther than {:.4f} snapped in {} rounds ({} moves "
                    "tried), farthest {:.4f} -> {:.4f}, {:.3f}s (with the tip caps {:.3f}s)",
                    snap.snapped, snap.candidates, s.snap_tolerance * s.emin, snap.rounds, snap.tries, snap.max_before,
                    snap.max_after, took.snap - (lap - caps_start), took.snap);
      if (snap.insertion_candidates > 0)
        spdlog::debug("snap to features, insertions: {} vertices inserted at {} of {} input vertices still farther "
                      "than {:.4f}, {:.3f}s", snap.inserted, snap.insertion_tries, snap.insertion_candidates,
                      s.snap_tolerance * s.emin, snap.insertion_seconds);
      if (snap.border_candidates > 0)
        spdlog::debug("snap to features, borders: {} of {} border vertices of the input farther than {:.4f} snapped in "
                      "{} rounds, farthest {:.4f} -> {:.4f}",
                      snap.border_snapped, snap.border_candidates, s.snap_tolerance * s.emin, snap.border_rounds,
                      snap.border_max_before, snap.border_max_after);
    }
    if (s.flip_toward_input) {
      const DataDependentFlips flips = data_dependent_flips(mesh, surface, s.emin, s.emax, s.snap_tolerance * s.emin,
                                                            projection_target.get(), s.kn,
                                                            snap.fixed.empty() ? nullptr : &snap.fixed, tree);
      result.data_dependent_flips = flips.flips;
      result.relaxed_flips = flips.relaxed_flips;
      step_end(took.flips);
      spdlog::debug("data-dependent flips: {} of {} edges near faces farther than {:.4f}, {} of {} more with the "
                    "vertices around relaxed, farthest face {:.4f} -> {:.4f}, {:.3f}s",
                    flips.flips, flips.candidates, s.snap_tolerance * s.emin, flips.relaxed_flips, flips.relaxed_tries,
                    flips.max_before, flips.max_after, took.flips);
    }
    // The faces the flips left farthest from the input get a vertex of their own (its time counted in the flips').
    if (s.snap_features && s.cap_faces) {
      const CapTipsResult caps = cap_far_faces(mesh, surface, *projection_target, s.kn, s.emin, s.emax,
                                               s.snap_tolerance * s.emin, snap.fixed, farthest_input, tree);
      result.capped_faces = caps.capped;
      result.face_cap_vertices = caps.added;
      double caps_seconds = 0;
      step_end(caps_seconds);
      took.flips += caps_seconds;
      spdlog::debug("face caps: {} of {} faces capped ({} tried), {} vertices added, {:.3f}s", caps.capped,
                    caps.candidates, caps.tries, caps.added, caps_seconds);
    }
    // The vertices the snap put on features stay there in the fit and the minimax fit.
    const std::vector<char>* snapped = snap.fixed.empty() ? nullptr : &snap.fixed;
    if (s.fit_surface) {
      SurfaceFitSettings fit_settings;
      fit_settings.measure_input_after = spdlog::should_log(spdlog::level::debug);  // (the debug line's figure only)
      const SurfaceFitResult fit = fit_to_surface(mesh, surface, s.emin, s.emax, fit_settings, snapped, tree);
      result.fitted = true;
      result.fit_rms_before = fit.rms_before;
      result.fit_rms_after = fit.rms_after;
      spdlog::debug("surface fit: RMS distance {:.4f} -> {:.4f}, the input's {:.4f} -> {:.4f}, {} CG iterations, {} "
                    "settling sweeps, {} halvings", fit.rms_before, fit.rms_after, fit.input_rms_before,
                    fit.input_rms_after, fit.solver_iterations, fit.settle_sweeps, fit.limited);
      step_end(took.surface_fit);
    }
    if (s.minimax_fit) {
      MinimaxFitSettings minimax_settings;
      minimax_settings.tolerance = s.snap_tolerance * s.emin;
      const MinimaxFitResult minimax =
          minimax_fit(mesh, surface, s.emin, s.emax, minimax_settings, snapped, tree);
      result.minimax_fitted = true;
      result.minimax_max_before = minimax.max_before;
      result.minimax_max_after = minimax.max_after;
      result.minimax_moves = minimax.moves;
      result.minimax_wide_moves = minimax.wide_moves;
      step_end(took.minimax_fit);
      spdlog::debug("minimax fit: largest sampled distance {:.4f} -> {:.4f}, {} moves at {} spots, {:.3f}s "
                    "(scans {:.3f}s)", minimax.max_before, minimax.max_after, minimax.moves, minimax.spots,
                    took.minimax_fit, minimax.scan_seconds);
    }
  }
  // The topology guard: a final mesh of another surface type is replaced by the best valid one.
  if (const std::optional<Topology> changed = enforce_surface_type(mesh, best)) {
    result.topology_violation = true;
    result.changed = *changed;
    spdlog::error("remesh changed the surface type (genus {} -> {}, components {} -> {}, borders {} -> {}); "
                  "kept the best mesh with the input's surface type",
                  result.before.genus, changed->genus, result.before.components, changed->components,
                  result.before.boundary_loops, changed->boundary_loops);
  }
  result.rejected_best = best.rejected();
  forget_projection(mesh);
  mesh.update_normals();
  record_final_figures(result, mesh, interval);
  // Started from a post-processed coarse level and left with more than a few edges outside: the level was no start
  // after all (a feature too thin for it, such as a torus tube of radius 0.6 at [0.8, 1.2]: 24 edges outside). The
  // input is remeshed directly, and the better of the two kept. (p > 0 replaces *target: no retry.)
  if (from_post_processed && s.p == 0 &&
      result.long_edges + result.short_edges > few_edges(mesh)) {
    spdlog::info("{} long and {} short edges left after the start from a post-processed coarse level: remeshing the "
                 "input at [{:.4f}, {:.4f}] directly",
                 result.long_edges, result.short_edges, s.emin, s.emax);
    TriMesh again = *target;
    RemeshSettings direct = s;
    direct.coarse_levels = 0;
    direct.measure_cut_off = false;  // measured below on the mesh kept
    RemeshResult r = remesh(again, direct);
    if (r.long_edges + r.short_edges < result.long_edges + result.short_edges) {
      r.coarse_iterations += result.coarse_iterations + result.iterations;
      r.log.insert(r.log.begin(), result.log.begin(), result.log.end());
      r.before = result.before;
      mesh = std::move(again);
      result = std::move(r);
    }
  }
  if (s.measure_cut_off) {
    const double t0 = seconds();
    const FarthestInputVertex far = farthest_input_vertex(mesh, input ? *input : *target);
    spdlog::debug("farthest input vertex from the result: {:.4f}, {:.3f}s", far.distance, seconds() - t0);
    result.farthest_input = far.distance;
    result.farthest_input_point = far.point;
    result.cut_off = result.farthest_input > s.emax;
    if (result.cut_off) {
      const Vec3& q = result.farthest_input_point;
      spdlog::warn("remesh: the input point ({:.4g}, {:.4g}, {:.4g}) is {:.4g} from the remeshed surface ({:.1f} "
                   "emax): a part of the input was cut off (as a rule a slit, fin or rim narrower than about emin, "
                   "{:.4g}, which the iterations bridge or pull in)",
                   q[0], q[1], q[2], result.farthest_input, result.farthest_input / s.emax, s.emin);
    }
  }
  result.seconds = seconds();
  took.other = std::max(0.0, result.seconds - took.iterations - took.cleanup - took.regularize - took.snap -
                                 took.flips - took.surface_fit - took.minimax_fit);  // (a direct remesh's, if kept)
  return result;
}

nlohmann::json to_json(const RemeshResult& r) {
  nlohmann::json log = nlohmann::json::array();
  for (const auto& l : r.log)
    log.push_back({{"iteration", l.iteration},
                   {"long", l.long_edges},
                   {"short", l.short_edges},
                   {"percent_regular", l.percent_regular},
                   {"mean", l.mean},
                   {"std", l.std},
                   {"seconds", l.seconds},
                   {"nonlinear", l.nonlinear},
                   {"l", l.l},
                   {"level", l.level}});
  nlohmann::json j = {{"converged", r.converged},
          {"iterations", r.iterations},
          {"coarse_levels", r.coarse_levels},
          {"coarse_iterations", r.coarse_iterations},
          {"post_processed", r.post_processed},
          {"diverged", r.diverged},
          {"vanished", r.vanished},
          {"stalled", r.stalled},
          {"kept_input", r.kept_input},
          {"stuck_edges_cleared", r.stuck_edges_cleared},
          {"bisected_vertices", r.bisected_vertices},
          {"long", r.long_edges},
          {"short", r.short_edges},
          {"percent_regular", r.percent_regular},
          {"percent_eval_gt1", r.percent_eval_gt1},
          {"seconds", r.seconds},
          {"topology_before", to_json(r.before)},
          {"topology_after", to_json(r.after)},
          {"topology_kept", r.before.same_type(r.after)},
          {"topology_violation", r.topology_violation},
          {"rejected_best", r.rejected_best},
          {"fitted", r.fitted},
          {"fit_rms_before", r.fit_rms_before},
          {"fit_rms_after", r.fit_rms_after},
          {"minimax_fitted", r.minimax_fitted},
          {"minimax_max_before", r.minimax_max_before},
          {"minimax_max_after", r.minimax_max_after},
          {"minimax_moves", r.minimax_moves},
          {"minimax_wide_moves", r.minimax_wide_moves},
          {"snapped", r.snapped},
          {"snapped_vertices", r.snapped_vertices},
          {"inserted_vertices", r.inserted_vertices},
          {"capped_tips", r.capped_tips},
          {"cap_vertices", r.cap_vertices},
          {"capped_faces", r.capped_faces},
          {"face_cap_vertices", r.face_cap_vertices},
          {"snap_max_before", r.snap_max_before},
          {"snap_max_after", r.snap_max_after},
          {"snapped_border_vertices", r.snapped_border_vertices},
          {"snap_border_max_before", r.snap_border_max_before},
          {"snap_border_max_after", r.snap_border_max_after},
          {"data_dependent_flips", r.data_dependent_flips},
          {"relaxed_flips", r.relaxed_flips},
          {"farthest_input", r.farthest_input},
          {"farthest_input_point", {r.farthest_input_point[0], r.farthest_input_point[1], r.farthest_input_point[2]}},
          {"cut_off", r.cut_off},
          {"step_seconds", {{"iterations", r.step_seconds.iterations},
                            {"cleanup", r.step_seconds.cleanup},
                            {"regularize", r.step_seconds.regularize},
                            {"snap", r.step_seconds.snap},
                            {"flips", r.step_seconds.flips},
                            {"surface_fit", r.step_seconds.surface_fit},
                            {"minimax_fit", r.step_seconds.minimax_fit},
                            {"other", r.step_seconds.other}}},
          {"log", log}};
  if (r.topology_violation) j["topology_changed"] = to_json(r.changed);
  return j;
}

}  // namespace carbonmesh
