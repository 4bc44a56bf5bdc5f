// `carbonmesh stats MESH [--emin A --emax B] [--ref REF] [--json]`
#include <fmt/format.h>

#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/hausdorff.hpp"
#include "carbonmesh/remesh/io.hpp"
#include "carbonmesh/remesh/metrics.hpp"
#include "commands.hpp"
#include "number_checks.hpp"

namespace carbonmesh::cli {

void add_stats_command(CLI::App& app, Action& action) {
  struct Options {
    std::string mesh, ref;
    std::optional<double> emin, emax;
    bool json = false, repair = false;
    std::size_t samples = 200000;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("stats", "mesh metrics: topology, edge lengths, valence, angles, self-intersections, Hausdorff");
  cmd->add_option("mesh", opt->mesh, "input mesh (.off .obj .ply .stl)")->required();
  cmd->add_option("--emin", opt->emin, "lower bound of the edge interval, mesh units (edges shorter are 'short'; default: none, no interval counts)");
  cmd->add_option("--emax", opt->emax, "upper bound of the edge interval, mesh units (edges longer are 'long'; default: none)");
  cmd->add_option("--ref", opt->ref, "reference mesh for the symmetric Hausdorff distance, in mesh units (default: none, no distance)");
  cmd->add_option("--samples", opt->samples,
                  fmt::format("Hausdorff samples per surface for the RMS (area-uniform; the max is bracketed within {:g} "
                              "over every point of both surfaces)",
                              HausdorffSettings{}.max_tolerance))
      ->default_val(200000)
      ->check(positive_number());
  cmd->add_flag("--json", opt->json, "one JSON object instead of text");
  cmd->add_flag("--repair", opt->repair, "merge duplicate and nearly coincident vertices, orient faces alike, split non-manifold edges and vertices and faces at T-junctions, drop degenerate/duplicate faces");
  cmd->callback([&action, opt] {
    action = [opt]() -> int {
      EdgeInterval interval;
      if (opt->emin) interval.emin = *opt->emin;
      if (opt->emax) interval.emax = *opt->emax;
      if (opt->emin && *opt->emin <= 0) throw InputError(fmt::format("--emin {} must be positive", *opt->emin));
      if (opt->emin && opt->emax && *opt->emin >= *opt->emax)
        throw InputError(fmt::format("--emin {} must be smaller than --emax {}", *opt->emin, *opt->emax));
      LoadSettings load;
      load.repair = opt->repair;
      const TriMesh mesh = load_mesh(opt->mesh, load);
      const MeshStats stats = mesh_stats(mesh, interval);
      std::optional<HausdorffResult> hausdorff;
      if (!opt->ref.empty()) {
        const TriMesh ref = load_mesh(opt->ref, load);
        HausdorffSettings hs;
        hs.samples = opt->samples;
        hausdorff = hausdorff_distance(mesh, ref, hs);
      }
      if (opt->json) {
        nlohmann::json j = to_json(stats);
        j["file"] = opt->mesh;
        if (hausdorff) {
          j["hausdorff"] = to_json(*hausdorff);
          j["hausdorff"]["reference"] = opt->ref;
        }
        std::cout << j.dump(2) << "\n";
      } else {
        std::cout << opt->mesh << "\n" << to_text(stats);
        if (hausdorff)
          std::cout << fmt::format("hausdorff to {}: max {:.6g} (at most {:.6g})  rms {:.6g}  ({} samples a side "
                                   "for the rms)\n",
                                   opt->ref, hausdorff->max, hausdorff->max_bound, hausdorff->rms,
                                   hausdorff->samples_per_side);
      }
      return 0;
    };
  });
}

}  // namespace carbonmesh::cli
