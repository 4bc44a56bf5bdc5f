// `carbonmesh remesh IN OUT --emin A --emax B [--iterations 150] [--kl 2] [--kn 2] [--p 0] [--l 0.5]
//  [--weights mean-value|shape-preserving] [--no-fit] [--no-snap] [--snap-tolerance t] [--coarse-levels k]
//  [--log convergence.csv] [--json] [--repair]`
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "carbonmesh/remesh/atomic_file.hpp"
#include "carbonmesh/remesh/components.hpp"
#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/io.hpp"
#include "carbonmesh/remesh/remesher.hpp"
#include "commands.hpp"
#include "number_checks.hpp"
#include "surface_checks.hpp"

namespace carbonmesh::cli {
namespace {

std::string topology_text(const Topology& t) {
  return fmt::format("genus {} components {} borders {}", t.genus, t.components, t.boundary_loops);
}

}  // namespace

void add_remesh_command(CLI::App& app, Action& action) {
  struct Options {
    std::string in, out, log;
    double emin = 0, emax = 0;
    int iterations = 150, kl = 2, kn = 2, p = 0, coarse_levels = 0, stall_limit = RemeshSettings{}.stall_limit;
    double l = 0.5, snap_tolerance = RemeshSettings{}.snap_tolerance;
    ParametrizationWeights weights = ParametrizationWeights::MeanValue;
    bool json = false, repair = false, no_fit = false, no_minimax = false, no_snap = false, no_flips = false;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("remesh", "remesh so that every edge length lies in [emin, emax] (Algorithm 1)");
  cmd->add_option("in", opt->in, "input mesh (.off .obj .ply .stl)")->required();
  cmd->add_option("out", opt->out, "output mesh (.off .obj .ply .stl)")->required();
  cmd->add_option("--emin", opt->emin, "lower bound of the edge interval (mesh units)")->required();
  cmd->add_option("--emax", opt->emax, "upper bound of the edge interval (mesh units)")->required();
  cmd->add_option("--iterations,-n", opt->iterations, "maximum number of iterations (n)")->default_val(150)->check(non_negative_number());
  cmd->add_option("--kl", opt->kl, "star number of the low-pass filter")->default_val(2)->check(positive_number());
  cmd->add_option("--kn", opt->kn, "star number of the nonlinear optimizer")->default_val(2)->check(positive_number());
  cmd->add_option("--p", opt->p, "replace the projection mesh every p iterations (0: never)")->default_val(0)->check(non_negative_number());
  cmd->add_option("--l", opt->l,
                  "percent of long+short edges at or below which the nonlinear optimizer runs (doubled once the "
                  "low-pass phase finds no new low in 5 iterations)")
      ->default_val(0.5)->check(non_negative_number());
  cmd->add_option("--stall-limit", opt->stall_limit,
                  "stop after this many iterations without a better mesh and post-process the best one (0: never)")
      ->default_val(RemeshSettings{}.stall_limit)->check(non_negative_number());
  const std::map<std::string, ParametrizationWeights> weights{{"mean-value", ParametrizationWeights::MeanValue},
                                                             {"shape-preserving", ParametrizationWeights::ShapePreserving}};
  cmd->add_option("--weights", opt->weights, "parametrization weights: mean-value or shape-preserving")
      ->transform(CLI::CheckedTransformer(weights, CLI::ignore_case))->default_str("mean-value");
  cmd->add_option("--coarse-levels", opt->coarse_levels,
                  "remesh at 2^k times the interval first, then halve every edge k times (fewer valence defects; "
                  "for fine intervals on large surfaces)")
      ->default_val(0)
      ->check(non_negative_number());
  cmd->add_flag("--no-fit", opt->no_fit, "skip the final least-squares fit to the input (every vertex stays on the input, as in the dissertation; default: fit)");
  cmd->add_flag("--no-minimax", opt->no_minimax, "skip moving the vertices where the remeshed surface and the input are farthest apart so that the largest distance falls (default: move)");
  cmd->add_flag("--no-snap", opt->no_snap, "skip moving vertices onto input points the remeshed surface cuts off (ear rims, tips, grooves; default: snap)");
  cmd->add_option("--snap-tolerance", opt->snap_tolerance,
                  "distance, as a fraction of emin, beyond which an input point counts as cut off by the remeshed "
                  "surface: the snap, the flips toward the input, the caps and the minimax fit work on the points "
                  "and faces farther than it (smaller: nearer the input, slower)")
      ->default_val(RemeshSettings{}.snap_tolerance)->check(non_negative_number());
  cmd->add_flag("--no-flips", opt->no_flips, "skip flipping edges whose faces bridge a groove or cut a ridge of the input where the other diagonal follows it, also those whose other diagonal needs the vertices around relaxed (default: flip)");
  cmd->add_option("--log", opt->log, "write the convergence (one line per iteration) as CSV (default: none)");
  cmd->add_flag("--json", opt->json, "final summary as one JSON object instead of text");
  cmd->add_flag("--repair", opt->repair, "merge duplicate and nearly coincident vertices, orient faces alike, split non-manifold edges and vertices and faces at T-junctions, drop degenerate/duplicate faces");
  cmd->callback([&action, opt] {
    action = [opt]() -> int {
      if (!(opt->emin > 0) || !std::isfinite(opt->emin))
        throw InputError(fmt::format("--emin {} must be a positive number", opt->emin));
      if (!(opt->emax > 0) || !std::isfinite(opt->emax))
        throw InputError(fmt::format("--emax {} must be a positive number", opt->emax));
      if (opt->emin >= opt->emax)
        throw InputError(fmt::format("--emin {} must be smaller than --emax {}", opt->emin, opt->emax));
      if (opt->emin > 2.0 / 3.0 * opt->emax)
        spdlog::warn("interval [{}, {}] is too tight: emin > 2/3 emax (dissertation Ineq 5.1), long and short edges may remain",
                     opt->emin, opt->emax);
      LoadSettings load;
      load.repair = opt->repair;
      TriMesh mesh = load_mesh(opt->in, load);
      // Components with less area than four triangles of the interval (a tetrahedron of edge emin, the smallest
      // closed surface whose edges can all be inside): debris of a scan, a corner a clipping box cut off. Kept, their
      // edges stay outside (the loop cannot grow them), and the whole mesh then goes without the regularisation,
      // the snap and the fits, which start once every edge is inside. The largest component always stays.
      const double smallest_surface = std::sqrt(3.0) * opt->emin * opt->emin;
      const SmallComponents debris = remove_small_components(mesh, smallest_surface);
      if (debris.removed > 0)
        spdlog::warn("{}: removed {} component{} with less area than four triangles of the interval ({:.4g}): {} "
                     "faces, area {:.4g} in all", opt->in, debris.removed, debris.removed == 1 ? "" : "s",
                     smallest_surface, debris.faces, debris.area);
      const SelfIntersections input_crossings = check_input_self_intersections(mesh, opt->in);
      RemeshSettings settings;
      settings.emin = opt->emin;
      settings.emax = opt->emax;
      settings.iterations = opt->iterations;
      settings.kl = opt->kl;
      settings.kn = opt->kn;
      settings.p = opt->p;
      settings.l = opt->l;
      settings.stall_limit = opt->stall_limit;
      settings.weights = opt->weights;
      settings.fit_surface = !opt->no_fit;
      settings.minimax_fit = !opt->no_minimax;
      settings.snap_features = !opt->no_snap;
      settings.flip_toward_input = !opt->no_flips;
      settings.snap_tolerance = opt->snap_tolerance;
      settings.coarse_levels = opt->coarse_levels;
      std::ostringstream csv;
      csv << "iteration,long,short,percent_regular,mean,std,seconds,nonlinear,level,l\n";
      settings.on_iteration = [&csv](const IterationLog& l) {
        spdlog::info("{}iteration {:3d}  long {:6d}  short {:6d}  regular {:6.2f}%  mean {:.4f}  std {:.4f}  {:.2f}s{}",
                     l.level > 0 ? fmt::format("level {} ", l.level) : "", l.iteration, l.long_edges, l.short_edges, l.percent_regular, l.mean, l.std, l.seconds,
                     l.nonlinear ? "  (nonlinear)" : "");
        csv << fmt::format("{},{},{},{:.4f},{:.6f},{:.6f},{:.3f},{},{},{}\n", l.iteration, l.long_edges, l.short_edges,
                           l.percent_regular, l.mean, l.std, l.seconds, l.nonlinear ? 1 : 0, l.level, l.l);
      };
      RemeshResult result;
      try {
        result = remesh(mesh, settings);
      } catch (const InputError& e) {  // e.g. an interval needing too many triangles: name the file
        throw InputError(opt->in + ": " + e.what());
      }
      save_mesh(mesh, opt->out);
      mesh.garbage_collection();  // the face indices of the file written
      const SelfIntersections crossings =
          check_remesh_self_intersections(self_intersections(mesh), opt->in, opt->out);
      if (!opt->log.empty())
        write_atomically(opt->log, [&csv](const std::filesystem::path& tmp) {
          std::ofstream file(tmp);
          file << csv.str();
          if (!file) throw InputError(fmt::format("cannot write {}", tmp.string()));
        });
      const RemeshStepSeconds& took = result.step_seconds;
      spdlog::info("remesh time: iterations {:.3f}s, cleanup {:.3f}s, regularize {:.3f}s, snap {:.3f}s, "
                   "flips {:.3f}s, surface fit {:.3f}s, minimax fit {:.3f}s, other {:.3f}s",
                   took.iterations, took.cleanup, took.regularize, took.snap, took.flips, took.surface_fit,
                   took.minimax_fit, took.other);
      if (opt->json) {
        nlohmann::json j = to_json(result);
        j["input"] = opt->in;
        j["output"] = opt->out;
        j["emin"] = opt->emin;
        j["emax"] = opt->emax;
        j["snap_tolerance"] = opt->snap_tolerance;
        j["removed_components"] = to_json(debris);
        j["input_self_intersections"] = to_json(input_crossings);
        j["self_intersections"] = to_json(crossings);
        std::cout << j.dump(2) << "\n";
      } else {
        std::cout << fmt::format(
            "{} -> {}\nlong {}  short {}  regular {:.2f}%  eval>1 {:.2f}%  iterations {}{}{}  {:.2f}s\n"
            "before: {}\nafter:  {}{}\n",
            opt->in, opt->out, result.long_edges, result.short_edges, result.percent_regular,
            result.percent_eval_gt1, result.iterations,
            result.coarse_iterations > 0 ? fmt::format(" (+{} at {} coarse level{})", result.coarse_iterations,
                                                       result.coarse_levels, result.coarse_levels == 1 ? "" : "s")
                                         : "",
            result.post_processed ? " (post-processed)" : "",
            result.seconds, topology_text(result.before), topology_text(result.after),
            result.before.same_type(result.after) ? "" : "  (SURFACE TYPE CHANGED)");
        if (result.snapped)
          std::cout << fmt::format("feature snap: {} vertices moved onto the input, {} inserted, farthest input "
                                   "vertex {:.4f} -> {:.4f}\n",
                                   result.snapped_vertices, result.inserted_vertices, result.snap_max_before,
                                   result.snap_max_after);
        if (result.capped_tips > 0)
          std::cout << fmt::format("tip caps: {} input vertices given a vertex with the cap around rebuilt ({:+} "
                                   "vertices)\n",
                                   result.capped_tips, result.cap_vertices);
        if (result.capped_faces > 0)
          std::cout << fmt::format("face caps: {} faces farthest from the input given a vertex with the cap around "
                                   "rebuilt ({:+} vertices)\n",
                                   result.capped_faces, result.face_cap_vertices);
        if (result.snapped && result.snap_border_max_before > 0)
          std::cout << fmt::format("feature snap, borders: {} border vertices moved onto the input's border, farthest "
                                   "border vertex {:.4f} -> {:.4f}\n",
                                   result.snapped_border_vertices, result.snap_border_max_before,
                                   result.snap_border_max_after);
        if (settings.flip_toward_input && result.converged)
          std::cout << fmt::format("data-dependent flips: {} edges flipped toward the input, {} more with the vertices "
                                   "around relaxed\n",
                                   result.data_dependent_flips, result.relaxed_flips);
        if (result.fitted)
          std::cout << fmt::format("surface fit: RMS distance to the input {:.4f} -> {:.4f}\n", result.fit_rms_before,
                                   result.fit_rms_after);
        if (result.minimax_fitted)
          std::cout << fmt::format("minimax fit: largest sampled distance to the input {:.4f} -> {:.4f} ({} moves{})\n",
                                   result.minimax_max_before, result.minimax_max_after, result.minimax_moves,
                                   result.minimax_wide_moves == 0
                                       ? std::string()
                                       : fmt::format(", {} in the farthest region's wider search",
                                                     result.minimax_wide_moves));
      }
      if (!result.converged)
        spdlog::warn("{} long and {} short edges remain outside [{}, {}]", result.long_edges, result.short_edges,
                     opt->emin, opt->emax);
      if (result.topology_violation) {
        std::cerr << fmt::format("carbonmesh: error: {}: remeshing changed the surface type ({} -> {}); wrote the "
                                 "best mesh with the input's surface type to {}\n",
                                 opt->in, topology_text(result.before), topology_text(result.changed), opt->out);
        return kExitTopologyViolation;
      }
      return 0;
    };
  });
}

}  // namespace carbonmesh::cli
