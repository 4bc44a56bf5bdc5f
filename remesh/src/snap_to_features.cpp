// Vertices moved onto the input points that the remeshed surface cuts off (not in the dissertation).
//
// With every vertex on the input and every edge in [emin, emax], a feature of the input narrower than an edge
// (an ear's rim, a cone tip, a groove) is bridged by triangles whose vertices happen to lie beside it: the
// Hausdorff distance is set there, up to most of an edge, and offsets along the normals (fit_to_surface)
// cannot reach it. Here each input vertex farther from the remeshed surface than `tolerance` pulls one of the
// nearest free remeshed vertices onto itself; that vertex is then held fixed while the interior vertices of
// its kn+2 rings are relaxed (Error_b with the interval hinge, Eq 4.7) and projected back onto the input. The
// move is kept only if the region gains no edge outside [emin, emax], no face under 3 degrees and no folded
// face, and if every input vertex and input edge midpoint nearest one of the region's faces, and every face the
// move changed, ends nearer than the farthest of those input points was at the start of the round (so that distance
// never grows, and the moved faces do not go farther from the input than that either); otherwise every position is
// restored. Farthest input vertices first, in rounds: the distances of the input points next to a kept move are
// measured again (locally) before the next round, so a ridge is captured vertex by vertex, and those whose move
// failed are tried once more in a new neighbourhood; of the points nearest one remeshed face, a round tries the four
// farthest (a rim the remesh pulls in leaves thousands of points nearest a few faces). Moves far enough apart that
// neither can see the other run on all threads (Schedule below), with the result of one thread taking them in order.
// Last, the farthest input vertices that no move reached (a tip, where the remeshed vertices near it would leave their
// neighbours behind) get a vertex of their own, a split of the face nearest each with flips toward the ideal
// valences, under the same tests (on one thread: the mesh grows).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdlib>
#include <limits>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <vector>

#include <spdlog/spdlog.h>

#include "carbonmesh/remesh/remesh_steps.hpp"
#include "carbonmesh/remesh/triangle_tree.hpp"
#include "local_region.hpp"
#include "remesh_geometry.hpp"
#include "threads.hpp"
#include "turned_against_input.hpp"

namespace carbonmesh {
namespace {

using namespace triangle_tree;

constexpr int kRounds = 6;           // at most; a round that keeps no move ends the step
constexpr std::size_t kChoices = 2;  // remeshed vertices tried per input vertex, nearest first (on armadillo a
                                     // third choice was kept in 5 of 105 tries)
constexpr int kRelaxRings = 2;      // the free vertices within kn + 2 rings of a moved vertex are relaxed around it
                                     // (kn + 1: armadillo's farthest input vertex, a cone tip 1.06 from the nearest
                                     // remeshed vertices, stayed 0.542 from the result; kn + 2: 0.482; kn + 3: 0.490,
                                     // the snap twice as long as with kn + 1)
constexpr int kPasses = 3;           // relax-and-project passes before a move is given up (kept at the first
                                     // clean one; given up after the second if that left no fewer flaws than the
                                     // first: on bunny, armadillo and a sphere with 2% noise 10 of 437 such third
                                     // passes kept a move, 21 of 338 where the second had reduced them)
constexpr std::size_t kInsertFlips = 6;  // flips at most around a vertex inserted at an input vertex
constexpr int kVisits = 2;  // tries of one input vertex in the rounds: the first and one more in a new neighbourhood
                            // (retries kept 5 moves of 212 on the seven seed-protocol models, 2 of them third tries;
                            // on an ellipsoid 10 x 5 x 2 whose rim the remesh pulls in, each kept move made
                            // thousands of points try again: 0 of 3917 retries kept, the snap 97% of the remesh time)
constexpr int kPerFace = 4;  // input points nearest one remeshed face tried in a round, farthest first (the others
                             // wait for a later round): on an ellipsoid 12 x 4 x 1 whose rim the remesh pulls in,
                             // 9012 candidates had 36 nearest faces (bunny: 146 on 133), and 2910 first tries of
                             // them kept nothing; with 2 an ellipsoid 10 x 1 x 1 ended 0.48 from its input, not 0.38
constexpr std::size_t kInsertions = 16;  // the farthest input vertices left that get an insertion tried (each try about
                                         // 3 ms, every watched point measured; of the 22 kept on the seven
                                         // seed-protocol models in up to 192 tries each, 15 were among the first 16,
                                         // the other 7 on armadillo, whose maximum they did not move)
constexpr std::size_t kNotCounted = static_cast<std::size_t>(-1);  // try_snap() counts the flaws before the move
constexpr double kProgressSeconds = 1.0;  // a round that takes longer is logged at info level (else debug)
constexpr std::size_t kHopelessFlaws = 8;  // more new flaws than this after a pass: given up at once (no kept move on
                                           // the seven seed-protocol models or a sphere with 2% noise had more than 8
                                           // after any pass; 25-39% of the failed ones had after the first)

struct Distance {
  double d = 0;
  int face = -1;  // the remeshed face nearest the input vertex (-1: not measured, a border or isolated vertex)
};

bool measured(const TriMesh& input, TriMesh::VertexHandle v, bool borders) {
  return !input.status(v).deleted() && (borders || !input.is_boundary(v)) && !input.is_isolated(v);
}

// The input points the snap measures: the input's vertices (indices 0 to vertices - 1: the candidates) and then the
// midpoints of its edges, watched so that a move does not take the surface off an input edge between two vertices
// (a crease that the moved faces cut: bunny's base rim went 0.65 -> 0.72 from the result with kn + 2 rings relaxed
// and only the vertices watched).
struct InputPoints {
  std::vector<Vec3> points;
  std::vector<char> interior, all;  // measured: the points off the input's border / every point (both steps)
  std::size_t vertices = 0;
};

InputPoints input_points(const TriMesh& input, bool edges) {
  InputPoints out;
  out.vertices = input.n_vertices();
  for (std::size_t i = 0; i < out.vertices; ++i) {  // (every index: the candidates are input vertex indices)
    const TriMesh::VertexHandle v(static_cast<int>(i));
    out.points.push_back(input.point(v));
    out.interior.push_back(measured(input, v, false));
    out.all.push_back(measured(input, v, true));
  }
  if (!edges) return out;
  for (auto e : input.edges()) {
    const auto h = input.halfedge_handle(e, 0);
    const auto a = input.from_vertex_handle(h), b = input.to_vertex_handle(h);
    out.points.push_back(0.5 * (input.point(a) + input.point(b)));
    out.interior.push_back(measured(input, a, false) && measured(input, b, false));
    out.all.push_back(measured(input, a, true) && measured(input, b, true));
  }
  return out;
}

// The distances of the input points marked in `which` to the remeshed surface, into `out` (one AABB tree; parallel,
// one slot per point); the others are left as they are.
void measure_input(const TriMesh& mesh, const InputPoints& input, const std::vector<char>& which,
                   std::vector<Distance>& out) {
  out.resize(input.points.size());
  const Triangles triangles = triangles_of(mesh);
  if (triangles.empty()) return;
  Tree tree(triangles.begin(), triangles.end());
  tree.build();
  tree.accelerate_distance_queries();
  const int n = static_cast<int>(input.points.size());
#pragma omp parallel for schedule(dynamic, 512)
  for (int i = 0; i < n; ++i) {
    if (!which[static_cast<std::size_t>(i)]) continue;
    const Point q = to_point(input.points[static_cast<std::size_t>(i)]);
    const auto [closest, primitive] = tree.closest_point_and_primitive(q);
    Distance& d = out[static_cast<std::size_t>(i)];
    d.d = std::sqrt(CGAL::squared_distance(q, closest));
    d.face = static_cast<int>(primitive - triangles.begin());  // triangles_of lists the faces in order
  }
}

// The distance of q to the faces around `face` (corners within `rings` of its first corner), after a local
// change near it.
Distance local_distance(const TriMesh& mesh, const Vec3& q, TriMesh::FaceHandle face, int rings, LocalRegion& local,
                        std::vector<TriMesh::VertexHandle>& around, std::vector<TriMesh::FaceHandle>& faces) {
  Distance best{std::numeric_limits<double>::infinity(), -1};
  local.collect(mesh, mesh.to_vertex_handle(mesh.halfedge_handle(face)), rings, around);
  local.faces(mesh, around, faces);
  const Point p = to_point(q);
  for (auto f : faces) {
    Vec3 a, b, c;
    geometry::face_points(mesh, f, a, b, c);
    const double d = std::sqrt(CGAL::squared_distance(p, Triangle(to_point(a), to_point(b), to_point(c))));
    if (d < best.d || (d == best.d && f.idx() < best.face)) best = {d, f.idx()};
  }
  return best;
}

// Input vertex indices, farthest from the remeshed surface first (ties by index).
void sort_farthest_first(std::vector<int>& candidates, const std::vector<Distance>& distances) {
  std::sort(candidates.begin(), candidates.end(), [&](int a, int b) {
    const double da = distances[static_cast<std::size_t>(a)].d, db = distances[static_cast<std::size_t>(b)].d;
    return da != db ? da > db : a < b;
  });
}

// What every move of a round reads and writes: the mesh, the input points' distances as measured at the start of
// the round, and the per-vertex marks.
struct SnapState {
  SnapState(TriMesh& m, const TriMesh& in, const InputPoints& p, const ProjectionTarget& t, int k, double lo, double hi)
      : mesh(m), input(in), points(p), target(t), kn(k), emin(lo), emax(hi) {}
  TriMesh& mesh;
  const TriMesh& input;
  const InputPoints& points;
  const ProjectionTarget& target;
  int kn;
  double emin, emax;
  std::vector<char> fixed, touched, tried;
  std::vector<int> visits;  // rounds' tries of each input vertex (at most kVisits)
  std::vector<Distance> distances;
  // Upper bounds of the input points' distances in the round, each the distance to one face at most (kept moves
  // update them).
  std::vector<Distance> upper;
  // Input points by their nearest face (as measured at the start of the round): first_near[f], then next_near[i].
  std::vector<int> first_near, next_near;
  double round_max = 0;  // the farthest input point at the start of the round
  const Tree* input_tree = nullptr;  // the input's faces
  bool borders = false;   // the step for the input's border vertices: border vertices slide in the relaxation too

  // Links the input points by the face that sets their distance in `by` (the distances, or their upper bounds), and
  // sets round_max to the farthest of them.
  void link_by_face(const std::vector<Distance>& by) {
    first_near.assign(mesh.n_faces(), -1);
    round_max = 0;
    for (std::size_t i = 0; i < by.size(); ++i) {
      round_max = std::max(round_max, by[i].d);
      if (by[i].face < 0) continue;
      next_near[i] = first_near[static_cast<std::size_t>(by[i].face)];
      first_near[static_cast<std::size_t>(by[i].face)] = static_cast<int>(i);
    }
  }
};

// One thread's scratch space and counts; visit() is the move of one candidate input vertex.
struct Worker {
  LocalRegion local, search;
  std::vector<TriMesh::VertexHandle> region, inner, variables, around;
  std::vector<std::pair<TriMesh::VertexHandle, Vec3>> saved;
  std::vector<TriMesh::FaceHandle> region_faces;
  std::vector<std::pair<TriMesh::FaceHandle, Vec3>> normals;
  std::vector<TriMesh::FaceHandle> moved_faces, around_faces;
  std::vector<Distance> watched_upper;
  std::vector<unsigned> moved_mark;  // == move_stamp: moved in this move, from moved_from
  std::vector<Vec3> moved_from;
  unsigned move_stamp = 0;
  std::vector<Vec3> neighbors;
  std::vector<int> watched;
  std::vector<std::pair<double, int>> choices;
  std::vector<TriMesh::EdgeHandle> flipped;
  std::vector<int> affected;
  bool remeasure = false;  // watched points measured, not bounded (after a face split)
  std::size_t tries = 0, snapped = 0;

  Worker(double emin, double emax) : local(emin, emax), search(emin, emax) {}

  void project(SnapState& s, TriMesh::VertexHandle v) { project_with_ring(s.mesh, s.target, v, neighbors); }

  Distance measure(const SnapState& s, int i) {
    return local_distance(s.mesh, s.points.points[static_cast<std::size_t>(i)],
                          TriMesh::FaceHandle(s.distances[static_cast<std::size_t>(i)].face), 2, search, around,
                          around_faces);
  }


  // After a move: whether every face it may have changed is nearer the input than `limit` (seven points each).
  bool faces_within(const SnapState& s, double limit) const {
    for (auto f : moved_faces)
      if (face_distance(*s.input_tree, s.mesh, f) >= limit) return false;
    return true;
  }

  // How far the corners of face f moved in this move (0 for corners it did not move).
  double corner_shift(const SnapState& s, int f) const {
    double shift = 0;
    for (auto w : s.mesh.fv_range(TriMesh::FaceHandle(f))) {
      const auto k = static_cast<std::size_t>(w.idx());
      if (moved_mark[k] == move_stamp) shift = std::max(shift, (s.mesh.point(w) - moved_from[k]).norm());
    }
    return shift;
  }

  // After a move: whether every watched input point is nearer than `limit`. A point's distance to a face grows by no
  // more than the face's corners moved (the point of the moved face at the same barycentric coordinates is no
  // farther), so a point whose bound (its upper bound, to its bounding face, plus that face's shift) stays under the
  // limit is not measured; the bounds or distances, in watched_upper, become the points' upper bounds if the move is
  // kept.
  bool watched_within(const SnapState& s, double limit) {
    watched_upper.clear();
    for (const int i : watched) {
      const auto k = static_cast<std::size_t>(i);
      Distance d = s.upper[k];
      d.d += corner_shift(s, d.face);
      if (remeasure || d.d >= limit * (1 - 1e-9)) d = measure(s, i);
      if (d.d >= limit) return false;
      watched_upper.push_back(d);
    }
    return true;
  }

  // Moves v onto q, relaxes and projects its neighbourhood; keeps the result if the region has no new flaw and the
  // input points nearest its faces all end nearer than the farthest input point at the start of the round
  // (without this check the snap raised the farthest input vertex of spheres with 4% noise in 10 of 16 seeds; a
  // stricter one, nearer than the farthest of the watched vertices, lowered armadillo's Hausdorff maximum 0.589 ->
  // 0.537 but raised bunny's 0.798 -> 0.850 and its RMS, 2M samples), and so does every face it moved (with kn + 2
  // rings relaxed and without this check the moved faces went 0.51 from armadillo's input, 2M samples; a stricter
  // one, each face no farther than it was or than the tolerance, kept 40% fewer moves and raised the maxima).
  bool try_snap(SnapState& s, TriMesh::VertexHandle v, const Vec3& q, std::size_t flaws_given = kNotCounted,
                double limit = 0) {
    TriMesh& mesh = s.mesh;
    if (limit <= 0) limit = s.round_max;
    local.collect(mesh, v, s.kn + kRelaxRings + 2, region);  // every vertex the relaxation moves, with their stars
    const std::size_t flaws_before = flaws_given != kNotCounted ? flaws_given : local.flaws(mesh, region);
    local.faces(mesh, region, region_faces);  // each once: the fold check below runs every pass
    watched.clear();
    for (auto f : region_faces)
      for (int i = s.first_near[static_cast<std::size_t>(f.idx())]; i >= 0;
           i = s.next_near[static_cast<std::size_t>(i)])
        watched.push_back(i);
    normals.clear();
    for (auto f : region_faces) normals.emplace_back(f, geometry::face_normal(mesh, f));
    // The free interior vertices within kn + 2 rings of v (breadth first) are relaxed around it, and in the step for
    // the border the free border vertices too, along their border curves (held, the border edges at a moved border
    // vertex leave the interval).
    local.collect(mesh, v, s.kn + kRelaxRings, inner);
    variables.clear();
    for (auto w : inner)
      if (w != v && !s.fixed[static_cast<std::size_t>(w.idx())] &&
          (!mesh.is_boundary(w) || (s.borders && slides_on_border(mesh, w))))
        variables.push_back(w);
    // The faces the move may change (each once).
    moved_faces.clear();
    for (auto w : variables)
      for (auto f : mesh.vf_range(w)) moved_faces.push_back(f);
    for (auto f : mesh.vf_range(v)) moved_faces.push_back(f);
    std::sort(moved_faces.begin(), moved_faces.end());
    moved_faces.erase(std::unique(moved_faces.begin(), moved_faces.end()), moved_faces.end());
    ++move_stamp;
    moved_mark.resize(mesh.n_vertices(), 0);
    moved_from.resize(mesh.n_vertices());
    auto mark_moved = [&](TriMesh::VertexHandle w) {
      moved_mark[static_cast<std::size_t>(w.idx())] = move_stamp;
      moved_from[static_cast<std::size_t>(w.idx())] = mesh.point(w);
    };
    for (auto w : variables) mark_moved(w);
    mark_moved(v);
    saved.assign(1, {v, mesh.point(v)});
    mesh.set_point(v, q);
    s.fixed[static_cast<std::size_t>(v.idx())] = 1;
    std::size_t last_flaws = 0;
    for (int pass = 0; pass < kPasses; ++pass) {
      for (auto w : variables) saved.emplace_back(w, mesh.point(w));
      optimize_vertices(mesh, variables, s.emin, s.emax);
      for (auto w : variables) project(s, w);
      bool folded = false;
      for (const auto& [f, before] : normals)
        folded = folded || OpenMesh::dot(before, geometry::face_normal(mesh, f)) < geometry::kMaxNormalTurnCos;
      const std::size_t flaws = local.flaws(mesh, region);
      if (!folded && flaws <= flaws_before && watched_within(s, limit) && faces_within(s, limit)) {
        for (auto w : region) s.touched[static_cast<std::size_t>(w.idx())] = 1;
        for (std::size_t j = 0; j < watched.size(); ++j)
          s.upper[static_cast<std::size_t>(watched[j])] = watched_upper[j];
        return true;
      }
      if (flaws > flaws_before + kHopelessFlaws) break;
      if (pass > 0 && flaws >= last_flaws) break;  // no progress: the third pass would rarely clear them
      last_flaws = flaws;
    }
    for (auto it = saved.rbegin(); it != saved.rend(); ++it) mesh.set_point(it->first, it->second);
    s.fixed[static_cast<std::size_t>(v.idx())] = 0;
    return false;
  }

  // Input vertex q, still farther than the tolerance after the moves, gets a vertex of its own: `face` (its nearest)
  // is split at q, and the edges opposite the new vertex are flipped while that brings the valences of their four
  // vertices nearer the ideal (a tip of the input, such as bunny's ear, takes a vertex of valence 5); the free
  // vertices around it are then relaxed as in try_snap(), with the same tests, and a valence off the ideal by more
  // than one at the new vertex or its neighbours undoes it too (flips back, then a collapse that leaves `face` as
  // it was). A move cannot do this where the remeshed vertices near q would have to leave their neighbours behind:
  // on bunny's ear tip each of the three nearest moved 1.3 from them with 20-30 edges left outside after any
  // number of relaxation passes. Serial: the mesh grows.
  bool try_insert(SnapState& s, TriMesh::FaceHandle face, const Vec3& q, double distance) {
    TriMesh& mesh = s.mesh;
    const TriMesh::VertexHandle corner = mesh.to_vertex_handle(mesh.halfedge_handle(face));
    local.collect(mesh, corner, s.kn + kRelaxRings + 1, region);  // within the region try_snap() counts around nv
    const std::size_t flaws_before = local.flaws(mesh, region);
    const TriMesh::VertexHandle nv = mesh.split(face, q);
    s.fixed.resize(mesh.n_vertices(), 0);
    s.touched.resize(mesh.n_vertices(), 0);
    s.first_near.resize(mesh.n_faces(), -1);
    flipped.clear();
    for (bool again = true; again && flipped.size() < kInsertFlips;) {
      again = false;
      for (auto h : mesh.voh_range(nv)) {
        const auto link = mesh.next_halfedge_handle(h);  // the edge opposite nv in this triangle
        const auto e = mesh.edge_handle(link);
        if (mesh.is_boundary(e) || !mesh.is_flip_ok(e)) continue;
        const auto a = mesh.from_vertex_handle(link), b = mesh.to_vertex_handle(link);
        const auto d = mesh.to_vertex_handle(mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(link)));
        if (valence_improvement(mesh, e) <= 0 ||  // Eq 4.3 over a, b (an edge less), nv and d (an edge more)
            !geometry::flip_keeps_shape(mesh.point(a), mesh.point(b), q, mesh.point(d)))
          continue;
        mesh.flip(e);
        flipped.push_back(e);
        again = true;
        break;
      }
    }
    bool valences = true;
    for (auto w : mesh.vv_range(nv))
      valences = valences && std::abs(geometry::valence(mesh, w) - ideal_valence(mesh, w)) <= 1;
    valences = valences && std::abs(geometry::valence(mesh, nv) - ideal_valence(mesh, nv)) <= 1;
    remeasure = true;  // the faces changed by more than their corners' moves: every watched point measured again
    bool kept = valences && try_snap(s, nv, q, flaws_before, distance);
    remeasure = false;
    const bool bounds_changed = kept;
    // try_snap compares the faces with themselves after the split: the new ones are compared with the input here (a
    // fold; the face split at an input vertex cannot be the reference: at a tip the new faces rise steeply from it).
    if (kept) {
      for (auto f : mesh.vf_range(nv)) kept = kept && !turned_against_input(*s.input_tree, mesh, f);
      if (kept) return true;
      for (auto it = saved.rbegin(); it != saved.rend(); ++it) mesh.set_point(it->first, it->second);
      s.fixed[static_cast<std::size_t>(nv.idx())] = 0;
    }
    undo_insertion(s, nv, corner, bounds_changed);
    return false;
  }

  // Flips back and collapses the vertex `nv` of try_insert() (positions already restored). A flip flipped back gives
  // its two faces each other's triangles, and the collapse deletes two of nv's faces: the input points bounded by one
  // of nv's faces (and with `bounds_changed` those try_snap() gave new bounds) are measured again, from a face at
  // `corner` (a corner of the split face).
  void undo_insertion(SnapState& s, TriMesh::VertexHandle nv, TriMesh::VertexHandle corner, bool bounds_changed) {
    TriMesh& mesh = s.mesh;
    affected.clear();
    for (auto f : mesh.vf_range(nv)) affected.push_back(f.idx());
    std::sort(affected.begin(), affected.end());
    for (auto it = flipped.rbegin(); it != flipped.rend(); ++it) mesh.flip(*it);
    const auto out = *mesh.voh_range(nv).begin();
    if (!mesh.is_collapse_ok(out)) throw std::logic_error("snap: a face split could not be undone");
    mesh.collapse(out);
    const auto anchor = *mesh.vf_range(corner).begin();
    auto is_affected = [&](int f) { return std::binary_search(affected.begin(), affected.end(), f); };
    auto remeasure_point = [&](std::size_t i) {
      Distance& d = s.distances[i];
      if (is_affected(d.face)) d.face = anchor.idx();
      d = s.upper[i] = measure(s, static_cast<int>(i));
    };
    if (bounds_changed)
      for (const int i : watched) remeasure_point(static_cast<std::size_t>(i));
    for (std::size_t i = 0; i < s.distances.size(); ++i)
      if (s.distances[i].face >= 0 && (is_affected(s.distances[i].face) || is_affected(s.upper[i].face)))
        remeasure_point(i);
  }

  // The move of input vertex c: reads the mesh within kn + 9 rings of the corners of c's nearest face and writes
  // within kn + 5 (see Schedule).
  void visit(SnapState& s, int c) {
    TriMesh& mesh = s.mesh;
    const Vec3 q = s.input.point(TriMesh::VertexHandle(c));
    const auto face = TriMesh::FaceHandle(s.distances[static_cast<std::size_t>(c)].face);
    // The remeshed surface near this point changed in this round: its distance is measured again first.
    bool stale = false;
    for (auto w : mesh.fv_range(face)) stale = stale || s.touched[static_cast<std::size_t>(w.idx())];
    if (stale) return;
    s.tried[static_cast<std::size_t>(c)] = 1;
    ++s.visits[static_cast<std::size_t>(c)];
    // The free vertices nearest the point among the nearest face's corners and their neighbours, border vertices
    // for a corner of the input's border and interior ones else; the second only if it is within emin (on armadillo
    // 0 of 13 second choices farther away were kept).
    const bool border = s.input.is_boundary(TriMesh::VertexHandle(c));
    choices.clear();
    for (auto corner : mesh.fv_range(face))
      for (auto w : mesh.vv_range(corner))
        for (auto u : {corner, w}) {
          const double d = (mesh.point(u) - q).norm();
          if (mesh.is_boundary(u) == border && !s.fixed[static_cast<std::size_t>(u.idx())] && d <= s.emax)
            choices.emplace_back(d, u.idx());
        }
    std::sort(choices.begin(), choices.end());
    choices.erase(std::unique(choices.begin(), choices.end()), choices.end());
    if (choices.size() > kChoices) choices.resize(kChoices);
    if (choices.size() > 1 && choices[1].first > s.emin) choices.resize(1);
    for (const auto& choice : choices) {
      ++tries;
      if (try_snap(s, TriMesh::VertexHandle(choice.second), q)) {
        ++snapped;
        break;
      }
    }
  }
};

// The moves of a round, on every thread, with the result of one thread taking them in order. A move reads the mesh
// within kn + 9 rings of the corners of its input vertex's nearest face (its region of kn + 4 rings around a vertex
// next to them, the stars of those, and the 2 rings around the faces nearest the input vertices it watches) and
// writes within kn + 3 (positions) and kn + 5 (the touched marks, read only at the corners): two moves whose balls
// of kn + 6 rings around their corners are disjoint are more than 2 kn + 12 rings apart, and neither sees the
// other. A move starts once every earlier move whose ball meets its own has finished.
class Schedule {
 public:
  Schedule(const TriMesh& mesh, int kn) : mesh_(mesh), rings_(kn + kRelaxRings + 4), claim_(mesh.n_vertices(), 0) {}

  // Runs visit(c) for every candidate c (input vertex indices in order).
  template <typename Visit>
  void run(const std::vector<int>& candidates, const std::vector<Distance>& distances, Visit&& visit) {
    balls_.assign(candidates.size(), {});
    for (std::size_t k = 0; k < candidates.size(); ++k)
      ball(TriMesh::FaceHandle(distances[static_cast<std::size_t>(candidates[k])].face), balls_[k]);
    state_.assign(candidates.size(), kWaiting);
    first_ = 0;
#pragma omp parallel
    {
      for (;;) {
        std::size_t k = 0;
        {
          std::unique_lock<std::mutex> lock(mutex_);
          bool found = false;
          for (;;) {
            while (first_ < state_.size() && state_[first_] == kDone) ++first_;
            if (first_ == state_.size()) break;
            found = pick(k);
            if (found) break;
            wake_.wait(lock);
          }
          if (!found) break;
          state_[k] = kRunning;
        }
        visit(candidates[k]);
        {
          std::lock_guard<std::mutex> lock(mutex_);
          state_[k] = kDone;
        }
        wake_.notify_all();
      }
    }
  }

 private:
  static constexpr char kWaiting = 0, kRunning = 1, kDone = 2;
  static constexpr std::size_t kScan = 64;  // unfinished moves looked at for one that may start

  // The earliest waiting move whose ball meets that of no earlier unfinished move.
  bool pick(std::size_t& out) {
    ++stamp_;
    std::size_t scanned = 0;
    for (std::size_t k = first_; k < state_.size() && scanned < kScan; ++k) {
      if (state_[k] == kDone) continue;
      ++scanned;
      bool free = true;
      for (const int v : balls_[k]) {
        unsigned& c = claim_[static_cast<std::size_t>(v)];
        free = free && c != stamp_;
        c = stamp_;
      }
      if (free && state_[k] == kWaiting) {
        out = k;
        return true;
      }
    }
    return false;
  }

  void ball(TriMesh::FaceHandle face, std::vector<int>& out) {
    ++stamp_;
    out.clear();
    auto visit = [&](TriMesh::VertexHandle v) {
      unsigned& c = claim_[static_cast<std::size_t>(v.idx())];
      if (c == stamp_) return;
      c = stamp_;
      out.push_back(v.idx());
    };
    for (auto v : mesh_.fv_range(face)) visit(v);
    for (std::size_t begin = 0, r = 0; r < static_cast<std::size_t>(rings_); ++r) {
      const std::size_t end = out.size();
      for (std::size_t i = begin; i < end; ++i)
        for (auto w : mesh_.vv_range(TriMesh::VertexHandle(out[i]))) visit(w);
      begin = end;
    }
  }

  const TriMesh& mesh_;
  int rings_;
  std::vector<unsigned> claim_;
  unsigned stamp_ = 0;
  std::vector<std::vector<int>> balls_;
  std::vector<char> state_;
  std::size_t first_ = 0;
  std::mutex mutex_;
  std::condition_variable wake_;
};

}  // namespace

FarthestInputVertex farthest_input_vertex(const TriMesh& mesh, const TriMesh& input) {
  FarthestInputVertex out;
  const InputPoints points = input_points(input, /*edges=*/false);
  std::vector<Distance> distances;
  measure_input(mesh, points, points.interior, distances);
  for (std::size_t i = 0; i < distances.size(); ++i)
    if (distances[i].face >= 0 && (!out.measured || distances[i].d > out.distance)) {
      out.distance = distances[i].d;
      out.point = input.point(TriMesh::VertexHandle(static_cast<int>(i)));
      out.measured = true;
    }
  return out;
}

SnapResult snap_to_features(TriMesh& mesh, const TriMesh& input, const ProjectionTarget& target, int kn, double emin,
                            double emax, double tolerance, const SurfaceTree* input_tree) {
  SnapResult result;
  mesh.garbage_collection();  // face indices = positions in triangles_of
  const InputPoints points = input_points(input, /*edges=*/true);
  const std::size_t nv = points.vertices;
  SnapState state(mesh, input, points, target, kn, emin, emax);
  state.fixed.assign(mesh.n_vertices(), 0);
  state.touched.assign(mesh.n_vertices(), 0);
  state.tried.assign(nv, 0);
  state.visits.assign(nv, 0);
  state.next_near.assign(points.points.size(), -1);
  measure_input(mesh, points, points.all, state.distances);
  // (With no input triangle no input vertex is measured and no move is tried.)
  std::optional<SurfaceTree> own;
  state.input_tree = &(input_tree ? *input_tree : own.emplace(input)).tree();
  std::vector<Distance>& distances = state.distances;
  std::vector<Worker> workers;
  for (int t = 0; t < max_threads(); ++t) workers.emplace_back(emin, emax);
  Schedule schedule(mesh, kn);

  // Rounds of moves of the candidates (interior input vertices, or with `borders` those of the input's border) until
  // one keeps none; returns the moves kept.
  auto rounds = [&](bool borders, std::size_t& first_candidates, int& rounds_run) {
    std::size_t kept = 0;
    std::vector<int> candidates, per_face;
    for (int round = 0; round < kRounds; ++round) {
      const auto round_start = std::chrono::steady_clock::now();
      candidates.clear();
      for (std::size_t i = 0; i < nv; ++i)
        if (distances[i].d > tolerance && distances[i].face >= 0 && !state.tried[i] && state.visits[i] < kVisits &&
            borders == input.is_boundary(TriMesh::VertexHandle(static_cast<int>(i))))
          candidates.push_back(static_cast<int>(i));
      if (round == 0) first_candidates = candidates.size();
      sort_farthest_first(candidates, distances);
      // The kPerFace farthest of the points nearest one remeshed face (the others wait for a later round).
      per_face.assign(mesh.n_faces(), 0);
      const std::size_t listed = candidates.size();
      std::size_t taken = 0;
      for (const int c : candidates)
        if (++per_face[static_cast<std::size_t>(distances[static_cast<std::size_t>(c)].face)] <= kPerFace)
          candidates[taken++] = c;
      candidates.resize(taken);
      std::fill(state.touched.begin(), state.touched.end(), 0);
      state.upper = distances;
      state.link_by_face(distances);
      // Farthest first; candidates far enough apart that neither move can see the other's run in parallel, so the
      // result is that of one thread taking them in order.
      for (auto& w : workers) w.snapped = 0;
      schedule.run(candidates, distances,
                   [&](int c) { workers[static_cast<std::size_t>(thread_index())].visit(state, c); });
      std::size_t snapped = 0;
      for (auto& w : workers) snapped += w.snapped;
      // Input vertices whose nearest face moved: measured again among the faces around it.
      for (std::size_t i = 0; i < distances.size(); ++i) {
        Distance& d = distances[i];
        if (d.face < 0) continue;
        bool stale = false;
        for (auto w : mesh.fv_range(TriMesh::FaceHandle(d.face)))
          stale = stale || state.touched[static_cast<std::size_t>(w.idx())];
        if (!stale) continue;
        if (state.upper[i].d < tolerance) {  // no candidate, and under the farthest point while any is a candidate:
          d = state.upper[i];                // its upper bound is enough
          continue;
        }
        d = local_distance(mesh, points.points[i], TriMesh::FaceHandle(d.face), 3, workers[0].search,
                           workers[0].around, workers[0].around_faces);
        if (i < nv) state.tried[i] = 0;  // a new neighbourhood: may be tried again
      }
      kept += snapped;
      rounds_run = round + 1;
      // Progress on a long snap (a noisy scan: thousands of input vertices off the surface, each a move to try).
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - round_start).count();
      spdlog::log(seconds >= kProgressSeconds ? spdlog::level::info : spdlog::level::debug,
                  "snap to features, {}round {}: {} of {} input vertices snapped, {:.1f}s", borders ? "border " : "",
                  round + 1, snapped, candidates.size(), seconds);
      if (snapped == 0 && candidates.size() == listed) break;  // none kept and none waiting
    }
    return kept;
  };
  auto interior_max = [&] {
    double m = 0;
    for (std::size_t i = 0; i < nv; ++i)
      if (!input.is_boundary(TriMesh::VertexHandle(static_cast<int>(i)))) m = std::max(m, distances[i].d);
    return m;
  };
  result.max_before = interior_max();
  result.snapped = rounds(false, result.candidates, result.rounds);
  // Then the corners of the input's borders (a scan's holes: the remeshed border, its vertices moved along the
  // curves through their border edges, cuts them), each pulling the nearest free border vertex onto itself. The
  // interior and border points are measured together in both steps, so no move takes the surface farther than the
  // farthest of all.
  std::fill(state.tried.begin(), state.tried.end(), 0);
  state.borders = true;
  auto border_max = [&] {
    double m = 0;
    for (std::size_t i = 0; i < nv; ++i)
      if (distances[i].face >= 0 && input.is_boundary(TriMesh::VertexHandle(static_cast<int>(i))))
        m = std::max(m, distances[i].d);
    return m;
  };
  result.border_max_before = border_max();
  if (result.border_max_before > tolerance)
    result.border_snapped = rounds(true, result.border_candidates, result.border_rounds);
  result.border_max_after = border_max();
  // Last, the interior input vertices no move reached get a vertex of their own (farthest first, on one thread).
  state.borders = false;
  std::vector<int> candidates;
  for (std::size_t i = 0; i < nv; ++i)
    if (distances[i].d > tolerance && distances[i].face >= 0 &&
        !input.is_boundary(TriMesh::VertexHandle(static_cast<int>(i))))
      candidates.push_back(static_cast<int>(i));
  sort_farthest_first(candidates, distances);
  if (candidates.size() > kInsertions) candidates.resize(kInsertions);
  result.insertion_candidates = candidates.size();
  const auto insertion_start = std::chrono::steady_clock::now();
  if (!candidates.empty()) {
    Worker& worker = workers[0];
    state.upper = distances;
    state.link_by_face(state.upper);  // (bounds: a kept insertion links the points it measured again)
    for (const int c : candidates) {
      const auto k = static_cast<std::size_t>(c);
      distances[k] = state.upper[k] = worker.measure(state, c);
      if (distances[k].d <= tolerance) continue;
      ++result.insertion_tries;
      if (!worker.try_insert(state, TriMesh::FaceHandle(distances[k].face), input.point(TriMesh::VertexHandle(c)),
                             distances[k].d))
        continue;
      ++result.inserted;
      state.link_by_face(state.upper);  // (round_max: unused here, each insertion has its own limit)
    }
    // The undone splits leave deleted elements: collected, the snapped vertices' flags carried along.
    std::vector<TriMesh::VertexHandle> fixed_vertices;
    for (auto v : mesh.vertices())
      if (state.fixed[static_cast<std::size_t>(v.idx())]) fixed_vertices.push_back(v);
    std::vector<TriMesh::VertexHandle*> vertex_pointers;
    for (auto& v : fixed_vertices) vertex_pointers.push_back(&v);
    std::vector<TriMesh::HalfedgeHandle*> halfedge_pointers;
    std::vector<TriMesh::FaceHandle*> face_pointers;
    mesh.garbage_collection(vertex_pointers, halfedge_pointers, face_pointers);
    state.fixed.assign(mesh.n_vertices(), 0);
    for (auto v : fixed_vertices) state.fixed[static_cast<std::size_t>(v.idx())] = 1;
    distances = state.upper;  // (the distances as measured, or upper bounds where a kept insertion changed faces)
    result.border_max_after = border_max();
  }
  result.insertion_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - insertion_start).count();
  for (const auto& w : workers) result.tries += w.tries;
  result.max_after = interior_max();  // (the border step may move interior vertices too)
  result.fixed = std::move(state.fixed);
  return result;
}

}  // namespace carbonmesh
