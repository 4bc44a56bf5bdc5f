// A vertex at each input tip the feature snap left cut off, with the cap around it rebuilt (not in the dissertation).
//
// The snap's insertion splits the face nearest a tip and relaxes kn + 2 rings around it with the snapped vertices
// held; where the tip rises far from the remeshed surface (bunny's ear tips, 0.6-1.1 away) the region has too few
// vertices for the cap, edges end 1.8-2.1 long and the insertion is refused. Here the region may grow and the snapped
// vertices in it may move: after the split, rounds of relaxation (Error_b with the interval hinge, Eq 4.7, projected
// onto the input), splits of the long edges at their midpoints, collapses of the short ones and flips toward the
// ideal valences, until every edge of the region is inside. Tried on a copy of the mesh, farthest input vertex first,
// and kept only if no face has an angle under 3 degrees or turns against the input, no valence is off the ideal by
// more than one, no input point (vertex or edge midpoint) within the rings ends farther from the surface than it was
// and than the tip was, and the faces within the rings end no farther from the input (their bracketed bound) than
// they were and than the tip was: nothing moves beyond the distance the cap takes away.
//
// Face caps (cap_far_faces) do the same where a face, not an input vertex, sets the largest distance: a face across a
// saddle or a crease whose corners the snap and the minimax fit cannot move (armadillo moved by the benchmark's first
// rigid motion: a face with edges 1.798 and 1.202 long and a snapped corner, 0.5497 from the input after every step).
// The vertex goes to the input point nearest the face's farthest point, and the cap is kept only if the faces within
// the rings end at least 5% nearer the input than the farthest of them was.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "carbonmesh/remesh/garbage_collection.hpp"
#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/remesh_steps.hpp"
#include "carbonmesh/remesh/triangle_tree.hpp"
#include "farthest_point.hpp"
#include "flip_quad.hpp"
#include "flips_toward_input.hpp"
#include "local_region.hpp"
#include "remesh_geometry.hpp"
#include "threads.hpp"
#include "turned_against_input.hpp"

namespace carbonmesh {
namespace {

using namespace triangle_tree;

constexpr std::size_t kTips = 8;  // the farthest input vertices tried, at most ...
constexpr double kShare = 0.8;    // ... and those farther than this share of the farthest (as in minimax_fit)
constexpr int kRounds = 6;        // relax-split-collapse-flip rounds before an attempt is given up
constexpr int kPasses = 3;        // relax-and-project passes a round
constexpr int kStalledRounds = 2;  // rounds without fewer flaws than before that end an attempt
// Rings around the tip in an attempt: kn + 5, and kn + 7 if that leaves edges outside (bunny's ear tips under six
// rigid motions, measured with a looser acceptance test: with kn + 3 rings 1 of 6 maxima fell, with kn + 5 rings 3,
// with kn + 7 rings 2, each taking tips where the other left edges outside).
constexpr std::array<int, 2> kExtraRings = {5, 7};
constexpr double kTolerance = 1e-4;         // the faces' distance to the input bracketed to within this (as
constexpr std::size_t kPiecesPerFace = 64;  // carbonmesh stats --ref), with at most this many pieces a face
constexpr double kFaceGain = 0.95;  // a face cap is kept only if the faces' bound falls by this factor at least
constexpr int kMaxFlips = 200;  // flips toward the ideal valences at a time, at most (a guard against cycles)

// Flips of the edges at `vertices` while one lowers E_val (Eq 4.3) and keeps its quad's shape.
void flips_toward_ideal(TriMesh& mesh, const std::vector<TriMesh::VertexHandle>& vertices,
                        std::vector<TriMesh::EdgeHandle>& edges) {
  for (int flips = 0, again = 1; again && flips < kMaxFlips;) {
    again = 0;
    edges.clear();
    for (auto v : vertices)
      for (auto e : mesh.ve_range(v)) edges.push_back(e);
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    for (auto e : edges) {
      if (mesh.is_boundary(e) || !mesh.is_flip_ok(e) || valence_improvement(mesh, e) <= 0) continue;
      const FlipQuad q = quad(mesh, e);
      if (!geometry::flip_keeps_shape(mesh.point(q.a), mesh.point(q.b), mesh.point(q.c), mesh.point(q.d))) continue;
      mesh.flip(e);
      ++flips;
      again = 1;
      break;
    }
  }
}

// Edges outside [emin, emax] and vertices off their ideal valence by more than one, in the whole mesh. A cap's splits
// and collapses move the rings, so that a vertex the attempt moved or flipped can end beyond the rings its region
// checks (bunny under a rigid motion, with another damping of the relaxations: a face cap kept with 2 short edges and a
// valence off by 2 outside them).
std::pair<std::size_t, std::size_t> flaws_everywhere(const TriMesh& mesh, double emin, double emax) {
  const EdgeStats edges = edge_stats(mesh, {emin, emax});
  const std::size_t outside = edges.long_edges + edges.short_edges;
  std::size_t off = 0;
  for (auto v : mesh.vertices())
    if (!mesh.is_isolated(v)) off += std::abs(geometry::valence(mesh, v) - ideal_valence(mesh, v)) > 1 ? 1 : 0;
  return {outside, off};
}

// How an attempt ended: kept, refused with edges left outside (or faces under 3 degrees), or refused otherwise.
enum class Outcome { kKept, kFlaws, kRefused };

// What every attempt reads, and its scratch space.
class TipCapper {
 public:
  TipCapper(const Tree& input_tree, const ProjectionTarget& target, double emin, double emax, const char* label)
      : input_tree_(input_tree), target_(target), emin_(emin), emax_(emax), local_(emin, emax), label_(label) {}

  // The debug lines of the attempts since the last call, logged in order (attempts run side by side: see Lane).
  void flush_notes() {
    for (const std::string& line : notes_) spdlog::debug("{}", line);
    notes_.clear();
  }
  void drop_notes() { notes_.clear(); }

  // A vertex at q in a copy of `mesh` (its face `nearest` split there) and the cap around it rebuilt within `rings`
  // rings; kept, with the copy in m and its fixed vertices in marks, if it passes the tests (see cap_tips(); with a
  // `gain`, the faces' bound must end under `gain` times what it was instead).
  Outcome attempt(const TriMesh& mesh, const std::vector<char>& fixed, TriMesh::FaceHandle nearest, const Vec3& q,
                  double distance, int rings, const std::vector<Vec3>& points, TriMesh& m, std::vector<char>& marks,
                  double gain = 0) {
    // The input points within the rings (watched_); their distances to the faces two rings beyond and the bound of the
    // faces within the rings, before the attempt, are measured at the end, when the other tests have passed (on
    // `mesh`, which the attempt leaves as it was): most attempts are refused before.
    const auto corner = mesh.to_vertex_handle(mesh.halfedge_handle(nearest));
    m = mesh;
    const auto tip = m.split(nearest, q);
    // The snapped vertices may move here (held, they left bunny's maxima higher on 3 of its 6 benchmark runs); one
    // that moves is no longer on its feature and loses its mark. The tip is held.
    marks = fixed;
    marks.resize(m.n_vertices(), 0);
    marks[static_cast<std::size_t>(tip.idx())] = 1;
    local_.collect(m, tip, 1, region_);
    flips_toward_ideal(m, region_, edges_);
    std::size_t flaws = 0, fewest = std::numeric_limits<std::size_t>::max();
    for (int round = 0, stalled = 0; round < kRounds; ++round) {
      local_.collect(m, tip, rings - 1, inner_);
      variables_.clear();
      for (auto w : inner_)
        if (w != tip && !m.is_boundary(w)) variables_.push_back(w);
      for (int pass = 0; pass < kPasses; ++pass) {
        optimize_vertices(m, variables_, emin_, emax_);
        for (auto w : variables_) project_with_ring(m, target_, w, neighbors_);
      }
      local_.collect(m, tip, rings, region_);
      flaws = local_.flaws(m, region_);
      if (flaws == 0) break;
      if (flaws < fewest) {
        fewest = flaws;
        stalled = 0;
      } else if (++stalled == kStalledRounds) {
        break;
      }
      // A vertex in the middle of each long edge of the relaxed vertices (on the input), ...
      collect_edges(m, [&](double l) { return l > emax_; });
      for (auto e : edges_) {
        if (m.is_boundary(e)) continue;  // (its middle would leave the border curve)
        const auto h = m.halfedge_handle(e, 0);
        const auto w = m.new_vertex(0.5 * (m.point(m.from_vertex_handle(h)) + m.point(m.to_vertex_handle(h))));
        m.split(e, w);
        project_with_ring(m, target_, w, neighbors_);
      }
      marks.resize(m.n_vertices(), 0);
      // ... each short one collapsed to its middle (not at the tip or a border), ...
      collect_edges(m, [&](double l) { return l < emin_; });
      for (auto e : edges_) {
        if (m.status(e).deleted() || geometry::edge_length(m, e) >= emin_) continue;
        const auto h = m.halfedge_handle(e, 0);
        const auto a = m.from_vertex_handle(h), b = m.to_vertex_handle(h);
        if (a == tip || b == tip || m.is_boundary(a) || m.is_boundary(b)) continue;
        const Vec3 middle = 0.5 * (m.point(a) + m.point(b));
        if (!collapse_ok(m, h, middle, emax_)) continue;
        m.collapse(h);
        m.set_point(b, middle);
        project_with_ring(m, target_, b, neighbors_);
      }
      // ... and flips toward the ideal valences.
      local_.collect(m, tip, rings - 1, inner_);
      flips_toward_ideal(m, inner_, edges_);
    }
    if (flaws > 0) {
      note("{}: {} rings, {} flaws left", label_, rings, flaws);
      return Outcome::kFlaws;
    }
    local_.collect(m, tip, rings, region_);
    for (auto w : region_)
      if (std::abs(geometry::valence(m, w) - ideal_valence(m, w)) > 1) {
        note("{}: {} rings, a valence off the ideal by more than one", label_, rings);
        return Outcome::kRefused;
      }
    if (const auto [outside_after, off_after] = flaws_everywhere(m, emin_, emax_); outside_after + off_after > 0) {
      const auto [outside_before, off_before] = flaws_everywhere(mesh, emin_, emax_);  // (only then needed)
      if (outside_after > outside_before || off_after > off_before) {
        note("{}: {} rings, {} edges outside and {} valences off by more than one beyond the rings (before {} and {})",
             label_, rings, outside_after, off_after, outside_before, off_before);
        return Outcome::kRefused;
      }
    }
    local_.faces(m, region_, faces_);
    for (auto f : faces_)
      if (turned_against_input(input_tree_, m, f)) {
        note("{}: {} rings, a face turned against the input", label_, rings);
        return Outcome::kRefused;
      }
    // No watched input point may end farther from the surface than it was and than the tip was, and the faces within
    // the rings may end no farther from the input than they were and than the tip was.
    local_.collect(mesh, corner, rings, region_);
    double radius = 0;
    for (auto v : region_) radius = std::max(radius, (mesh.point(v) - q).norm());
    watched_.clear();
    for (const Vec3& p : points)
      if ((p - q).norm() <= radius) watched_.push_back(p);
    local_.collect(mesh, corner, rings + 2, region_);
    local_.faces(mesh, region_, faces_);
    region_triangles(mesh);
    distances_to_region(watched_before_);
    local_.collect(m, tip, rings + 2, region_);
    local_.faces(m, region_, faces_);
    region_triangles(m);
    distances_to_region(watched_after_);
    std::size_t farther = 0;
    for (std::size_t i = 0; i < watched_.size(); ++i)
      farther += watched_after_[i] > std::max(watched_before_[i], distance);
    if (farther > 0) {
      note("{}: {} rings, {} of {} watched input points farther than they were and than the tip was", label_, rings,
           farther, watched_.size());
      return Outcome::kRefused;
    }
    local_.collect(m, tip, rings, region_);
    local_.faces(m, region_, faces_);
    region_triangles(m);
    const double forward_after = forward_bound();
    local_.collect(mesh, corner, rings, region_);
    local_.faces(mesh, region_, faces_);
    region_triangles(mesh);
    const double forward_before = forward_bound();
    note("{}: {} rings, the faces' distance bound {:.4f} -> {:.4f} (the tip {:.4f})", label_, rings, forward_before,
         forward_after, distance);
    if (forward_after > (gain > 0 ? gain * forward_before : std::max(forward_before, distance)))
      return Outcome::kRefused;
    for (auto v : m.vertices()) {
      const auto i = static_cast<std::size_t>(v.idx());
      if (v != tip && i < mesh.n_vertices() && marks[i] && m.point(v) != mesh.point(v)) marks[i] = 0;
    }
    // Without the deleted elements, the marks following their vertices.
    OpenMesh::VPropHandleT<char> mark;
    m.add_property(mark);
    for (auto v : m.vertices()) m.property(mark, v) = marks[static_cast<std::size_t>(v.idx())];
    collect_garbage(m);
    marks.assign(m.n_vertices(), 0);
    for (auto v : m.vertices()) marks[static_cast<std::size_t>(v.idx())] = m.property(mark, v);
    m.remove_property(mark);
    return Outcome::kKept;
  }

 private:
  template <class... Args>
  void note(fmt::format_string<Args...> format, Args&&... args) {
    if (spdlog::should_log(spdlog::level::debug)) notes_.push_back(fmt::format(format, std::forward<Args>(args)...));
  }

  // The triangles of faces_, into triangles_.
  void region_triangles(const TriMesh& mesh) {
    triangles_.clear();
    for (auto f : faces_) {
      Vec3 a, b, c;
      geometry::face_points(mesh, f, a, b, c);
      triangles_.emplace_back(to_point(a), to_point(b), to_point(c));
    }
  }

  // The distances of the points watched_ to triangles_, into `out`.
  void distances_to_region(std::vector<double>& out) const {
    out.assign(watched_.size(), std::numeric_limits<double>::infinity());
    if (triangles_.empty()) return;
    Tree tree(triangles_.begin(), triangles_.end());
    tree.accelerate_distance_queries();
    for (std::size_t i = 0; i < watched_.size(); ++i) out[i] = std::sqrt(tree.squared_distance(to_point(watched_[i])));
  }

  // The bound of the distance of triangles_ to the input (bracketed to within kTolerance).
  double forward_bound() const {
    return farthest_point(triangles_, input_tree_, kTolerance, kPiecesPerFace * triangles_.size()).bound;
  }

  // The edges at the relaxed vertices (inner_) whose length passes `select`, into edges_ (each once).
  template <class Select>
  void collect_edges(const TriMesh& m, Select select) {
    edges_.clear();
    for (auto w : inner_)
      for (auto e : m.ve_range(w))
        if (select(geometry::edge_length(m, e))) edges_.push_back(e);
    std::sort(edges_.begin(), edges_.end());
    edges_.erase(std::unique(edges_.begin(), edges_.end()), edges_.end());
  }

  const Tree& input_tree_;
  const ProjectionTarget& target_;
  double emin_, emax_;
  LocalRegion local_;
  const char* label_;  // of the log lines
  std::vector<std::string> notes_;
  std::vector<TriMesh::VertexHandle> region_, inner_, variables_;
  std::vector<TriMesh::FaceHandle> faces_;
  std::vector<TriMesh::EdgeHandle> edges_;
  std::vector<Vec3> neighbors_, watched_;
  std::vector<double> watched_before_, watched_after_;
  Triangles triangles_;
};

// The input points an attempt watches: the input's vertices and edge midpoints.
std::vector<Vec3> watched_points(const TriMesh& input) {
  std::vector<Vec3> points;
  for (auto v : input.vertices()) points.push_back(input.point(v));
  for (auto e : input.edges()) {
    const auto h = input.halfedge_handle(e, 0);
    points.push_back(0.5 * (input.point(input.from_vertex_handle(h)) + input.point(input.to_vertex_handle(h))));
  }
  return points;
}

// One thread's attempt (TipCapper::attempt reads `mesh` and writes only its own copy): attempts run side by side, one
// a thread, and their outcomes are taken in order; those after a kept one are tried again on the mesh it left. So the
// result is that of one thread taking the attempts in order (most are refused: bunny's 14 in 0.23 s on one thread).
struct Lane {
  TipCapper capper;
  TriMesh capped;
  std::vector<char> marks;
  bool tried = false, kept = false;
};

std::vector<Lane> lanes(const Tree& input_tree, const ProjectionTarget& target, double emin, double emax,
                        const char* label) {
  return std::vector<Lane>(static_cast<std::size_t>(std::max(1, max_threads())),
                           Lane{TipCapper(input_tree, target, emin, emax, label), {}, {}});
}

// run(j) for j < count on `count` threads.
template <class Run>
void side_by_side(std::size_t count, Run run) {
  if (count == 0) return;
  const int n = static_cast<int>(count);
#pragma omp parallel for schedule(static, 1) num_threads(n)
  for (int j = 0; j < n; ++j) run(static_cast<std::size_t>(j));
}

}  // namespace

CapTipsResult cap_tips(TriMesh& mesh, const TriMesh& input, const ProjectionTarget& target, int kn, double emin,
                       double emax, double tolerance, std::vector<char>& fixed, const SurfaceTree* input_tree) {
  CapTipsResult result;
  collect_garbage(mesh);
  fixed.resize(mesh.n_vertices(), 0);
  if (input.n_faces() == 0 || mesh.n_faces() == 0) return result;
  std::optional<SurfaceTree> own;
  const SurfaceTree& input_surface = input_tree ? *input_tree : own.emplace(input);
  // The remeshed surface's triangles in face order and their tree (built again after each kept cap).
  Triangles triangles = triangles_of(mesh);
  auto tree = std::make_unique<Tree>(triangles.begin(), triangles.end());
  tree->build();  // before the threads query it
  tree->accelerate_distance_queries();
  // The interior input vertices farther than the tolerance, farthest first (ties by index).
  std::vector<TriMesh::VertexHandle> interior;
  for (auto v : input.vertices())
    if (!input.is_boundary(v)) interior.push_back(v);
  std::vector<double> to_surface(interior.size());
  const int ni = static_cast<int>(interior.size());
#pragma omp parallel for schedule(dynamic, 1024)
  for (int i = 0; i < ni; ++i) {
    const auto k = static_cast<std::size_t>(i);
    to_surface[k] = std::sqrt(tree->squared_distance(to_point(input.point(interior[k]))));
  }
  std::vector<std::pair<double, int>> far;
  for (std::size_t k = 0; k < interior.size(); ++k)
    if (to_surface[k] > tolerance) far.emplace_back(to_surface[k], interior[k].idx());
  std::sort(far.begin(), far.end(), [](const auto& x, const auto& y) {
    return x.first != y.first ? x.first > y.first : x.second < y.second;
  });
  // Those that set the largest distance: within kShare of the farthest. None where that is farther than emax: a part
  // of the input is cut off there (a slit or rim narrower than the interval), which sets the maximum and which no
  // cap mends (camelhead's mouth and the flat disc 20:1 of the generated shapes: 0.7 and 1.5 s of attempts just
  // under emax, none kept).
  if (!far.empty()) result.farthest = far.front().first;
  while (!far.empty() && far.back().first < kShare * far.front().first) far.pop_back();
  if (!far.empty() && far.front().first > emax) far.clear();
  if (far.size() > kTips) far.resize(kTips);
  result.candidates = far.size();
  const std::vector<Vec3> points = watched_points(input);
  std::vector<Lane> lane = lanes(input_surface.tree(), target, emin, emax, "cap tips");
  for (std::size_t next = 0; next < far.size();) {
    // The next candidates, one a thread, on the mesh as earlier caps left it.
    const std::size_t count = std::min(lane.size(), far.size() - next);
    side_by_side(count, [&](std::size_t j) {
      Lane& l = lane[j];
      const Vec3 q = input.point(TriMesh::VertexHandle(far[next + j].second));
      // The face nearest q.
      const auto hit = tree->closest_point_and_primitive(to_point(q));
      const TriMesh::FaceHandle nearest(static_cast<int>(hit.second - triangles.cbegin()));
      const double nearest_d = (to_vec(hit.first) - q).norm();
      l.tried = nearest_d > tolerance;
      l.kept = false;
      if (!l.tried) return;
      for (const int extra : kExtraRings) {
        const Outcome outcome = l.capper.attempt(mesh, fixed, nearest, q, nearest_d, kn + extra, points, l.capped,
                                                 l.marks);
        l.kept = outcome == Outcome::kKept;
        if (outcome != Outcome::kFlaws) break;  // more rings only where edges were left outside
      }
    });
    // Their outcomes in order, up to the first kept one (the mesh changes there).
    std::size_t taken = 0;
    for (; taken < count; ++taken) {
      Lane& l = lane[taken];
      if (!l.tried) continue;
      ++result.tries;
      l.capper.flush_notes();
      const auto& [distance, index] = far[next + taken];
      spdlog::debug("cap tips: input vertex {}, {:.4f} from the surface: {}", index, distance,
                    l.kept ? "capped" : "refused");
      if (!l.kept) continue;
      ++result.capped;
      result.added += static_cast<long>(l.capped.n_vertices()) - static_cast<long>(mesh.n_vertices());
      std::swap(mesh, l.capped);
      std::swap(fixed, l.marks);
      triangles = triangles_of(mesh);
      tree = std::make_unique<Tree>(triangles.begin(), triangles.end());
      tree->build();  // (before the threads query it)
      tree->accelerate_distance_queries();
      ++taken;
      break;
    }
    for (std::size_t j = taken; j < count; ++j) lane[j].capper.drop_notes();  // (tried again)
    next += taken;
  }
  return result;
}

CapTipsResult cap_far_faces(TriMesh& mesh, const TriMesh& input, const ProjectionTarget& target, int kn, double emin,
                            double emax, double tolerance, std::vector<char>& fixed, double farthest_input,
                            const SurfaceTree* input_tree) {
  CapTipsResult result;
  collect_garbage(mesh);
  fixed.resize(mesh.n_vertices(), 0);
  if (input.n_faces() == 0 || mesh.n_faces() == 0) return result;
  std::optional<SurfaceTree> own;
  const Tree& tree = (input_tree ? *input_tree : own.emplace(input)).tree();
  // The faces' sampled distances to the input, measured again after each kept cap.
  std::vector<double> distance = face_distances(mesh, tree, tolerance);
  // The faces that set the largest distance, within kShare of it, the input vertices' included: none where that is
  // more than emax (a part of the input cut off, as in cap_tips(): camelhead's mouth, where 8 attempts at faces
  // 0.55-0.66 from the input took 1.5 s and none was kept).
  const double farthest =
      std::max(farthest_input, distance.empty() ? 0.0 : *std::max_element(distance.begin(), distance.end()));
  result.farthest = farthest;
  if (farthest > emax) return result;
  const std::vector<Vec3> points = watched_points(input);
  std::vector<Lane> lane = lanes(tree, target, emin, emax, "face caps");
  struct Pick {
    TriMesh::FaceHandle face;
    Vec3 q;
    double distance;
    std::size_t candidates;  // the faces taken up to this one since the pick before (skipped ones and this one)
  };
  std::vector<Pick> picks;
  std::vector<Vec3> refused;  // the input points of the refused attempts
  for (;;) {
    // The next faces to try, one a thread, picked as one thread would pick them if every attempt before were refused.
    picks.clear();
    std::vector<Vec3> skip = refused;
    std::size_t pending = 0;
    while (picks.size() < lane.size() && result.tries + picks.size() < kTips) {
      const auto best = std::max_element(distance.begin(), distance.end());
      if (*best <= tolerance || *best < kShare * farthest) break;
      ++pending;
      const TriMesh::FaceHandle face(static_cast<int>(best - distance.begin()));
      *best = -1;  // (taken)
      Vec3 a, b, c;
      geometry::face_points(mesh, face, a, b, c);
      const Triangles one = {Triangle(to_point(a), to_point(b), to_point(c))};
      const Farthest far = farthest_point(one, tree, kTolerance, kPiecesPerFace);
      const Vec3 q = to_vec(tree.closest_point(far.at));
      // A face next to one whose attempt was refused has its farthest point at the same spot: the attempt would
      // rebuild the same rings (bunny's attempts 8 -> 6).
      if (std::any_of(skip.begin(), skip.end(), [&](const Vec3& r) { return (r - q).norm() < emax; })) continue;
      picks.push_back({face, q, far.distance, pending});
      pending = 0;
      skip.push_back(q);
    }
    // With the tips' first ring count only (the second, where edges were left outside, kept no face cap on the seven
    // models and their benchmark motions, and doubled the time of an attempt).
    side_by_side(picks.size(), [&](std::size_t j) {
      Lane& l = lane[j];
      l.kept = l.capper.attempt(mesh, fixed, picks[j].face, picks[j].q, picks[j].distance, kn + kExtraRings[0], points,
                                l.capped, l.marks, kFaceGain) == Outcome::kKept;
    });
    // Their outcomes in order, up to the first kept one (the mesh and the faces' distances change there).
    bool kept = false;
    for (std::size_t j = 0; j < picks.size(); ++j) {
      Lane& l = lane[j];
      if (kept) {
        l.capper.drop_notes();  // (picked again)
        continue;
      }
      result.candidates += picks[j].candidates;
      ++result.tries;
      l.capper.flush_notes();
      spdlog::debug("face caps: a face {:.4f} from the input: {}", picks[j].distance, l.kept ? "capped" : "refused");
      if (!l.kept) {
        refused.push_back(picks[j].q);
        continue;
      }
      kept = true;
      ++result.capped;
      result.added += static_cast<long>(l.capped.n_vertices()) - static_cast<long>(mesh.n_vertices());
      std::swap(mesh, l.capped);
      std::swap(fixed, l.marks);
      distance = face_distances(mesh, tree, tolerance);
    }
    if (kept) continue;
    result.candidates += pending;  // (skipped after the last pick)
    if (picks.size() < lane.size() || result.tries == kTips) break;  // no face left to pick, or enough tries
  }
  return result;
}

}  // namespace carbonmesh
