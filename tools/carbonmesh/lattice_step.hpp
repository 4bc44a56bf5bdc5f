#pragma once
// `build --lattice`: a flat input cut from a triangular lattice of edge a = sqrt(3) b instead of remeshed
// (carbonmesh/remesh/lattice_sheet.hpp), and the hint `build` gives for a flat input without it.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "carbonmesh/remesh/components.hpp"
#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/lattice_sheet.hpp"
#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/remesher.hpp"

namespace carbonmesh::cli {

// A surface is flat when no vertex is farther from the best-fit plane than this share of the lattice edge.
constexpr double kFlatShare = 1e-3;

inline bool is_flat(const Flatness& plane, double edge) { return plane.distance <= kFlatShare * edge; }

struct LatticeStep {
  RemeshResult result;  // the figures a remesh would give (0 iterations)
  nlohmann::json json;  // summary.json's "lattice"
};

// Replaces the flat `mesh` by the lattice cut to its outline (pieces smaller than `min_area` dropped). Throws
// InputError naming `source` if the surface is not flat or the cut keeps nothing.
inline LatticeStep cut_lattice(TriMesh& mesh, const std::string& source, double edge, double turn_deg,
                               const EdgeInterval& interval, double min_area) {
  const auto start = std::chrono::steady_clock::now();
  const Flatness plane = flatness(mesh);
  if (!is_flat(plane, edge))
    throw InputError(fmt::format("{}: --lattice needs a flat surface, and a vertex is {:.4g} A from the plane that "
                                 "fits it best (more than {:.2g} A)",
                                 source, plane.distance, kFlatShare * edge));
  LatticeStep step;
  step.result.before = topology(mesh);
  LatticeSheet sheet;
  try {
    sheet = lattice_sheet(mesh, plane, edge, turn_deg);
  } catch (const InputError& e) {
    throw InputError(source + ": " + e.what());
  }
  mesh = std::move(sheet.mesh);
  const SmallComponents pieces = remove_small_components(mesh, min_area);
  if (mesh.n_faces() == 0)
    throw InputError(fmt::format("{}: no lattice triangle of edge {:.4f} A fits inside the outline; build it larger "
                                 "(--atoms, --size)",
                                 source, edge));
  RemeshResult& r = step.result;
  record_final_figures(r, mesh, interval);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  spdlog::info("{}: cut from a triangular lattice of edge {:.4f} A, turned {:g} degrees from its longest straight side "
               "({}): {} vertices, {} triangles{}",
               source, edge, turn_deg, std::fmod(std::abs(turn_deg), 60.0) == 0 ? "a zigzag edge there"
                                       : std::fmod(std::abs(turn_deg), 60.0) == 30 ? "an armchair edge there"
                                                                                  : "a chiral edge there",
               mesh.n_vertices(), mesh.n_faces(),
               sheet.dropped > 0 ? fmt::format(", {} touching the rest at one corner only left out", sheet.dropped)
                                 : std::string());
  if (!r.before.same_type(r.after))
    spdlog::warn("{}: the lattice cut has genus {}, {} components and {} borders where the input has {}, {} and {}: "
                 "a neck or hole narrower than about one lattice edge ({:.3f} A) was cut or filled",
                 source, r.after.genus, r.after.components, r.after.boundary_loops, r.before.genus,
                 r.before.components, r.before.boundary_loops, edge);
  step.json = {{"edge", edge},
               {"turn_deg", turn_deg},
               {"angle_deg", sheet.angle_deg},
               {"flatness", plane.distance},
               {"dropped_triangles", sheet.dropped},
               {"removed_pieces", to_json(pieces)}};
  return step;
}

}  // namespace carbonmesh::cli
