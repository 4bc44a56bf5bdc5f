// `build --lattice`: a flat input cut from a triangular lattice of edge a = sqrt(3) b, a cylindrical one from that
// lattice rolled into a tube, a sphere replaced by that lattice folded onto an icosahedron, a capsule by that
// icosahedron lengthened into a capped tube, instead of remeshed (carbonmesh/remesh/lattice_sheet.hpp,
// lattice_tube.hpp, lattice_sphere.hpp, lattice_capsule.hpp), and the hint `build` gives for such an input without it.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "carbonmesh/remesh/components.hpp"
#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/lattice_capsule.hpp"
#include "carbonmesh/remesh/lattice_sheet.hpp"
#include "carbonmesh/remesh/lattice_sphere.hpp"
#include "carbonmesh/remesh/lattice_tube.hpp"
#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/remesher.hpp"
#include "carbonmesh/remesh/shapes.hpp"

namespace carbonmesh::cli {

// A surface is flat when no vertex is farther from the best-fit plane than this share of the lattice edge.
constexpr double kFlatShare = 1e-3;

inline bool is_flat(const Flatness& plane, double edge) { return plane.distance <= kFlatShare * edge; }

// A surface is cylindrical when it has a border (a closed surface cannot lie on a cylinder: checked before the fit),
// no vertex is farther from the cylinder that fits it best than kFlatShare of the lattice edge, and that cylinder's
// circumference is at most kMaxTubeEdges lattice edges (beyond, the surface is as good as flat and the chiral
// indices run past 10^8).
constexpr double kMaxTubeEdges = 1e8;

inline bool has_border(const TriMesh& mesh) {
  return std::any_of(mesh.halfedges_begin(), mesh.halfedges_end(), [&](auto h) { return mesh.is_boundary(h); });
}

inline bool is_cylinder(const Cylinder& cylinder, double edge) {
  return cylinder.distance <= kFlatShare * edge && 2 * std::acos(-1.0) * cylinder.radius <= kMaxTubeEdges * edge;
}

// A closed surface is a sphere when no vertex is farther from the sphere that fits it best than kFlatShare of the
// lattice edge, its faces cover at least kMinSphereCover of that sphere's area, and it has one component and genus 0
// (checked by the caller: the topology of a mesh whose vertices lie on one sphere can still be another). The corners
// of a cube or an icosahedron lie on a sphere too, but their faces cover 64% and 76% of its area; an icosphere of 80
// faces covers 93%, of 320 faces 98%.
constexpr double kMinSphereCover = 0.9;

inline double sphere_cover(const TriMesh& mesh, const Sphere& sphere) {
  return surface_area(mesh) / (4 * std::acos(-1.0) * sphere.radius * sphere.radius);
}

// Every vertex within kFlatShare of the lattice edge from the fitted sphere or capsule (`distance`), the faces covering
// at least kMinSphereCover of its area (`cover`: their share).
inline bool fits_closed_shape(double distance, double cover, double edge) {
  return distance <= kFlatShare * edge && cover >= kMinSphereCover;
}

inline bool is_one_closed_genus0(const TriMesh& mesh) {
  const Topology t = topology(mesh);
  return t.boundary_loops == 0 && t.genus == 0 && t.components == 1;
}

inline bool is_whole_sphere(const TriMesh& mesh, double edge) {
  if (!is_one_closed_genus0(mesh)) return false;
  const Sphere sphere = sphere_fit(mesh);
  return fits_closed_shape(sphere.distance, sphere_cover(mesh, sphere), edge);
}

// A closed surface that is no sphere is a capsule by the same rules, with the capsule that fits it best.
inline bool is_whole_capsule(const TriMesh& mesh, double edge) {
  if (!is_one_closed_genus0(mesh)) return false;
  const Capsule capsule = capsule_fit(mesh);
  return fits_closed_shape(capsule.distance, surface_area(mesh) / capsule_area(capsule), edge);
}

// --chirality N,M is refused where the tube's (or the fullerene's) radius would be more than this many times the
// input's, or less than its inverse: the input is unrolled to the tube's circumference (or replaced by the fullerene),
// and that far off it is not the input's shape.
constexpr double kMaxTubeRatio = 2.0;

// What the user asked of the lattice: a flat sheet's turn, a tube's chiral indices (each default when not given).
struct LatticeOptions {
  std::optional<double> turn_deg;
  std::optional<Chirality> chirality;
};

struct LatticeStep {
  RemeshResult result;  // the figures a remesh would give (0 iterations)
  nlohmann::json json;  // summary.json's "lattice"
  std::optional<TriMesh> surface;  // a tube's: its cylinder, a fullerene's: itself, for the atoms to stay on
};

namespace detail {

inline std::string edge_kind(double angle_deg) {
  const double turn = std::fmod(std::abs(angle_deg), 60.0);
  return turn == 0 ? "zigzag" : turn == 30 ? "armchair" : "chiral";
}

// f(), its InputError prefixed with the input's name.
template <typename F>
auto naming_input(const std::string& source, F&& f) {
  try {
    return f();
  } catch (const InputError& e) {
    throw InputError(source + ": " + e.what());
  }
}

inline std::string with_article(const std::string& word) { return (word.front() == 'a' ? "an " : "a ") + word; }

// The end of a cut's log line: the triangles left out where they touched the rest at one corner only, if any.
inline std::string dropped_note(std::size_t dropped) {
  return dropped > 0 ? fmt::format(", {} touching the rest at one corner only left out", dropped) : std::string();
}

// Refuses --lattice-turn on a surface that is no sheet (`what`: which it is, and what sets its lattice instead).
inline void refuse_turn(const LatticeOptions& options, const std::string& source, const std::string& what) {
  if (options.turn_deg)
    throw InputError(fmt::format("{}: --lattice-turn turns a sheet's lattice, and this surface is {}", source, what));
}

// Refuses indices asked for (`what`: "tube" or "fullerene") whose radius is more than kMaxTubeRatio times the
// input's, or less than its inverse (`ratio`: the lattice's radius over the input's).
inline void check_asked_radius(const std::string& source, const std::string& what, std::array<int, 2> asked,
                               std::array<int, 2> nearest, double ratio, double input_radius) {
  if (ratio > kMaxTubeRatio || ratio < 1 / kMaxTubeRatio)
    throw InputError(fmt::format("{}: the ({}, {}) {}'s radius {:.4f} A is {:.3g} times the input's {:.4f} A (more "
                                 "than {:g} times either way): the indices nearest the input's radius are ({}, {}), "
                                 "or scale the input by {:.4g} to fit the {} (--scale, --size, --atoms)",
                                 source, asked[0], asked[1], what, ratio * input_radius, ratio, input_radius,
                                 kMaxTubeRatio, nearest[0], nearest[1], ratio, what));
}

// Warns where the lattice (`what`: "(5, 5) tube", "C1580 fullerene") has a radius more than 5% off the input's.
inline void warn_radius_off(const std::string& source, const std::string& what, double radius, double input_radius) {
  if (std::abs(radius - input_radius) > 0.05 * input_radius)
    spdlog::warn("{}: the {}'s radius {:.4f} A is {:.0f}% off the input's {:.4f} A: the atoms follow the {}", source,
                 what, radius, 100 * (radius - input_radius) / input_radius, input_radius,
                 what.substr(what.rfind(' ') + 1));
}

// A flat `mesh` replaced by the lattice cut to its outline; summary.json's "lattice".
inline nlohmann::json cut_sheet(TriMesh& mesh, const std::string& source, const Flatness& plane, double edge,
                                const LatticeOptions& options) {
  if (options.chirality)
    throw InputError(fmt::format("{}: --chirality rolls the lattice onto a cylindrical surface, and this one is flat "
                                 "(--lattice-turn turns a flat sheet's lattice)",
                                 source));
  const double turn_deg = options.turn_deg.value_or(0.0);
  LatticeSheet sheet = naming_input(source, [&] { return lattice_sheet(mesh, plane, edge, turn_deg); });
  mesh = std::move(sheet.mesh);
  spdlog::info("{}: cut from a triangular lattice of edge {:.4f} A, turned {:g} degrees from its longest straight side "
               "({} edge there): {} vertices, {} triangles{}",
               source, edge, turn_deg, with_article(edge_kind(turn_deg)), mesh.n_vertices(), mesh.n_faces(),
               dropped_note(sheet.dropped));
  return {{"kind", "sheet"},
          {"edge", edge},
          {"turn_deg", turn_deg},
          {"angle_deg", sheet.angle_deg},
          {"flatness", plane.distance},
          {"dropped_triangles", sheet.dropped}};
}

// A cylindrical `mesh` replaced by the rolled lattice cut to its outline, `surface` by the tube's cylinder;
// summary.json's "lattice".
inline nlohmann::json cut_tube(TriMesh& mesh, std::optional<TriMesh>& surface, const std::string& source,
                               const Cylinder& cylinder, double edge, const LatticeOptions& options) {
  refuse_turn(options, source, "a tube (it goes around its axis: --chirality N,M sets its lattice)");
  const Chirality nearest = nearest_chirality(cylinder.radius, edge);
  const Chirality chirality = options.chirality.value_or(nearest);
  naming_input(source, [&] { check_chirality(chirality); });
  if (options.chirality)
    check_asked_radius(source, "tube", {chirality.n, chirality.m}, {nearest.n, nearest.m},
                       chiral_circumference(chirality, edge) / (2 * std::acos(-1.0) * cylinder.radius),
                       cylinder.radius);
  LatticeTube tube = naming_input(source, [&] { return lattice_tube(mesh, cylinder, edge, chirality); });
  mesh = std::move(tube.mesh);
  surface = std::move(tube.surface);
  const double angle = chiral_angle_deg(chirality);
  spdlog::info("{}: rolled from a triangular lattice of edge {:.4f} A into a ({}, {}) tube ({}, chiral angle {:.2f} "
               "degrees) of radius {:.4f} A (the input's {:.4f} A{}): {} vertices, {} triangles{}",
               source, edge, chirality.n, chirality.m, edge_kind(std::round(angle * 1e9) / 1e9), angle, tube.radius,
               cylinder.radius, options.chirality ? "" : ", the nearest a tube can have", mesh.n_vertices(),
               mesh.n_faces(),
               dropped_note(tube.dropped));
  warn_radius_off(source, fmt::format("({}, {}) tube", chirality.n, chirality.m), tube.radius, cylinder.radius);
  return {{"kind", "tube"},
          {"edge", edge},
          {"chirality", {chirality.n, chirality.m}},
          {"chiral_angle_deg", angle},
          {"radius", tube.radius},
          {"input_radius", cylinder.radius},
          {"axis", {cylinder.axis[0], cylinder.axis[1], cylinder.axis[2]}},
          {"circularity", cylinder.distance},
          {"dropped_triangles", tube.dropped}};
}

// A part of a cylinder that does not go around its axis replaced by the flat lattice cut to its unrolled outline and
// rolled back, `surface` by its cylinder; summary.json's "lattice".
inline nlohmann::json cut_curved_sheet(TriMesh& mesh, std::optional<TriMesh>& surface, const std::string& source,
                                       const Cylinder& cylinder, const std::vector<double>& angles, double edge,
                                       const LatticeOptions& options) {
  if (options.chirality)
    throw InputError(fmt::format("{}: --chirality rolls the lattice into a tube, and this surface is a part of a "
                                 "cylinder that does not go around its axis (--lattice-turn turns its lattice)",
                                 source));
  const double turn_deg = options.turn_deg.value_or(0.0);
  CurvedSheet sheet = naming_input(source, [&] { return curved_sheet(mesh, cylinder, angles, edge, turn_deg); });
  mesh = std::move(sheet.mesh);
  surface = std::move(sheet.surface);
  spdlog::info("{}: a part of a cylinder of radius {:.4f} A, unrolled, cut from a triangular lattice of edge {:.4f} A "
               "turned {:g} degrees from its longest straight side ({} edge there) and rolled back: {} vertices, {} "
               "triangles{}",
               source, cylinder.radius, edge, turn_deg, with_article(edge_kind(turn_deg)), mesh.n_vertices(),
               mesh.n_faces(), dropped_note(sheet.dropped));
  return {{"kind", "curved_sheet"},
          {"edge", edge},
          {"turn_deg", turn_deg},
          {"angle_deg", sheet.angle_deg},
          {"radius", cylinder.radius},
          {"axis", {cylinder.axis[0], cylinder.axis[1], cylinder.axis[2]}},
          {"circularity", cylinder.distance},
          {"dropped_triangles", sheet.dropped}};
}

// A sphere replaced by the Goldberg-Coxeter sphere nearest its radius (or of the indices asked for), `surface` by that
// too; summary.json's "lattice".
inline nlohmann::json cut_fullerene(TriMesh& mesh, std::optional<TriMesh>& surface, const std::string& source,
                                    const Sphere& sphere, double edge, const LatticeOptions& options) {
  refuse_turn(options, source,
              "a sphere (folded onto an icosahedron: --chirality H,K sets its Goldberg-Coxeter indices)");
  const GoldbergIndices nearest = nearest_goldberg_indices(sphere.radius, edge);
  const GoldbergIndices indices =
      options.chirality ? GoldbergIndices{options.chirality->n, options.chirality->m} : nearest;
  naming_input(source, [&] { check_goldberg_coxeter(indices.h, indices.k); });
  if (options.chirality)
    check_asked_radius(source, "fullerene", {indices.h, indices.k}, {nearest.h, nearest.k},
                       fullerene_radius(indices, edge) / sphere.radius, sphere.radius);
  LatticeFullerene fullerene = naming_input(source, [&] { return lattice_fullerene(mesh, sphere, edge, indices); });
  mesh = std::move(fullerene.mesh);
  surface = mesh;
  const long t = triangulation_number(indices.h, indices.k);
  const bool chiral = indices.k != 0 && indices.k != indices.h;
  spdlog::info("{}: the triangular lattice of edge {:.4f} A folded onto an icosahedron, Goldberg-Coxeter indices ({}, "
               "{}), T = {}: the icosahedral fullerene C{} (symmetry {}) of radius {:.4f} A (the input's {:.4f} A{}): "
               "{} vertices, {} triangles",
               source, edge, indices.h, indices.k, t, 20 * t, chiral ? "I, chiral" : "Ih", fullerene.radius,
               sphere.radius, options.chirality ? "" : ", the nearest a fullerene can have", mesh.n_vertices(),
               mesh.n_faces());
  warn_radius_off(source, fmt::format("C{} fullerene", 20 * t), fullerene.radius, sphere.radius);
  return {{"kind", "fullerene"},
          {"edge", edge},
          {"indices", {indices.h, indices.k}},
          {"triangulation_number", t},
          {"symmetry", chiral ? "I" : "Ih"},
          {"radius", fullerene.radius},
          {"input_radius", sphere.radius},
          {"centre", {sphere.centre[0], sphere.centre[1], sphere.centre[2]}},
          {"sphericity", sphere.distance},
          {"dropped_triangles", 0}};
}

// Refuses a closed surface whose vertices lie on a `what` ("sphere" or "capsule") of `radius` if its faces cover less
// than kMinSphereCover of that shape's area (`cover`: their share; a polyhedron's corners can lie on it) or if it is
// not one component of genus 0.
inline void check_whole(const std::string& source, const std::string& what, double radius, double cover,
                        const Topology& before) {
  if (cover < kMinSphereCover)
    throw InputError(fmt::format("{}: --lattice needs a flat, cylindrical, spherical or capsule-shaped surface, and "
                                 "this one's vertices lie on a {} of radius {:.4g} A but its faces cover {:.0f}% of "
                                 "that {}'s area (a polyhedron; a tessellated {} covers {:.0f}% or more)",
                                 source, what, radius, 100 * cover, what, what, 100 * kMinSphereCover));
  if (before.genus != 0 || before.components != 1)
    throw InputError(fmt::format("{}: --lattice folds the lattice onto one {}, and this surface lies on a {} but has {} "
                                 "components and genus {}",
                                 source, what, what, before.components, before.genus));
}

// A capsule replaced by the capped tube nearest its radius (or of the indices asked for) and straight length,
// `surface` by that too; summary.json's "lattice".
inline nlohmann::json cut_capped_tube(TriMesh& mesh, std::optional<TriMesh>& surface, const std::string& source,
                                      const Capsule& capsule, double edge, const LatticeOptions& options) {
  refuse_turn(options, source, "a capsule (a capped tube: --chirality N,M sets its indices)");
  const std::array<int, 2> nearest = nearest_capped_chirality(capsule.radius, edge);
  const std::array<int, 2> chirality =
      options.chirality ? std::array<int, 2>{options.chirality->n, options.chirality->m} : nearest;
  naming_input(source, [&] { check_capped_tube(chirality[0], chirality[1]); });
  if (options.chirality) {
    const Chirality any = nearest_chirality(capsule.radius, edge);  // any indices: apex caps where not (5h, 5k)
    check_asked_radius(source, "capped tube", chirality, {any.n, any.m},
                       capped_tube_radius(chirality[0], chirality[1], edge) / capsule.radius, capsule.radius);
  }
  LatticeCappedTube tube = naming_input(source, [&] { return lattice_capped_tube(mesh, capsule, edge, chirality); });
  mesh = std::move(tube.mesh);
  surface = mesh;
  const double angle = chiral_angle_deg({chirality[0], chirality[1]});
  const double period = capped_tube_period(chirality[0], chirality[1], edge);
  const bool apex = tube.caps == CapKind::apex;
  const int h = apex ? 0 : chirality[0] / 5, k = apex ? 0 : chirality[1] / 5;
  const long t = apex ? 0 : triangulation_number(h, k);
  const std::string tube_text =
      fmt::format("the ({}, {}) tube ({}, chiral angle {:.2f} degrees) of radius {:.4f} A{} and straight part {:.4f} A",
                  chirality[0], chirality[1], edge_kind(std::round(angle * 1e9) / 1e9), angle, tube.radius,
                  options.chirality ? "" : " (the nearest a capped tube with icosahedral caps can have)", tube.length);
  if (apex)
    spdlog::info("{}: a capsule of radius {:.4f} A and straight part {:.4f} A: the triangular lattice of edge {:.4f} A "
                 "folded onto a tube closed by {}, {} (period {:.4f} A): {} vertices, {} triangles",
                 source, capsule.radius, capsule.length, edge, cap_kind_description(tube.caps), tube_text, period,
                 mesh.n_vertices(), mesh.n_faces());
  else
    spdlog::info("{}: a capsule of radius {:.4f} A and straight part {:.4f} A: the triangular lattice of edge {:.4f} A "
                 "folded onto an icosahedron lengthened along a five-fold axis, {} ({} periods of {:.4f} A) closed by "
                 "the halves of C{} (Goldberg-Coxeter indices ({}, {})): {} vertices, {} triangles",
                 source, capsule.radius, capsule.length, edge, tube_text, tube.periods, period, 20 * t, h, k,
                 mesh.n_vertices(), mesh.n_faces());
  warn_radius_off(source, fmt::format("capped ({}, {}) tube", chirality[0], chirality[1]), tube.radius,
                  capsule.radius);
  return {{"kind", "capped_tube"},
          {"edge", edge},
          {"chirality", {chirality[0], chirality[1]}},
          {"chiral_angle_deg", angle},
          {"caps", cap_kind_name(tube.caps)},
          {"cap_indices", apex ? nlohmann::json() : nlohmann::json({h, k})},
          {"triangulation_number", apex ? nlohmann::json() : nlohmann::json(t)},
          {"periods", apex ? nlohmann::json() : nlohmann::json(tube.periods)},
          {"period", period},
          {"radius", tube.radius},
          {"input_radius", capsule.radius},
          {"length", tube.length},
          {"input_length", capsule.length},
          {"centre", {capsule.centre[0], capsule.centre[1], capsule.centre[2]}},
          {"axis", {capsule.axis[0], capsule.axis[1], capsule.axis[2]}},
          {"fit_distance", capsule.distance},
          {"dropped_triangles", 0}};
}

}  // namespace detail

// Why a lattice holds another number of atoms than the input's area promised (`percent`: the lattice's area over the
// input's, in percent).
inline std::string lattice_shortfall(const nlohmann::json& lattice, double percent) {
  const std::string kind = lattice.value("kind", "");
  if (kind == "capped_tube") {
    if (lattice.value("caps", "") == "apex")
      return fmt::format("a capped tube has whole rows of the lattice, and the ({}, {}) tube has a radius of {:.4f} A "
                         "and a straight part of {:.4f} A where the input has {:.4f} A and {:.4f} A",
                         lattice["chirality"][0].get<int>(), lattice["chirality"][1].get<int>(),
                         lattice["radius"].get<double>(), lattice["length"].get<double>(),
                         lattice["input_radius"].get<double>(), lattice["input_length"].get<double>());
    const long t = lattice["triangulation_number"].get<long>();
    const Chirality any = nearest_chirality(lattice["input_radius"].get<double>(), lattice["edge"].get<double>());
    return fmt::format("a capped tube has 20 T atoms and whole periods of the tube, and the ({}, {}) tube (caps from "
                       "C{}) has a radius of {:.4f} A and a straight part of {:.4f} A where the input has {:.4f} A and "
                       "{:.4f} A; --chirality {},{} (the indices nearest that radius) gives apex caps and the straight "
                       "part within half a lattice row",
                       lattice["chirality"][0].get<int>(), lattice["chirality"][1].get<int>(), 20 * t,
                       lattice["radius"].get<double>(), lattice["length"].get<double>(),
                       lattice["input_radius"].get<double>(), lattice["input_length"].get<double>(), any.n, any.m);
  }
  if (kind == "fullerene") {
    const long t = lattice["triangulation_number"].get<long>();
    return fmt::format("an icosahedral fullerene has 20 T atoms, T = h^2 + hk + k^2, and C{} (indices ({}, {})) has "
                       "a radius of {:.4f} A where the input has {:.4f} A",
                       20 * t, lattice["indices"][0].get<int>(), lattice["indices"][1].get<int>(),
                       lattice["radius"].get<double>(), lattice["input_radius"].get<double>());
  }
  return fmt::format("the lattice sites inside the outline, less the border triangles taken off, cover {:.0f}% of the "
                     "input's area ({})",
                     percent,
                     kind == "tube" ? fmt::format("the tube's radius is {:.4f} A, the input's {:.4f} A; a short tube "
                                                  "loses a larger share at its rims",
                                                  lattice["radius"].get<double>(), lattice["input_radius"].get<double>())
                                    : std::string("a small flake loses a larger share at its border"));
}

// Replaces the flat, cylindrical, spherical or capsule-shaped `mesh` by the lattice cut to its outline or folded onto
// an icosahedron, round or lengthened (pieces smaller than `min_area` dropped). Throws InputError naming `source` if the surface is none of these, if an
// option does not fit its kind, or if the cut keeps nothing.
inline LatticeStep cut_lattice(TriMesh& mesh, const std::string& source, double edge, const LatticeOptions& options,
                               const EdgeInterval& interval, double min_area) {
  const auto start = std::chrono::steady_clock::now();
  LatticeStep step;
  step.result.before = topology(mesh);
  const Topology& before = step.result.before;
  const Flatness plane = flatness(mesh);
  if (is_flat(plane, edge)) {
    step.json = detail::cut_sheet(mesh, source, plane, edge, options);
  } else if (before.boundary_loops == 0) {
    const Sphere sphere = sphere_fit(mesh);
    const double cover = sphere_cover(mesh, sphere);
    if (sphere.distance > kFlatShare * edge) {
      const Capsule capsule = capsule_fit(mesh);
      const double capsule_cover = surface_area(mesh) / capsule_area(capsule);
      if (capsule.distance > kFlatShare * edge)
        throw InputError(fmt::format("{}: --lattice needs a flat, cylindrical, spherical or capsule-shaped surface, "
                                     "and this one is closed and a vertex is {:.4g} A from the sphere and {:.4g} A "
                                     "from the capsule that fit it best (more than {:.2g} A)",
                                     source, sphere.distance, capsule.distance, kFlatShare * edge));
      detail::check_whole(source, "capsule", capsule.radius, capsule_cover, before);
      step.json = detail::cut_capped_tube(mesh, step.surface, source, capsule, edge, options);
    } else {
      detail::check_whole(source, "sphere", sphere.radius, cover, before);
      step.json = detail::cut_fullerene(mesh, step.surface, source, sphere, edge, options);
    }
  } else {
    const Cylinder cylinder = cylinder_fit(mesh);
    if (!is_cylinder(cylinder, edge))
      throw InputError(fmt::format("{}: --lattice needs a flat, cylindrical, spherical or capsule-shaped surface, and "
                                   "a vertex is {:.4g} A from the plane and {:.4g} A from the cylinder that fit it best "
                                   "(more than {:.2g} A; a sphere or a capsule must be closed)",
                                   source, plane.distance, cylinder.distance, kFlatShare * edge));
    if (const auto angles = angles_along_surface(mesh, cylinder))
      step.json = detail::cut_curved_sheet(mesh, step.surface, source, cylinder, *angles, edge, options);
    else
      step.json = detail::cut_tube(mesh, step.surface, source, cylinder, edge, options);
  }
  const SmallComponents pieces = remove_small_components(mesh, min_area);
  if (mesh.n_faces() == 0)
    throw InputError(fmt::format("{}: no lattice triangle of edge {:.4f} A fits inside the outline; build it larger "
                                 "(--atoms, --size)",
                                 source, edge));
  RemeshResult& r = step.result;
  record_final_figures(r, mesh, interval);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!r.before.same_type(r.after))
    spdlog::warn("{}: the lattice cut has genus {}, {} components and {} borders where the input has {}, {} and {}: "
                 "a neck or hole narrower than about one lattice edge ({:.3f} A) was cut or filled",
                 source, r.after.genus, r.after.components, r.after.boundary_loops, r.before.genus,
                 r.before.components, r.before.boundary_loops, edge);
  step.json["removed_pieces"] = to_json(pieces);
  return step;
}

}  // namespace carbonmesh::cli
