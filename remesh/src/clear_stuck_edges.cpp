// Edges left outside [emin, emax] after the loop and its post-processing (not in the dissertation).
//
// The nonlinear optimizer moves vertices and never changes the connectivity, and the stellar operations of the
// post-processing refuse a collapse that creates long edges. Some configurations are out of reach of both: a border
// vertex of valence 3 (ideal 4), whose two triangles have about 90 degrees there on a straight border (so the edge
// opposite it is about sqrt(2) times the edges at it, which must stay near emin), kept one short edge while its
// neighbours moved (an annulus built at 31000 and 45000 atoms). Here each edge still outside gets a few local changes
// of connectivity, tried in turn: a flip of one of the four edges of its two triangles or of itself, or its collapse.
// After each the free vertices around it (interior ones, and border ones along their border curves) are relaxed
// (Error_b with the interval hinge, projected onto the target; after the post-processing, where that is refused, once
// more without projection), and the change is kept only when the region then has fewer edges outside or faces under 3
// degrees than before and no more faces turned over than before (on a crumpled surface some are before any change);
// otherwise it is undone.
#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

#include <spdlog/spdlog.h>

#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/remesh_steps.hpp"
#include "local_region.hpp"
#include "remesh_geometry.hpp"

namespace carbonmesh {
namespace {

using VH = TriMesh::VertexHandle;
using EH = TriMesh::EdgeHandle;

constexpr int kRelaxRings = 2;  // the free vertices within kn + 2 rings of the changed edge are relaxed
constexpr int kPasses = 3;      // relax-and-project passes before a change is undone
constexpr int kRounds = 3;      // passes over the edges left outside
// More edges outside than this share of all edges: nothing is tried. Such a mesh is not near the interval at all, and
// flips and collapses do not shorten edges much longer than emax: bunny.off (mean edge 2.25) in [1.2, 1.5], against
// Ineq 5.1, where the loop found no mesh with fewer edges outside than the input, came here with 9245 of 10068
// outside and kept 73 changes in 216 s. Nearer the interval these changes do their work: the same model and
// fertility in [1.2, 1.56] come here with 11% outside (2912 of 27366, 3564 of 35526) and leave 16 and 24 (8 s).
constexpr double kMostOutside = 0.5;
// Where most changes fail, the rest would fail too, each after relaxations of milliseconds: once kFewestTries edges
// were tried, the step ends when fewer than one in kTriesPerKept was cleared. A flat disc (20:1, mean edge 2.25) in
// [1.2, 1.6], against Ineq 5.1, came here with 1198 edges outside and kept 39 changes in 35 s (now 15 of the first
// 200 tried, 3 s; 1118 edges left instead of 1046). The two models above clear about two of three tried (a change
// often clears the edges next to it too), and their outputs do not change.
constexpr std::size_t kFewestTries = 200;
constexpr std::size_t kTriesPerKept = 10;

bool outside(const TriMesh& mesh, EH e, double emin, double emax) {
  const double l = geometry::edge_length(mesh, e);
  return l < emin || l > emax;
}

class StuckEdges {
 public:
  StuckEdges(TriMesh& mesh, const ProjectionTarget& target, bool in_place_too, int kn, double emin, double emax)
      : mesh_(mesh), target_(target), in_place_too_(in_place_too), kn_(kn), emin_(emin), emax_(emax),
        local_(emin, emax) {}

  // Tries the changes for `e` until one is kept.
  bool clear(EH e) {
    const auto h = mesh_.halfedge_handle(e, 0);
    const VH a = mesh_.from_vertex_handle(h), b = mesh_.to_vertex_handle(h);
    local_.collect(mesh_, a, kn_ + kRelaxRings + 2, region_);  // every vertex the relaxation moves, with its star
    const std::size_t flaws_before = local_.flaws(mesh_, region_);
    normals_.clear();
    for (auto v : region_) normals_.emplace_back(v, geometry::vertex_normal(mesh_, v));
    turned_before_ = turned();  // not 0 on a crumpled surface: a change may not add to them
    // The flips: the four edges of the two triangles (a border vertex among them gets an edge more), then e.
    std::vector<EH> flips;
    for (auto g : {h, mesh_.opposite_halfedge_handle(h)}) {
      if (mesh_.is_boundary(g)) continue;
      flips.push_back(mesh_.edge_handle(mesh_.next_halfedge_handle(g)));
      flips.push_back(mesh_.edge_handle(mesh_.prev_halfedge_handle(g)));
    }
    flips.push_back(e);
    for (const EH f : flips)
      if (try_flip(f, a, flaws_before)) {
        spdlog::debug("stuck edge {}: a flip kept ({} flaws around it before)", e.idx(), flaws_before);
        return true;
      }
    if (geometry::edge_length(mesh_, e) >= emin_) return false;
    VH from = a, to = b;
    for (int side = 0; side < 2; ++side, std::swap(from, to)) {
      const auto g = mesh_.find_halfedge(from, to);
      if (g.is_valid() && try_collapse(g, flaws_before, from)) {
        spdlog::debug("stuck edge {}: a collapse kept ({} flaws around it before)", e.idx(), flaws_before);
        return true;
      }
    }
    return false;
  }

 private:
  bool try_flip(EH f, VH centre, std::size_t flaws_before) {
    if (mesh_.is_boundary(f) || !mesh_.is_flip_ok(f)) return false;
    const auto h = mesh_.halfedge_handle(f, 0), o = mesh_.halfedge_handle(f, 1);
    const VH a = mesh_.from_vertex_handle(h), b = mesh_.to_vertex_handle(h);
    const VH c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h));
    const VH d = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(o));
    if (!geometry::flip_keeps_shape(mesh_.point(a), mesh_.point(b), mesh_.point(c), mesh_.point(d))) return false;
    mesh_.flip(f);
    if (relaxed(centre, flaws_before)) return true;
    mesh_.flip(f);  // the same edge flipped back: the connectivity before
    return false;
  }

  // Collapses h (from-vertex removed) with the kept vertex where it is on a border, else at the midpoint.
  // An undone collapse gives the removed vertex a new handle: `removed` gets it.
  bool try_collapse(TriMesh::HalfedgeHandle h, std::size_t flaws_before, VH& removed) {
    const VH v = mesh_.from_vertex_handle(h), u = mesh_.to_vertex_handle(h);
    const Vec3 pv = mesh_.point(v), pu = mesh_.point(u);
    const Vec3 position = mesh_.is_boundary(u) && !mesh_.is_boundary(v) ? pu : 0.5 * (pv + pu);
    if (!collapse_ok(mesh_, h, position, std::numeric_limits<double>::infinity())) return false;
    const VH vl = mesh_.is_boundary(h) ? VH() : mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h));
    const auto o = mesh_.opposite_halfedge_handle(h);
    const VH vr = mesh_.is_boundary(o) ? VH() : mesh_.to_vertex_handle(mesh_.next_halfedge_handle(o));
    if (!vl.is_valid() || !vr.is_valid()) return false;  // (border edges: their vertex split is not the inverse)
    mesh_.collapse(h);
    mesh_.set_point(u, position);
    if (relaxed(u, flaws_before, {u, pu})) return true;
    mesh_.set_point(u, pu);
    mesh_.vertex_split(pv, u, vl, vr);  // the inverse of the collapse; v comes back as the last vertex
    removed = VH(static_cast<int>(mesh_.n_vertices()) - 1);
    return false;
  }

  // Relaxes the free vertices around `centre`, projected onto the target, then (where that is refused and
  // in_place_too_) again from the same positions without projection; keeps a result (true) or puts every position
  // back, `first` too.
  bool relaxed(VH centre, std::size_t flaws_before, std::pair<VH, Vec3> first = {VH(), Vec3(0, 0, 0)}) {
    local_.collect(mesh_, centre, kn_ + kRelaxRings, inner_);
    variables_.clear();
    for (auto w : inner_)
      if (!mesh_.is_boundary(w) || slides_on_border(mesh_, w)) variables_.push_back(w);
    for (const bool project : {true, false}) {
      if (!project && !in_place_too_) break;
      saved_.clear();
      bool kept = false;
      std::size_t last = std::numeric_limits<std::size_t>::max();
      for (int pass = 0; pass < kPasses && !kept; ++pass) {
        for (auto w : variables_) saved_.emplace_back(w, mesh_.point(w));
        optimize_vertices(mesh_, variables_, emin_, emax_);
        if (project)
          for (auto w : variables_) project_with_ring(mesh_, target_, w, neighbors_);
        const std::size_t flaws = local_.flaws(mesh_, region_);
        kept = flaws < flaws_before && turned() <= turned_before_;
        if (flaws >= last) break;
        last = flaws;
      }
      if (kept) return true;
      for (auto it = saved_.rbegin(); it != saved_.rend(); ++it) mesh_.set_point(it->first, it->second);
    }
    if (first.first.is_valid()) mesh_.set_point(first.first, first.second);
    return false;
  }

  // Faces at region vertices turned against that vertex's normal before the change (a face counted at each of its
  // region corners).
  std::size_t turned() const {
    std::size_t count = 0;
    for (const auto& [v, n] : normals_) {
      if (mesh_.status(v).deleted()) continue;
      for (auto f : mesh_.vf_range(v))
        count += OpenMesh::dot(n, geometry::face_normal(mesh_, f)) < geometry::kMaxNormalTurnCos;
    }
    return count;
  }

  TriMesh& mesh_;
  const ProjectionTarget& target_;
  bool in_place_too_;
  int kn_;
  double emin_, emax_;
  LocalRegion local_;
  std::vector<VH> region_, inner_, variables_;
  std::vector<std::pair<VH, Vec3>> normals_, saved_;
  std::size_t turned_before_ = 0;
  std::vector<Vec3> neighbors_;
};

}  // namespace

StuckEdgesResult clear_stuck_edges(TriMesh& mesh, const ProjectionTarget& target, int kn, double emin, double emax,
                                   bool in_place_too) {
  StuckEdgesResult result;
  const EdgeStats start = edge_stats(mesh, {emin, emax});
  result.outside = start.long_edges + start.short_edges;
  if (static_cast<double>(result.outside) > kMostOutside * static_cast<double>(start.count)) {
    spdlog::info("stuck edges: {} of {} edges outside [{}, {}], more than {:.0f}%: not near the interval, local "
                 "changes not tried",
                 result.outside, start.count, emin, emax, 100 * kMostOutside);
    result.not_near = true;
    return result;
  }
  StuckEdges stuck(mesh, target, in_place_too, kn, emin, emax);
  for (int round = 0; round < kRounds && !result.few_cleared; ++round) {
    std::vector<EH> edges;
    for (auto e : mesh.edges())
      if (!mesh.status(e).deleted() && outside(mesh, e, emin, emax)) edges.push_back(e);
    std::size_t kept = 0;
    for (const EH e : edges) {
      if (mesh.status(e).deleted() || !outside(mesh, e, emin, emax)) continue;
      ++result.tried;
      if (stuck.clear(e)) ++kept;
      result.few_cleared = result.tried >= kFewestTries && (result.cleared + kept) * kTriesPerKept < result.tried;
      if (result.few_cleared) break;
    }
    result.cleared += kept;
    spdlog::debug("stuck edges, round {}: {} edges outside, {} cleared ({} tried in all)", round + 1, edges.size(),
                  kept, result.tried);
    if (kept == 0) break;
  }
  if (result.few_cleared)
    spdlog::info("stuck edges: {} of the {} edges tried were cleared, fewer than one in {}: the others not tried",
                 result.cleared, result.tried, kTriesPerKept);
  if (result.cleared > 0) mesh.garbage_collection();
  return result;
}

}  // namespace carbonmesh
