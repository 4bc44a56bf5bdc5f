#pragma once
// The interval-constraining remesher of the reference dissertation (Algorithm 1): every edge length is driven
// into [emin, emax] while topology and shape are kept and valences are made regular.
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "carbonmesh/remesh/mesh.hpp"
#include "carbonmesh/remesh/metrics.hpp"

namespace carbonmesh {

enum class ParametrizationWeights { MeanValue, ShapePreserving };

// One line of progress: the state after an iteration of Algorithm 1.
struct IterationLog {
  int iteration = 0;
  std::size_t long_edges = 0, short_edges = 0;
  double percent_regular = 0;
  double mean = 0, std = 0;  // edge length
  double seconds = 0;        // since the start of remesh()
  bool nonlinear = false;    // the nonlinear optimizer ran instead of the low-pass filter
  double l = 0;              // the share of long+short edges (percent) at or below which it runs: settings.l,
                             // doubled once the low-pass phase has found no new low in 5 iterations
  int level = 0;             // coarse-to-fine level: 0 the final interval, k the interval times 2^k
};

struct RemeshSettings {
  double emin = 1.2, emax = 1.8;  // the constraining interval
  int iterations = 150;           // n: at most this many iterations
  int kl = 2;                     // star number of the low-pass filter
  int kn = 2;                     // star number of the nonlinear optimizer
  int p = 0;                      // replace the projection target by the current mesh every p iterations (0: never)
  double l = 0.5;                 // percent of long+short edges at or below which the nonlinear optimizer runs
  // The loop ends after this many iterations without a better mesh (fewer long+short edges, ties by more regular
  // vertices) and the best mesh goes to the post-processing, as after n iterations (0: never before n).
  int stall_limit = 40;
  ParametrizationWeights weights = ParametrizationWeights::MeanValue;
  // Refuse (InputError) an interval that would need more triangles than this: the estimate is the surface area
  // over the area of an equilateral triangle of edge (emin + emax) / 2. Guards against a model in the wrong
  // units (a 1e9 sphere remeshed to edges of 2) filling the memory.
  double max_faces = 1e8;
  // After convergence, move the vertices along their normals to the least-squares fit of the input
  // (fit_to_surface in remesh_steps.hpp): about half the Hausdorff distance, every edge kept inside.
  // Off: every vertex stays on the input, as in the dissertation.
  bool fit_surface = true;
  // After the fit, move the vertices around the spots where the two surfaces are farthest apart so that the
  // largest distance there falls (minimax_fit in remesh_steps.hpp), every edge kept inside.
  bool minimax_fit = true;
  // After convergence, move vertices onto input points farther than snap_tolerance * emin from the remeshed
  // surface (snap_to_features in remesh_steps.hpp: ear rims, cone tips, grooves), every edge kept inside.
  bool snap_features = true;
  // The same distance is what the flips toward the input, the caps and the minimax fit below work beyond. 0.33
  // (0.25 until session 49): on 92 generated and noisy inputs the RMS distance fell on 52 and rose on 12, the
  // largest distance fell on 43 and rose on 32, their time 503 -> 348 s (one run each), every edge inside
  // (docs/algorithm.md, Snap tolerance).
  double snap_tolerance = 0.33;  // as a fraction of emin
  // After the snap, the input vertices it left farthest from the surface get a vertex of their own with the cap around
  // it rebuilt (cap_tips in remesh_steps.hpp: tips that no move or single split reached), every edge kept inside.
  // Only with snap_features.
  bool cap_tips = true;
  // After the data-dependent flips, the faces farthest from the input get a vertex at the input point nearest their
  // farthest point, with the cap around it rebuilt (cap_far_faces in remesh_steps.hpp: a face across a saddle or a
  // crease that no vertex move or flip brings nearer), every edge kept inside. Only with snap_features.
  bool cap_faces = true;
  // After the snap, flip the diagonals of quads whose faces lie farther than snap_tolerance * emin from the input
  // where the other diagonal follows it (data_dependent_flips in remesh_steps.hpp: grooves, ridges), every edge
  // kept inside and no vertex more than one off its ideal valence; then those whose other diagonal is outside the
  // interval, with the vertices around relaxed until it is inside (relaxed_flips in remesh_steps.hpp).
  bool flip_toward_input = true;
  // At the end, measure the input vertex farthest from the remeshed surface (RemeshResult::farthest_input) and warn
  // when it is more than emax away: a part of the input was cut off (a slit, fin or rim narrower than emin, which
  // the iterations bridge or pull in). Off for the coarse levels, which the fine level measures.
  bool measure_cut_off = true;
  // Coarse to fine: remesh into [2^k emin, 2^k emax] first, then k times split every triangle into four at its
  // edge midpoints (halving every edge), project onto the input and continue at the next finer interval. For
  // large structures: the fine level starts nearly converged, and with 4^k times fewer valence defects.
  int coarse_levels = 0;
  // When > 0 (`build`: the target edge a): a mesh that starts with its mean edge inside [emin, emax] but more than
  // 5% away from target_mean goes on to the coarse levels (if any) as if it had edges outside, and the level that
  // remeshes it itself first splits it into four triangles per triangle at its edge midpoints, so that the loop
  // brings the mean to the middle of the interval as it does from a mesh with a mean edge outside (otherwise it
  // only mends the few edges outside; one atom per triangle: the atom count of a build follows the mean edge).
  // Doubled for each coarse level.
  double target_mean = 0;
  // Called with the mesh of every coarse level that converged, just before it is subdivided (level 1: the one at
  // twice the interval; on the input, not fitted). May be empty.
  std::function<void(const TriMesh&, int level)> on_coarse_mesh;
  // Called after every iteration (progress lines, CSV logs). May be empty.
  std::function<void(const IterationLog&)> on_iteration;
};

// Where a remesh's wall time went, in seconds (0 for a step that did not run); the steps add up to
// RemeshResult::seconds.
struct RemeshStepSeconds {
  double iterations = 0;   // the setup, the coarse levels and the loop (Algorithm 1)
  double cleanup = 0;      // post-processing (4.6), valence defects and stuck edges after the loop
  double regularize = 0;   // valence flips that keep every edge inside
  double snap = 0;         // snap_to_features and cap_tips
  double flips = 0;        // data_dependent_flips, the relaxed ones included, and cap_far_faces
  double surface_fit = 0;  // fit_to_surface
  double minimax_fit = 0;  // minimax_fit
  double other = 0;        // the rest: the topology guard, the final figures, the farthest input vertex, and a first
                           // attempt from a coarse level that a direct remesh replaced
};

struct RemeshResult {
  bool converged = false;  // no long and no short edge left
  int iterations = 0;        // at the final interval
  int coarse_levels = 0;     // levels remeshed at a coarser interval first (settings.coarse_levels)
  int coarse_iterations = 0;  // iterations at those levels
  bool post_processed = false;
  // The loop stopped early: the mesh had grown to 4 times the faces the interval needs (or it had at the start).
  bool diverged = false;
  // The loop stopped early: the surface area was below half of what it started with and still falling by more than
  // 15% per 10 iterations (a surface thinner than the interval eroding); the best mesh goes to the post-processing.
  bool vanished = false;
  // The loop stopped early: no better mesh for settings.stall_limit iterations; the best mesh goes to the
  // post-processing.
  bool stalled = false;
  // An input with every edge inside (but irregular valences) that the loop and the post-processing left with edges
  // outside: the input is kept (and regularized, snapped and fitted like a converged mesh).
  bool kept_input = false;
  // Local changes of connectivity kept by clear_stuck_edges after the loop (edges it left outside; 0 when none were).
  std::size_t stuck_edges_cleared = 0;
  std::size_t bisected_vertices = 0;  // vertices added by the longest-edge bisection of an input with mean edge > 2 emax
  std::size_t long_edges = 0, short_edges = 0;
  double percent_regular = 0;
  double percent_eval_gt1 = 0;  // vertices with (ideal - valence)^2 > 1
  double seconds = 0;
  Topology before, after;  // the surface type (genus, components, borders) is kept: before.same_type(after)
  // The topology guard: the final mesh had another surface type than the input (`changed` holds it) and was
  // replaced by the best mesh of the run with the input's surface type (the input itself at worst).
  bool topology_violation = false;
  Topology changed;
  std::size_t rejected_best = 0;  // iterations whose better mesh was refused as best for a changed surface type
  bool fitted = false;            // fit_to_surface ran (settings.fit_surface)
  double fit_rms_before = 0, fit_rms_after = 0;  // its area-weighted RMS distance to the input, before and after
  bool minimax_fitted = false;  // minimax_fit ran (settings.minimax_fit)
  double minimax_max_before = 0, minimax_max_after = 0;  // the largest sampled distance, before and after
  std::size_t minimax_moves = 0;                         // vertex moves it kept
  std::size_t minimax_wide_moves = 0;  // of those, in the farthest region's second search (its ring movable too)
  bool snapped = false;              // snap_to_features ran (settings.snap_features)
  std::size_t snapped_vertices = 0;  // vertices it moved onto the input's features
  std::size_t inserted_vertices = 0;  // vertices it added at input vertices no move reached (a split face each)
  std::size_t capped_tips = 0;  // input vertices given a vertex of their own by cap_tips (settings.cap_tips)
  long cap_vertices = 0;        // vertices it added in all (the tips, less the collapses, plus the splits around)
  std::size_t capped_faces = 0;  // faces given a vertex of their own by cap_far_faces (settings.cap_faces)
  long face_cap_vertices = 0;    // vertices it added in all
  // The farthest interior input vertex from the remeshed surface, before and after the snap (before the fit and the
  // tip caps).
  double snap_max_before = 0, snap_max_after = 0;
  // The same for the input's border vertices (border vertices moved onto the corners of the input's borders).
  std::size_t snapped_border_vertices = 0;
  double snap_border_max_before = 0, snap_border_max_after = 0;
  std::size_t data_dependent_flips = 0;  // flips toward the input (settings.flip_toward_input)
  std::size_t relaxed_flips = 0;         // and those with their neighbourhood relaxed
  // The interior input vertex farthest from the final surface (settings.measure_cut_off): more than emax means a
  // part of the input was cut off, and remesh() warns.
  double farthest_input = 0;
  Vec3 farthest_input_point{0, 0, 0};
  bool cut_off = false;  // farthest_input > emax
  RemeshStepSeconds step_seconds;
  std::vector<IterationLog> log;
};

// The best mesh of a run: fewest long+short edges, ties by the higher share of regular vertices, and only a mesh
// with the surface type (genus, components, borders) of the input. Starts with the input, which always qualifies.
class BestMesh {
 public:
  BestMesh(const TriMesh& input, std::size_t troubling, double percent_regular);
  // Keeps a copy of `mesh` if it scores better and has the input's surface type (computed only for a better
  // score). Returns whether it was kept.
  bool offer(const TriMesh& mesh, std::size_t troubling, double percent_regular);
  const TriMesh& mesh() const { return mesh_; }
  const Topology& input_topology() const { return input_; }
  std::size_t troubling() const { return troubling_; }
  std::size_t rejected() const { return rejected_; }  // better meshes refused for their surface type

 private:
  Topology input_;
  TriMesh mesh_;
  std::size_t troubling_ = 0;
  double percent_regular_ = 0;
  std::size_t rejected_ = 0;
};

// The end-of-remesh check: if `mesh` has another surface type than best.input_topology(), replaces it by
// best.mesh() and returns the rejected topology; otherwise leaves it and returns nothing.
std::optional<Topology> enforce_surface_type(TriMesh& mesh, const BestMesh& best);

// The figures of a finished mesh in `result`: long and short edges against `interval`, converged, the shares of
// regular vertices and of vertices with Eval > 1, and the topology after.
void record_final_figures(RemeshResult& result, const TriMesh& mesh, const EdgeInterval& interval);

// Remeshes `mesh` in place. Throws InputError for an invalid interval (emin <= 0 or emin >= emax) or one that
// would need more than settings.max_faces triangles.
RemeshResult remesh(TriMesh& mesh, const RemeshSettings& settings);

nlohmann::json to_json(const RemeshResult& result);

}  // namespace carbonmesh
