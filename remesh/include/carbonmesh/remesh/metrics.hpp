#pragma once
// Trusted mesh metrics: every figure carbonmesh reports about a triangle mesh comes from here.
#include <cstddef>
#include <limits>
#include <map>
#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "carbonmesh/remesh/mesh.hpp"
#include "carbonmesh/remesh/self_intersections.hpp"

namespace carbonmesh {

struct Topology {
  std::size_t vertices = 0, edges = 0, faces = 0;
  std::size_t components = 0;      // connected components (by faces and edges)
  std::size_t boundary_loops = 0;  // closed chains of border edges
  long euler = 0;                  // chi = V - E + F
  long genus = 0;                  // sum over components of g = (2 - chi_c - b_c) / 2
  // Same surface type: components, borders and genus (sizes may differ).
  bool same_type(const Topology& o) const {
    return components == o.components && boundary_loops == o.boundary_loops && genus == o.genus;
  }
};
Topology topology(const TriMesh& mesh);

// An edge is long if |e| > emax, short if |e| < emin (strict, no tolerance).
struct EdgeInterval {
  double emin = 0.0;
  double emax = std::numeric_limits<double>::infinity();
  bool given() const { return emin > 0.0 || emax < std::numeric_limits<double>::infinity(); }
};

struct EdgeStats {
  std::size_t count = 0;
  double min = 0, mean = 0, std = 0, max = 0;  // std is the population standard deviation
  std::size_t long_edges = 0, short_edges = 0;
  double percent_inside = 100.0;
};
EdgeStats edge_stats(const TriMesh& mesh, const EdgeInterval& interval = {});

// Ideal valence: 6 for an interior vertex, 4 on a border.
int ideal_valence(const TriMesh& mesh, TriMesh::VertexHandle v);

struct ValenceStats {
  std::map<int, std::size_t> interior;  // valence -> vertex count
  std::map<int, std::size_t> boundary;
  double percent_regular = 0;  // valence equal to the ideal one
  // Eval_i = (ideal - valence)^2 (Eq. 4.2 per vertex), as the share of vertices with 0, 1 and > 1.
  double percent_eval0 = 0, percent_eval1 = 0, percent_eval_gt1 = 0;
  std::size_t eval_total = 0;  // sum of Eval_i over the mesh (Eq. 4.2)
};
ValenceStats valence_stats(const TriMesh& mesh);

// Total area of the faces.
double surface_area(const TriMesh& mesh);

// The volume the faces enclose, signed: positive where they face away from the inside (for a closed surface the same
// about any point; `about` is where the cones to the faces start).
double signed_volume(const TriMesh& mesh, const Vec3& about);

struct AngleStats {
  double min_deg = 0, max_deg = 0;
};
AngleStats angle_stats(const TriMesh& mesh);

struct HausdorffResult;  // hausdorff.hpp

struct MeshStats {
  Topology topology;
  EdgeInterval interval;
  EdgeStats edges;
  ValenceStats valence;
  AngleStats angles;
  SelfIntersections self_intersections;
};
// `search_self_intersections` false leaves self_intersections unsearched (searched = false): for a mesh that cannot
// pass through itself by construction, such as a flat lattice sheet, where CGAL's search is slow (the boxes of a plane
// have no thickness: 10 s of a 15 s build of a 10^6-atom flake).
MeshStats mesh_stats(const TriMesh& mesh, const EdgeInterval& interval = {}, bool search_self_intersections = true);

nlohmann::json to_json(const Topology& t);
nlohmann::json to_json(const EdgeStats& e, const EdgeInterval& interval);
nlohmann::json to_json(const ValenceStats& v);
nlohmann::json to_json(const MeshStats& s);
std::string to_text(const MeshStats& s);

}  // namespace carbonmesh
