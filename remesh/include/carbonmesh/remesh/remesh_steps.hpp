#pragma once
// The steps of the interval-constraining remesher (dissertation chapter 4), one free function per step.
// remesh() in remesher.hpp chains them (Algorithm 1); they are public so that tests can check each one.
#include <array>
#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "carbonmesh/remesh/mesh.hpp"
#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/remesher.hpp"

namespace carbonmesh {

namespace triangle_tree {
class SurfaceTree;
}
// The steps after Algorithm 1 that measure against the input take its tree as `input_tree` where the caller has one
// (remesh() builds it once for all of them; it must be the tree of `input`), and otherwise build their own.

// ---- stellar_operations.cpp (section 4.1) -------------------------------------------------------------

// The intermediate interval [e^i_min, e^i_max] of section 4.1 from the current mean edge length m_i; on a mesh
// with m_i below (emax - emin) / 2 its lower bound is m_i instead of one that no edge is below.
struct IntermediateInterval {
  double emin = 0, emax = 0;
};
IntermediateInterval intermediate_interval(double current_mean, double emin, double emax);

// Collapsing `h` (from-vertex removed, to-vertex kept) keeps the topology: OpenMesh's is_collapse_ok
// (link condition), no interior edge with both ends on a border, no border closed (loops of 3 edges),
// and a border vertex is never removed in favour of an interior one.
bool collapse_keeps_topology(TriMesh& mesh, TriMesh::HalfedgeHandle h);  // non-const: is_collapse_ok tags

// collapse_keeps_topology plus geometry with the kept vertex moved to `position`: no face flipped or
// degenerate, and no edge of the new star longer than `max_edge`.
bool collapse_ok(TriMesh& mesh, TriMesh::HalfedgeHandle h, const Vec3& position, double max_edge);

// Position minimising sum_j (|x - V_j| - m)^2 (Eq 4.1) over `neighbors`, restricted to the plane through
// `start` with normal `normal` (Gauss-Newton from `start`).
Vec3 minimize_length_energy(const std::vector<Vec3>& neighbors, const Vec3& start, const Vec3& normal, double m);

struct StellarResult {
  std::size_t splits = 0, collapses = 0;
};
// Splits edges longer than `emax` and collapses edges shorter than `emin` in priority order (farthest
// outside first, ties by edge index); positions by Eq 4.1 with target length `m`. An interior edge shorter than
// 2 emin is not split in a pass that added an interior vertex opposite it (its halves would be short). Leaves deleted
// elements in place (call garbage_collection()).
StellarResult stellar_operations(TriMesh& mesh, double emin, double emax, double m);

// ---- correct_valence.cpp (section 4.2, Algorithm 2) ---------------------------------------------------

// J_mp of flipping `e` (Eq 4.3): E_val before minus after, over the four vertices involved.
int valence_improvement(const TriMesh& mesh, TriMesh::EdgeHandle e);
// Flips edges with J_mp > 0 in priority order until no flip is done. Returns the number of flips.
// With `keep`, a flip that replaces an edge inside that interval by one outside is refused.
std::size_t correct_valence(TriMesh& mesh, double m, const EdgeInterval* keep = nullptr);

// ---- local_parametrization.cpp (sections 3.6, 4.3.1) --------------------------------------------------

// The k-star of a vertex: vertices with their star number (0 for the centre), and the faces incident to
// vertices of star number < k.
struct KStar {
  std::vector<TriMesh::VertexHandle> vertices;  // vertices[0] is the centre
  std::vector<int> ring;                        // star number of each vertex
  std::vector<TriMesh::FaceHandle> faces;
};
// Every interior vertex's 1-ring (circulator order) and its parametrization weights lambda_ij (Eq 3.4-3.5
// or shape-preserving), computed once per pass of the low-pass filter instead of once per star holding the
// vertex (the same numbers: positions do not change during a pass).
struct RingWeights {
  std::vector<int> begin;        // CSR offsets, one more than vertices
  std::vector<int> ring;         // neighbour indices
  std::vector<double> lambda;    // weight of each neighbour
  std::vector<char> valid;       // weights present (interior vertex with 3 to 64 neighbours)
};
RingWeights ring_weights(const TriMesh& mesh, ParametrizationWeights weights);
// Per-thread scratch space for k-star collection (sized to the mesh).
struct StarScratch {
  std::vector<int> vertex_mark, face_mark, local;
  int stamp = 0;
  const RingWeights* weights = nullptr;  // if set, compute_parametrization reads the weights from here
  explicit StarScratch(const TriMesh& mesh);
};
void collect_k_star(const TriMesh& mesh, TriMesh::VertexHandle v, int k, KStar& star, StarScratch& scratch);

// Floater parametrization of a k-star homeomorphic to a disk: border on a circle (arc length kept),
// interior vertices as convex combinations of their neighbours (Eq 3.1-3.3, weights Eq 3.4-3.5 or
// shape-preserving), solved with Eigen's LU (dense for up to 40 interior vertices, sparse beyond). `uv` gets one
// point per star vertex.
// Returns false when the star is not a disk (the caller falls back to the tangential Laplacian).
bool compute_parametrization(const TriMesh& mesh, const KStar& star, ParametrizationWeights weights,
                             StarScratch& scratch, std::vector<Eigen::Vector2d>& uv);

// ---- low_pass_filter.cpp (section 4.3, Algorithm 3) ---------------------------------------------------

// New position of one interior vertex: Laplacian with weights 1/2^(star-1) in the local parametrization
// of its kl_i-star (Eq 4.4), or the tangential Laplacian when the star is not a disk.
Vec3 low_pass_position(const TriMesh& mesh, TriMesh::VertexHandle v, int kl, ParametrizationWeights weights,
                       StarScratch& scratch);
// Moves a border vertex along the quadratic curve through its two border edges, minimising Eq 4.1.
// Returns false if it was not moved.
bool border_optimizer(TriMesh& mesh, TriMesh::VertexHandle v, double m);
// One pass of Algorithm 3 over the whole mesh (OpenMP over vertices, applied in vertex order).
void low_pass_filter(TriMesh& mesh, int kl, ParametrizationWeights weights, double m);

// ---- nonlinear_optimizer.cpp (section 4.4) ------------------------------------------------------------

struct NonlinearResult {
  std::size_t troubling = 0;  // long+short edges before
  std::size_t regions = 0;    // regions optimised
};
// Minimises Error_b (Eq 4.7) over tangent-plane displacements of the kn-star around each troubling edge,
// edges by priority p_j = n_l + n_s (ties by edge index). Border vertices move along their border curve
// (the quadratic of border_optimizer, one parameter each); border endpoints of a troubling edge first go
// through border_optimizer.
NonlinearResult nonlinear_optimizer(TriMesh& mesh, int kn, double emin, double emax);

// Minimises Error_b with the interval hinge over the interior vertices of the k-star of `e` (ring < k;
// the other vertices stay fixed). `moved` gets those vertices with their positions before. Returns their
// number.
std::size_t optimize_edge_region(TriMesh& mesh, TriMesh::EdgeHandle e, int k, double emin, double emax,
                                 std::vector<std::pair<TriMesh::VertexHandle, Vec3>>& moved);

// The same over the given vertices: interior ones, and border ones for which slides_on_border(), each moving along
// the curve through its border edges; every other vertex stays where it is.
void optimize_vertices(TriMesh& mesh, const std::vector<TriMesh::VertexHandle>& variables, double emin, double emax);

// Whether border vertex `v` has a border curve to move along (it lies on exactly one border, and its two border
// neighbours differ).
bool slides_on_border(const TriMesh& mesh, TriMesh::VertexHandle v);

// ---- projection.cpp (section 4.5, Algorithm 4) --------------------------------------------------------

// The target vertices nearest a point `at`, kept with a mesh vertex between projections. A target vertex is at
// most |q - at| nearer to a point q than to `at`, so when the k-th nearest of the kept ones is nearer to q than
// `beyond` - |q - at|, no other target vertex is among q's k nearest: they are taken from the kept ones, the
// search is skipped, and the projection is the same as with it.
struct NearestTargetVertices {
  static constexpr std::size_t kKept = 16;  // at least k (10 in the projection steps)
  std::array<double, 3> at{};
  double beyond = -1;  // the distance from `at` of the nearest target vertex not kept (infinity: none); < 0: unset
  std::array<int, kKept> ids{};
  std::size_t count = 0;
};

// The projection mesh M_p with its spatial index (a uniform grid over its vertices, cell_grid.hpp).
class ProjectionTarget {
 public:
  // With max_edge > 0 the target's edges longer than max_edge are bisected first (longest-edge bisection: the new
  // vertices lie on the old edges, so the surface is the same). The candidates of Algorithm 4 are the faces around
  // the k nearest target vertices: on a fan of long slivers a point can lie over a face with no corner among them.
  explicit ProjectionTarget(const TriMesh& target, double max_edge = 0);
  ~ProjectionTarget();
  ProjectionTarget(const ProjectionTarget&) = delete;
  ProjectionTarget& operator=(const ProjectionTarget&) = delete;
  // Algorithm 4 for one point: candidate triangles around the k nearest target vertices, scored by the
  // neighbourhood-aware distance |V-P| + sum_k ||V-V_k| - |P-V_k||.
  // With `kept` (k at most its kKept), the k nearest target vertices kept there are used if they hold for v,
  // else searched and kept there.
  Vec3 project(const Vec3& v, const std::vector<Vec3>& neighbors, int k = 10,
               NearestTargetVertices* kept = nullptr) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};
// Projects every vertex of `mesh` onto the target (OpenMP over vertices, applied in vertex order). With
// `only_moved`, vertices still where the previous projection onto this target put them are skipped
// (they lie on the target already); the remembered positions live in a vertex property that
// forget_projection() removes (call it when the target changes or the mesh is handed back).
// With `keep`, a vertex whose projection would put more of its edges outside that interval than lie outside it now
// goes half or a quarter of the way instead where that does not, or stays (and is tried again by the next
// projection).
void projection(const ProjectionTarget& target, TriMesh& mesh, bool only_moved = false,
                const EdgeInterval* keep = nullptr);
// The vertex properties of projection(): where each vertex was put (x, y, z, 1) and its NearestTargetVertices
// (spatial_order() moves them with their vertices), and the mesh property naming the target those were searched
// on (a projection onto another target starts them over).
inline constexpr const char* kProjectedProperty = "carbonmesh:projected";
inline constexpr const char* kNearestTargetProperty = "carbonmesh:nearest target vertices";
inline constexpr const char* kNearestTargetOwnerProperty = "carbonmesh:nearest target vertices, target";
void forget_projection(TriMesh& mesh);
// Removes only the NearestTargetVertices of the vertices (a cache: the next projections give the same result), as
// from a copy kept aside.
void forget_nearest_target_vertices(TriMesh& mesh);

// ---- remove_valence_defects.cpp ------------------------------------------------------------------------

// Collapses each interior vertex of valence <= 4 (ideal 6) into a neighbour when, after the kn-stars of the
// edges around the kept vertex are relaxed (Error_b with the interval hinge, projected onto `target`), the
// region has no more edges outside [emin, emax] or faces under 3 degrees than before; otherwise the collapse
// is undone. With every edge inside before they all stay inside. Returns the vertices removed.
std::size_t remove_valence_defects(TriMesh& mesh, const ProjectionTarget& target, int kn, double emin,
                                   double emax);

// ---- clear_stuck_edges.cpp ------------------------------------------------------------------------------

// Each edge outside [emin, emax] gets local changes of connectivity in turn (a flip of one of the four edges of its
// triangles or of itself, then its collapse), each followed by a relaxation of the free vertices around it (Error_b
// with the interval hinge, projected onto `target`; where that is refused and `in_place_too`, once more from the
// same positions without projection, as the post-processing of section 4.6 relaxes) and kept only when the region
// then has fewer edges outside or faces under 3 degrees and no more faces turned over than before; otherwise undone.
// These changes are for a few stuck edges: nothing is tried when more than half the edges are outside (a mesh not
// near the interval: flips and collapses do not shorten much longer edges), and the step ends once 200 edges were
// tried and fewer than one in 10 cleared.
struct StuckEdgesResult {
  std::size_t outside = 0;   // edges outside [emin, emax] at the start
  std::size_t tried = 0;     // edges whose changes were tried
  std::size_t cleared = 0;   // changes kept
  bool not_near = false;     // more than half the edges outside: nothing tried
  bool few_cleared = false;  // ended early: fewer than one in 10 of 200 or more tried cleared
};
StuckEdgesResult clear_stuck_edges(TriMesh& mesh, const ProjectionTarget& target, int kn, double emin, double emax,
                                   bool in_place_too = false);

// ---- snap_to_features.cpp ----------------------------------------------------------------------------------

struct SnapResult {
  std::size_t candidates = 0;  // input vertices farther than the tolerance from the remeshed surface at the start
  std::size_t snapped = 0;     // remeshed vertices moved onto one of them and kept there
  std::size_t tries = 0;       // moves tried (each a relaxation of up to three passes)
  int rounds = 0;
  double max_before = 0, max_after = 0;  // largest distance of an interior input vertex to the remeshed surface,
                                         // before and after this step
  std::vector<char> fixed;               // per vertex of the mesh: 1 where it was snapped onto the input
  // The same for the input's border vertices, after the interior ones (border vertices moved onto them).
  std::size_t border_candidates = 0, border_snapped = 0;
  int border_rounds = 0;
  double border_max_before = 0, border_max_after = 0;
  // Then the interior input vertices still farther than the tolerance, each given a vertex of its own (a split of
  // its nearest face) where that passes the same tests.
  std::size_t insertion_candidates = 0, insertion_tries = 0, inserted = 0;
  double insertion_seconds = 0;
};
// Each interior input vertex farther than `tolerance` from `mesh` (farthest first) pulls the nearest free
// interior vertex of `mesh` onto itself; the interior vertices of its kn+2 rings are relaxed (Error_b with
// the interval hinge) and projected onto `target`. Kept only if that adds no edge outside [emin, emax], no
// face under 3 degrees and no folded face, and leaves the input vertices and input edge midpoints nearest the moved
// faces, and the moved faces themselves, nearer the input than the farthest of those input points was (that
// distance never grows); with every edge inside before they all stay inside. Then the same for the input's border
// vertices, each pulling the nearest free border vertex of `mesh` onto itself (interior and border points measured
// together for the farthest distance). Last, the 16 farthest interior input vertices still farther than `tolerance`
// each get a new vertex where that passes the same tests (a split of the face nearest it, flips toward the ideal
// valences, no valence off it by more than one, no new face turned against the input); `mesh` is then without
// deleted elements, and `fixed` covers the new vertices.
SnapResult snap_to_features(TriMesh& mesh, const TriMesh& input, const ProjectionTarget& target, int kn, double emin,
                            double emax, double tolerance, const triangle_tree::SurfaceTree* input_tree = nullptr);

struct FarthestInputVertex {
  double distance = 0;  // to the remeshed surface
  Vec3 point{0, 0, 0};
  bool measured = false;  // false: no interior input vertex or no face
};
// The interior vertex of `input` farthest from the surface of `mesh` (one AABB tree over its triangles). Farther
// than an edge, it shows a part of the input that the remeshed surface cut off.
FarthestInputVertex farthest_input_vertex(const TriMesh& mesh, const TriMesh& input);

// ---- cap_tips.cpp ---------------------------------------------------------------------------------------------

struct CapTipsResult {
  std::size_t candidates = 0;  // interior input vertices to try (the farthest, see below)
  std::size_t tries = 0;       // of them, those still farther than the tolerance when their turn came
  std::size_t capped = 0;      // given a vertex of their own, kept
  long added = 0;  // vertices added, net (the tips and the splits of long edges, less the collapses of short ones)
  double farthest = 0;  // the largest distance at the start (of an interior input vertex; with the faces: of either)
};
// The interior input vertices farthest from `mesh` (at most 8, farther than `tolerance` and than 0.8 of the farthest;
// none if the farthest is more than emax away: a part of the input cut off) each get a vertex of their own: the face
// nearest one is split there, and the vertices within kn + 4 rings (kn + 6 if edges were left outside) are relaxed
// (Error_b with the interval hinge, projected onto `target`), with splits of their long edges, collapses of their short
// ones and flips toward the ideal valences, in up to 6 rounds. Kept only if the region then has every edge in [emin,
// emax], no face under 3 degrees or turned against the input, no valence off the ideal by more than one, no input
// vertex or edge midpoint within it farther from the surface than it was and than the tip was, and its faces' distance
// to the input (bracketed) no larger than it was and than the tip's. Vertices marked in `fixed` (the snap's) may move,
// and lose their mark if they do; the tips are marked.
CapTipsResult cap_tips(TriMesh& mesh, const TriMesh& input, const ProjectionTarget& target, int kn, double emin,
                       double emax, double tolerance, std::vector<char>& fixed,
                       const triangle_tree::SurfaceTree* input_tree = nullptr);

// The same for the faces of `mesh` farthest from `input` (at most 8 attempts, farther than `tolerance` and than 0.8 of
// the farthest face or of `farthest_input`, the farthest input vertex's distance if larger, seven samples a face; none
// if that is more than emax; kn + 5 rings only): a vertex at the input point nearest the face's farthest point, the cap
// around it rebuilt, kept under the same tests except that the faces within the rings must end at least 5% nearer the
// input than the farthest of them was. One attempt a spot (a face whose point is within emax of a refused attempt's is
// not tried). `candidates` counts the faces taken, `tries` the attempts.
CapTipsResult cap_far_faces(TriMesh& mesh, const TriMesh& input, const ProjectionTarget& target, int kn, double emin,
                            double emax, double tolerance, std::vector<char>& fixed, double farthest_input = 0,
                            const triangle_tree::SurfaceTree* input_tree = nullptr);

// ---- data_dependent_flips.cpp ------------------------------------------------------------------------------

struct DataDependentFlips {
  std::size_t candidates = 0;  // edges of faces farther than the tolerance from the input
  std::size_t flips = 0;
  std::size_t relaxed_tries = 0, relaxed_flips = 0;  // flips with the vertices around relaxed: tried, kept
  double max_before = 0, max_after = 0;  // the largest sampled distance of a face to the input, before and after
};
// Flips the diagonal of the quads around faces farther than `tolerance` from `input` (farthest first) where the two
// new faces are nearer the input by 10% at least, the new edge lies in [emin, emax], no new angle is under 3
// degrees, no new face turns against an old one, and the valences stay within one of the ideal (6 inside, 4 on a
// border) with E_val (Eq 4.2) up by 2 at most. A pair of faces bridging a groove or cutting a ridge is replaced by
// the pair along it.
// With `target`, then the same flips where the new edge would lie outside [emin, emax] (from half emin to 1.7 emax),
// farthest first: the edge is flipped and the interior vertices within kn + 2 rings of the new edge's ends are
// relaxed (Error_b with the interval hinge, Eq 4.7) and projected onto `target`; kept only if the region has no
// more edges outside [emin, emax] or faces under 3 degrees than before, no face folds, the two new faces end nearer
// the input than 0.9 of the pair's distance d, and no other face moved and no input point near the region ends
// farther than the larger of d and its own distance before (relaxed_flips.cpp). Of the vertices with
// (*fixed)[index] != 0 (those the snap put on input vertices), those on a tip of the input (an angle deficit over 60
// degrees) stay; the others may move, their input vertices being watched like every input point.
DataDependentFlips data_dependent_flips(TriMesh& mesh, const TriMesh& input, double emin, double emax,
                                        double tolerance, const ProjectionTarget* target = nullptr, int kn = 2,
                                        const std::vector<char>* fixed = nullptr,
                                        const triangle_tree::SurfaceTree* input_tree = nullptr);

// ---- spatial_order.cpp ----------------------------------------------------------------------------------

// Rebuilds `mesh` with its vertices in Morton order of their positions and its faces by first vertex, so
// that surface neighbours are memory neighbours (deleted elements dropped; the projection memory kept).
// Returns false and leaves the mesh unchanged if a face cannot be re-added.
bool spatial_order(TriMesh& mesh);

// ---- midpoint_subdivision.cpp: the refinement of the coarse-to-fine remesh -----------------------------------

// Splits every triangle into four at its edge midpoints (every new edge half an old one; old vertices keep their
// valence, new ones have valence 6, or 4 on a border). Deleted elements are dropped and vertex properties are not
// kept; the result is in spatial memory order (as spatial_order leaves a mesh). Returns false and leaves the mesh
// unchanged if a face cannot be added (a non-manifold mesh).
bool midpoint_subdivision(TriMesh& mesh);

// ---- longest_edge_bisection.cpp -------------------------------------------------------------------------------

// Bisects the longest edges (OpenMesh's LongestEdgeT) until no edge is longer than max_edge; the new vertices lie
// at edge midpoints, so the surface is the same. Appends elements (no spatial reordering).
void longest_edge_bisection(TriMesh& mesh, double max_edge);

// ---- spring_relaxation.cpp: after a midpoint subdivision ----------------------------------------------------

// `steps` Jacobi steps of springs of rest length `target` on the edges, each interior vertex moved in its tangent
// plane by half the mean spring force of its ring (border vertices stay). A midpoint subdivision turns each
// triangle into four similar ones, so a flat coarse triangle leaves a patch of sheared ones, which a Laplacian
// low-pass filter keeps (an affine image of a regular patch is its fixed point) and springs even out. Deterministic
// for any thread count. Project onto the surface afterwards.
void spring_relaxation(TriMesh& mesh, double target, int steps);

// ---- regularize (correct_valence.cpp): valence optimisation that keeps every edge inside -------------

// After convergence: flips with J_mp > 0 (Eq 4.3) whose new diagonal may be outside [emin, emax] are tried
// with the kn-star of the new edge relaxed (Error_b with the interval hinge) and projected onto `target`;
// a flip is kept only if every edge at the moved vertices (and the new edge) is inside [emin, emax] and no
// face folds, otherwise positions and connectivity are restored. Passes repeat while flips are kept (at
// most `max_passes`). Returns the number of flips kept.
std::size_t regularize(TriMesh& mesh, const ProjectionTarget& target, int kn, double emin, double emax,
                       int max_passes = 10);

// ---- post_process.cpp (section 4.6) -------------------------------------------------------------------

// Runs the nonlinear optimizer without projection while the number of long+short edges decreases; where it stops
// decreasing, rounds of the stellar operations on [emin, emax] first (up to 3 in a row that do not lower it either);
// keeps the best state. Returns the number of rounds that improved.
int post_process(TriMesh& mesh, int kn, double emin, double emax);

// ---- surface_fit.cpp: least-squares fit of the remeshed surface to the input (after Algorithm 1) ---------

struct SurfaceFitSettings {
  int rounds = 2;               // linearise-and-solve rounds
  double max_offset = 0.4;      // largest move of a vertex off its place, as a fraction of emin
  double edge_stiffness = 0.3;  // weight of an edge's length change, against a sample's squared distance
  int settle_sweeps = 20;       // sweeps moving edges the solve took out of [emin, emax] back in, each round
  bool measure_input_after = true;  // measure input_rms_after (a tree of the result: 1-1.5% of a remesh)
};

struct SurfaceFitResult {
  double rms_before = 0, rms_after = 0;  // area-weighted RMS distance of the faces' quadrature points to the input
  // The same for the input's faces' points to the mesh (input_rms_after: 0 without measure_input_after).
  double input_rms_before = 0, input_rms_after = 0;
  std::size_t limited = 0;            // displacement halvings that kept an edge inside [emin, emax]
  std::size_t solver_iterations = 0;  // conjugate-gradient iterations, all rounds
  std::size_t settle_sweeps = 0;      // sweeps moving edges back into the interval, all rounds
};

// Moves every interior vertex in space so that the squared distance between the triangles and `surface`, both
// ways, plus a penalty on the edges' length changes, is least (sparse normal equations in 3x3 blocks, conjugate
// gradients); edges inside [emin, emax] before stay inside. Border vertices and those with (*fixed)[index] != 0
// stay where they are.
SurfaceFitResult fit_to_surface(TriMesh& mesh, const TriMesh& surface, double emin, double emax,
                                const SurfaceFitSettings& settings = {}, const std::vector<char>* fixed = nullptr,
                                const triangle_tree::SurfaceTree* input_tree = nullptr);

// ---- minimax_fit.cpp: the largest distance to the input lowered where it is set (after the surface fit) ---------

struct MinimaxFitSettings {
  int rounds = 1;         // scans of both surfaces, each followed by the search around its spots
  double share = 0.8;     // spots: farther than this share of the largest sampled distance ...
  double tolerance = 0;   // ... and than this (absolute)
};

struct MinimaxFitResult {
  double max_before = 0, max_after = 0;  // the largest sampled distance between the surfaces, before and after
  std::size_t spots = 0;                 // regions searched
  std::size_t moves = 0;                 // vertex moves kept
  std::size_t wide_moves = 0;            // of those, in the farthest region's second search (its ring movable too)
  double scan_seconds = 0;               // of the time taken, the scans of both surfaces
};

// Moves the vertices around the spots where the remeshed surface and `surface` are farthest apart (either way,
// sampled; spots farther than emax are left, and spots whose region is farther than emax + sqrt(emax^2 - emin^2),
// which no move within the interval brings within emax) so that the largest distance over each spot's region falls;
// edges inside [emin, emax] before stay inside. Border vertices, and those with (*fixed)[index] != 0, stay where they
// are.
// The output does not depend on the thread count.
MinimaxFitResult minimax_fit(TriMesh& mesh, const TriMesh& surface, double emin, double emax,
                             const MinimaxFitSettings& settings = {}, const std::vector<char>* fixed = nullptr,
                             const triangle_tree::SurfaceTree* input_tree = nullptr);

}  // namespace carbonmesh
