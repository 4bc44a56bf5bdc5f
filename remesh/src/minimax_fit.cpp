// Vertices moved to lower the largest distance between the remeshed surface and the input (after the surface fit;
// not in the dissertation).
//
// The least-squares fit (surface_fit.cpp) lowers the mean of the squared distance; the largest distance is set at a few
// spots: faces bridging a groove of the input or cutting across a ridge, where the fit trades one side against the
// other in the mean. A scan samples both surfaces (remeshed faces at their centroid and edge midpoints, input corners,
// edge midpoints and face centroids: on a coarse input a crease along an input edge is farthest in its middle, which
// neither its corners nor the faces' centroids see), and the faces of either surface whose samples come within 0.75 of
// the spots' threshold are bracketed (their farthest point, by branch and bound: a face's farthest point lies at a
// sample only by chance); spots farther than `tolerance` and than `share` of the largest distance are taken farthest
// first (those farther than an edge are left: a part of the input was cut off there, which small moves do not mend;
// so is a spot whose region's largest distance no search can bring within an edge, see out_of_reach()).
// Around each spot, the corners of its face and the far corners of its three neighbours move
// one at a time, along their normal and two tangents, in a pattern search (the step halved when no move gains) over the
// region: the faces at those vertices. A move is kept if every edge at the vertex stays in [emin, emax], no face at it
// gets an angle under 3 degrees or turns by more than ~72 degrees from its start, and the region's largest distance
// falls, or stays and the squared excess of its samples over 0.7 of it falls (so that two balanced maxima can both come
// down). The distances are those of 15 samples of each region face to the input faces near it and of 15 samples of each
// input face under the region to the region's faces (the samples nearer the region than the ring of faces around it;
// the others are the ring's, which no move changes). Where each vertex alone is held (an edge at an end of the
// interval, two balanced maxima), joint steps of all the region's vertices follow: the linear program of the largest
// distance, its rows linearised at the samples and at the faces' bracketed farthest point, under linearised edge
// lengths in [emin, emax] and a box (minimax_step.hpp, GLPK's simplex); a step is kept if the same rules hold
// and the region's bracketed largest distance falls. The result is kept only if the region's largest distance fell for
// certain: the bound over every point of its faces (branch and bound, as `carbonmesh stats --ref`) and over 153 samples
// of each input face under it lie below the largest distance the region had (else the search may only have moved it
// between its samples: it runs again with 45 samples a face, then gives up). Spots run on every thread, each starting
// once every earlier spot near it has finished (OrderedSchedule): the output does not depend on the thread count.
// Then the region left farthest, if still farther than the tolerance, is searched once more (on one thread) with the
// neighbours of its vertices movable too: where its own vertices are held by edges at the ends of the interval, the
// ring around can make room (on bunny's 24 rigid motions of tools/bench/remesh_motions.py, motion 14 0.5312 -> 0.4924).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include <spdlog/spdlog.h>

#include "carbonmesh/remesh/remesh_steps.hpp"
#include "carbonmesh/remesh/triangle_tree.hpp"
#include "bounded_triangles.hpp"
#include "farthest_point.hpp"
#include "minimax_step.hpp"
#include "ordered_schedule.hpp"
#include "remesh_geometry.hpp"
#include "threads.hpp"

namespace carbonmesh {
namespace {

using namespace triangle_tree;

constexpr int kGrid = 4;    // a face's samples in the search: the barycentric grid of step 1/4 (15 points), or 1/8
constexpr int kCheck = 16;  // the check of a region's result: 153 samples of each input face under it (the search
                            // may only have moved the largest distance between its samples), and the region's
constexpr double kTolerance = 1e-4;         // own faces bracketed to within this (as carbonmesh stats --ref),
constexpr std::size_t kPiecesPerFace = 64;  // with at most this many pieces a face
constexpr double kBracketShare = 0.75;  // the scan brackets the faces whose samples come within this of the threshold
constexpr double kGain = 1e-6;  // a move must lower the region's largest distance by this fraction at least ...
constexpr double kExcessGain = 1e-2;  // ... or keep it and lower the excess over kLevel of it by this fraction
constexpr double kLevel = 0.7;
constexpr double kFirstStep = 0.1, kLastStep = 0.02;  // the search's steps, as fractions of emin
constexpr int kSweeps = 24;                            // at most this many sweeps over the movable vertices
constexpr int kJointSteps = 16;  // at most this many joint steps after the pattern search, kCuts tries a box
constexpr int kCuts = 3;
// At most this many spots a round: the farthest set the largest distance, and a search costs 10-100 ms (a 20:1 disc,
// its whole rim between 0.8 emax and emax from the input, had 61: 3.3 s for a maximum of 2.71 -> 2.61).
constexpr std::size_t kMaxSpots = 16;

// A move keeps every edge at the vertex within [emin, emax], so on a flat star it lifts the vertex off the plane of
// its neighbours by sqrt(emax^2 - emin^2) at most: a region farther than emax plus that from the input stays farther
// than an edge (a part cut off) whatever the search does (camelhead at twice its size: a region at 1.8343 came to
// 1.6162).
double out_of_reach(double emin, double emax) { return emax + std::sqrt(emax * emax - emin * emin); }

void dense_samples(const Vec3& a, const Vec3& b, const Vec3& c, int grid, std::vector<Vec3>& out) {
  for (int i = 0; i <= grid; ++i)
    for (int j = 0; j <= grid - i; ++j) {
      const double u = static_cast<double>(i) / grid, v = static_cast<double>(j) / grid;
      out.push_back((1 - u - v) * a + u * b + v * c);
    }
}

std::vector<TriMesh::FaceHandle> live_faces(const TriMesh& mesh) {
  std::vector<TriMesh::FaceHandle> faces;
  faces.reserve(mesh.n_faces());
  for (auto f : mesh.faces())
    if (!mesh.status(f).deleted()) faces.push_back(f);
  return faces;
}

// The distances of one scan of both surfaces, and the remeshed faces nearest each input face's samples.
struct Scan {
  double max = 0;
  std::vector<std::pair<double, int>> spots;  // (-distance, remeshed face index), farthest first
  std::vector<std::vector<int>> input_faces;  // by remeshed face index: the input faces with a sample nearest it
};

// What a scan keeps for the next one: the search moves vertices only, so the live faces keep their positions in the
// list, and a face none of whose corners moved keeps its distances.
struct ScanMemory {
  std::vector<double> centroid, bound;             // by face position: the centroid's distance, the face's bound
  std::vector<Tree::Point_and_primitive_id> hits;  // and the centroid's nearest input point
  std::vector<Vec3> nearest_point;                 // by input point: its nearest remeshed point ...
  std::vector<int> nearest_position;               // ... on this face (a position; -1: none)
};

// The scan of both surfaces. With `moved` (by face index: a corner moved since the scan that filled `memory`), the
// other faces' distances are taken from `memory` and the input points' nearest points there start their searches.
// With `spots_wanted` false only Scan::max is filled in.
Scan scan(const TriMesh& mesh, const TriMesh& input, const Tree& input_tree, Triangles::const_iterator first_input,
          double share, double tolerance, double reach, ScanMemory& memory, const std::vector<char>* moved,
          bool spots_wanted) {
  const auto faces = live_faces(mesh);
  const int nf = static_cast<int>(faces.size());
  auto kept = [&](std::size_t k) { return moved && !(*moved)[static_cast<std::size_t>(faces[k].idx())]; };
  // Remeshed faces: centroid and edge midpoints, to the input. The centroid is measured in the tree; a midpoint is
  // first bounded by the input faces around the centroid's nearest one, and measured in the tree only where the
  // face's bound could make it a spot or set a largest distance (below): the figures are those of measuring all.
  std::vector<double>& bound = memory.bound;
  std::vector<Tree::Point_and_primitive_id>& hits = memory.hits;
  if (!moved) {
    memory.centroid.assign(faces.size(), 0);
    bound.assign(faces.size(), 0);
    hits.assign(faces.size(), {});
  }
  const double cutoff = 0.5 * tolerance;  // a bound this small is looked no further into (see `needed`)
#pragma omp parallel for schedule(dynamic, 256)
  for (int i = 0; i < nf; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (kept(k)) continue;
    Vec3 a, b, c;
    geometry::face_points(mesh, faces[k], a, b, c);
    const Vec3 centroid = (a + b + c) / 3.0;
    hits[k] = input_tree.closest_point_and_primitive(to_point(centroid));
    memory.centroid[k] = bound[k] = (to_vec(hits[k].first) - centroid).norm();
    const TriMesh::FaceHandle nearest(static_cast<int>(hits[k].second - first_input));
    for (const Vec3& p : {0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a)}) {
      Vec3 x, y, z;
      geometry::face_points(input, nearest, x, y, z);
      double d = point_triangle_distance(p, x, y, z);
      for (auto corner : input.fv_range(nearest))
        for (auto g : input.vf_range(corner)) {
          if (d <= cutoff || d <= memory.centroid[k]) break;
          geometry::face_points(input, g, x, y, z);
          d = std::min(d, point_triangle_distance(p, x, y, z));
        }
      bound[k] = std::max(bound[k], d);
    }
  }
  // The largest centroid distance of a face whose bound is within reach is a lower bound of the largest distance
  // within reach (and of the largest): a face whose bound is no larger than it, and than the spots' threshold it
  // gives, is neither a spot nor sets a largest distance; the others are measured.
  std::vector<double> forward = memory.centroid;
  double lower = 0;
  for (std::size_t k = 0; k < faces.size(); ++k)
    if (bound[k] <= reach) lower = std::max(lower, forward[k]);
  const double needed = std::min(lower, std::max(tolerance, share * lower));
#pragma omp parallel for schedule(dynamic, 256)
  for (int i = 0; i < nf; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (bound[k] <= needed) continue;
    Vec3 a, b, c;
    geometry::face_points(mesh, faces[k], a, b, c);
    double worst = forward[k] * forward[k];
    for (const Vec3& p : {0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a)})
      worst = std::max(worst, input_tree.squared_distance(to_point(p), hits[k].first));
    forward[k] = std::sqrt(worst);
  }
  // Input corners, face centroids and edge midpoints, to the remeshed surface (and the remeshed face nearest each;
  // the tree's triangles in the order of `faces`).
  Triangles triangles;
  triangles.reserve(faces.size());
  for (auto f : faces) {
    Vec3 a, b, c;
    geometry::face_points(mesh, f, a, b, c);
    triangles.emplace_back(to_point(a), to_point(b), to_point(c));
  }
  Tree tree(triangles.begin(), triangles.end());
  tree.build();
  tree.accelerate_distance_queries();
  const int nv = static_cast<int>(input.n_vertices()), ni = static_cast<int>(input.n_faces());
  const int ne = static_cast<int>(input.n_edges()), n = nv + ni + ne;
  std::vector<double> backward(static_cast<std::size_t>(n), 0);
  if (!moved) {
    memory.nearest_point.assign(static_cast<std::size_t>(n), Vec3(0, 0, 0));
    memory.nearest_position.assign(static_cast<std::size_t>(n), -1);
  }
#pragma omp parallel for schedule(dynamic, 256)
  for (int k = 0; k < n; ++k) {
    Vec3 p;
    if (k < nv) {
      const TriMesh::VertexHandle v(k);
      if (input.status(v).deleted() || input.is_isolated(v)) continue;
      p = input.point(v);
    } else if (k < nv + ni) {
      const TriMesh::FaceHandle f(k - nv);
      if (input.status(f).deleted()) continue;
      Vec3 a, b, c;
      geometry::face_points(input, f, a, b, c);
      p = (a + b + c) / 3.0;
    } else {
      const TriMesh::EdgeHandle e(k - nv - ni);
      if (input.status(e).deleted()) continue;
      const auto h = input.halfedge_handle(e, 0);
      p = 0.5 * (input.point(input.from_vertex_handle(h)) + input.point(input.to_vertex_handle(h)));
    }
    const auto j = static_cast<std::size_t>(k);
    const int before = memory.nearest_position[j];
    const auto hit = moved && before >= 0 && kept(static_cast<std::size_t>(before))
                         ? tree.closest_point_and_primitive(to_point(p), {to_point(memory.nearest_point[j]),
                                                                          triangles.begin() + before})
                         : tree.closest_point_and_primitive(to_point(p));
    backward[j] = (to_vec(hit.first) - p).norm();
    memory.nearest_point[j] = to_vec(hit.first);
    memory.nearest_position[j] = static_cast<int>(hit.second - triangles.begin());
  }
  // A face's farthest point is seen only where it lies at a sample: the faces of either surface whose samples come
  // within kBracketShare of the spots' threshold are bracketed (as the check of a region), and a backward maximum
  // found so is a spot of the remeshed face nearest it.
  std::vector<double> near_forward = forward;  // the faces' distances, bracketed near the threshold
  struct Bracketed {
    int input_face = -1;
    double distance = 0;
    int position = -1;  // of the remeshed face nearest its farthest point
  };
  std::vector<Bracketed> bracketed;  // the input faces bracketed
  if (spots_wanted) {
    double sampled = 0;
    for (const auto* distances : {&forward, &backward})
      for (const double d : *distances)
        if (d <= reach) sampled = std::max(sampled, d);
    const double near = kBracketShare * std::max(tolerance, share * sampled);
#pragma omp parallel for schedule(dynamic, 16)
    for (int i = 0; i < nf; ++i) {
      const auto k = static_cast<std::size_t>(i);
      if (forward[k] < near || forward[k] > reach) continue;
      const Farthest f = farthest_point(Triangles{triangles[k]}, input_tree, kTolerance, kPiecesPerFace);
      near_forward[k] = std::max(forward[k], f.distance);
    }
    for (auto f : input.faces()) {
      if (input.status(f).deleted()) continue;
      double d = backward[static_cast<std::size_t>(nv + f.idx())];
      for (auto v : input.fv_range(f)) d = std::max(d, backward[static_cast<std::size_t>(v.idx())]);
      for (auto e : input.fe_range(f)) d = std::max(d, backward[static_cast<std::size_t>(nv + ni + e.idx())]);
      if (d >= near && d <= reach) bracketed.push_back({f.idx()});
    }
    const int nc = static_cast<int>(bracketed.size());
#pragma omp parallel for schedule(dynamic, 16)
    for (int i = 0; i < nc; ++i) {
      Bracketed& b = bracketed[static_cast<std::size_t>(i)];
      const Farthest f = farthest_point(Triangles{*(first_input + b.input_face)}, tree, kTolerance, kPiecesPerFace);
      b.distance = f.distance;
      b.position = static_cast<int>(tree.closest_point_and_primitive(f.at).second - triangles.begin());
    }
  }
  Scan result;
  // Spots farther than `reach` are out of the search's reach (a part of the input cut off, an input border the
  // remesh does not follow): the share is taken of the largest distance within it.
  // (Scan::max is the samples', as in the scan after the search.)
  double within = 0;
  for (const auto* distances : {&forward, &backward})
    for (const double d : *distances) result.max = std::max(result.max, d);
  for (const auto* distances : {&near_forward, &backward})
    for (const double d : *distances)
      if (d <= reach) within = std::max(within, d);
  for (const Bracketed& b : bracketed)
    if (b.distance <= reach) within = std::max(within, b.distance);
  if (!spots_wanted) return result;
  const double threshold = std::max(tolerance, share * within);
  auto spot = [&](double d) { return d > threshold && d <= reach; };
  for (int i = 0; i < nf; ++i)
    if (spot(near_forward[static_cast<std::size_t>(i)]))
      result.spots.emplace_back(-near_forward[static_cast<std::size_t>(i)], faces[static_cast<std::size_t>(i)].idx());
  result.input_faces.assign(mesh.n_faces(), {});
  for (int k = 0; k < n; ++k) {
    const int position = memory.nearest_position[static_cast<std::size_t>(k)];
    if (position < 0) continue;
    const int owner = faces[static_cast<std::size_t>(position)].idx();
    const double d = backward[static_cast<std::size_t>(k)];
    if (spot(d)) result.spots.emplace_back(-d, owner);
    auto& list = result.input_faces[static_cast<std::size_t>(owner)];
    if (k < nv) {
      for (auto f : input.vf_range(TriMesh::VertexHandle(k))) list.push_back(f.idx());
    } else if (k < nv + ni) {
      list.push_back(k - nv);
    } else {
      const TriMesh::EdgeHandle e(k - nv - ni);
      for (int side = 0; side < 2; ++side) {
        const auto f = input.face_handle(input.halfedge_handle(e, side));
        if (f.is_valid()) list.push_back(f.idx());
      }
    }
  }
  for (const Bracketed& b : bracketed) {
    if (!spot(b.distance)) continue;
    const int owner = faces[static_cast<std::size_t>(b.position)].idx();
    result.spots.emplace_back(-b.distance, owner);
    result.input_faces[static_cast<std::size_t>(owner)].push_back(b.input_face);
  }
  std::sort(result.spots.begin(), result.spots.end());
  return result;
}

// The vertices a spot's search moves: the corners of the spot face and the far corners of its neighbours (border
// vertices and those with (*fixed)[index] != 0 stay), and the faces at them (the region).
void region_of(const TriMesh& mesh, const std::vector<char>* fixed, TriMesh::FaceHandle spot,
               std::vector<TriMesh::VertexHandle>& movable, std::vector<TriMesh::FaceHandle>& faces,
               bool wide = false) {
  movable.clear();
  faces.clear();
  auto add_vertex = [&](TriMesh::VertexHandle v) {
    if (mesh.is_boundary(v) || (fixed && (*fixed)[static_cast<std::size_t>(v.idx())])) return;
    if (std::find(movable.begin(), movable.end(), v) == movable.end()) movable.push_back(v);
  };
  for (auto h : mesh.fh_range(spot)) {
    add_vertex(mesh.to_vertex_handle(h));
    const auto o = mesh.opposite_halfedge_handle(h);
    if (!mesh.is_boundary(o)) add_vertex(mesh.to_vertex_handle(mesh.next_halfedge_handle(o)));
  }
  if (wide) {
    const std::vector<TriMesh::VertexHandle> core = movable;
    for (auto v : core)
      for (auto w : mesh.vv_range(v)) add_vertex(w);
  }
  for (auto v : movable)
    for (auto f : mesh.vf_range(v))
      if (std::find(faces.begin(), faces.end(), f) == faces.end()) faces.push_back(f);
}

// The region's distances: the largest, and the sum of the squared excess of every sample over a level below it (the
// search also takes a move that keeps the largest and lowers the others near it: the next move may then lower it).
struct Value {
  double max = 0, excess = 0;
  void add(double d, double level) {
    max = std::max(max, d);
    if (d > level) excess += (d - level) * (d - level);
  }
  void add(const Value& o) {
    max = std::max(max, o.max);
    excess += o.excess;
  }
  bool better_than(const Value& o) const {
    return max < o.max * (1 - kGain) || (max <= o.max && excess < o.excess * (1 - kExcessGain));
  }
};

// The pattern search around one spot (a remeshed face).
class Region {
 public:
  Region(TriMesh& mesh, const std::vector<char>* fixed, const TriMesh& input, const Triangles& input_triangles,
         const Tree& input_tree, const Scan& scan, double emin, double emax)
      : mesh_(mesh), fixed_(fixed), input_(input), first_triangle_(input_triangles.begin()), input_tree_(input_tree),
        scan_(scan), emin_(emin), emax_(emax) {}

  // Returns the number of moves kept; `largest` gets the region's largest distance after them (the bound over its
  // faces and the check's samples; without a kept move, the distance it had).
  std::size_t optimize(TriMesh::FaceHandle spot, bool wide, double& largest) {
    largest = 0;
    collect(spot, wide);
    if (movable_.empty()) return 0;
    const Samples check = input_samples(kCheck);
    const double checked_before = largest_distance(check).first;
    largest = checked_before;
    // A region that no search can bring within an edge of the input holds a part of it that was cut off (a spot within
    // reach can lie beside one: camelhead's slit, 3.2-7.7 from its lid): left, as the spots farther than an edge are.
    if (checked_before > out_of_reach(emin_, emax_)) return 0;
    std::vector<Vec3> start_positions;
    for (auto v : movable_) start_positions.push_back(mesh_.point(v));
    // The search sees `grid_` samples a face; its result is kept only if the largest distance over the check's
    // finer samples fell too. Else the search may have only moved the largest distance between its samples: it
    // runs again from the start with twice the samples, while fewer than the check's.
    for (grid_ = kGrid; grid_ < kCheck; grid_ *= 2) {
      const std::size_t moves = search();
      if (moves == 0) return 0;
      const double after = largest_distance(check).second;
      if (after < checked_before) {
        largest = after;
        return moves;
      }
      for (std::size_t m = 0; m < movable_.size(); ++m) mesh_.point(movable_[m]) = start_positions[m];
    }
    return 0;
  }

 private:
  struct Samples;
  // The pattern search over the movable vertices; returns the number of moves kept.
  std::size_t search() {
    samples_ = input_samples(grid_);
    level_ = kLevel * objective().max;  // (the largest distance does not depend on the level)
    forward_.clear();
    for (auto f : faces_) forward_.push_back(face_forward_near(f));
    Value current = objective();
    std::size_t moves = 0;
    int sweeps = 0;
    for (double step = kFirstStep * emin_; step >= kLastStep * emin_ && sweeps < kSweeps; ++sweeps) {
      bool improved = false;
      for (std::size_t m = 0; m < movable_.size(); ++m) {
        const auto v = movable_[m];
        const Vec3 start = mesh_.point(v);
        const Vec3 n = geometry::vertex_normal(mesh_, v);
        Vec3 t1, t2;
        geometry::tangent_basis(n, t1, t2);
        Vec3 best_position = start;
        Value best = current;
        save(m);
        for (const Vec3& direction : {n, -n, t1, -t1, t2, -t2}) {
          Value value;
          if (try_position(m, start + step * direction, value) && value.better_than(best)) {
            best = value;
            best_position = start + step * direction;
          }
        }
        if (best_position != start) {
          Value kept;
          try_position(m, best_position, kept);
          for (std::size_t j = 0; j < at_vertex_[m].size(); ++j)
            forward_[static_cast<std::size_t>(at_vertex_[m][j])] = moved_forward_[j];
          current = kept;
          ++moves;
          improved = true;
        } else {
          mesh_.point(v) = start;
        }
      }
      if (!improved) step *= 0.5;
    }
    return moves + joint_search();
  }

  // Steps of every movable vertex at once, after the pattern search: where each vertex alone is held (an edge at an
  // end of the interval, two balanced maxima), a joint step may still lower the largest distance. Each step solves
  // the linear program of the distances near the largest (the faces' samples and their farthest point, the input
  // samples) and the lengths of the edges at the movable vertices, linearised where they are, within a box of
  // half-width r (minimax_step). It is kept if the rules of a move hold at every vertex and the region's largest
  // distance (its faces' farthest point, bracketed, and the input samples) falls; if the faces' farthest point rose
  // instead, that point becomes a row of another try at the same box (kCuts at most), else r is halved.
  std::size_t joint_search() {
    std::size_t steps = 0;
    double radius = kFirstStep * emin_;
    std::vector<Vec3> start(movable_.size());
    Farthest farthest = forward_farthest();
    Nearest nearest = sample_distances(), moved_nearest;
    double best = std::max(farthest.distance, nearest.max);
    if (best > emax_) return 0;  // farther than an edge, a part of the input was cut off here: left (as a spot)
    // Points of the region faces (face position, barycentric weights) where a step's farthest point fell: rows of the
    // next try at the same box (the samples and the farthest point before the step did not see them rise).
    std::vector<std::pair<std::size_t, std::array<double, 3>>> cuts;
    int tries = 0;  // at this box
    for (int k = 0; k < kJointSteps && radius >= kLastStep * emin_; ++k) {
      // A distance moves by at most sqrt(3) r (its point does): one below this cannot set the new largest.
      const double reach = best - 2 * std::sqrt(3.0) * radius;
      std::vector<LinearRow> distances, lengths;
      forward_rows(reach, distances);
      point_row(locate(to_vec(farthest.at)), reach, distances);
      for (const auto& cut : cuts) point_row(cut, reach, distances);
      backward_rows(nearest, reach, distances);
      length_rows(lengths);
      // A length is convex in the displacements, so above its linearisation: by at most |d_a - d_b|^2 / (2 l).
      const double upper = emax_ - 6 * radius * radius / emin_;
      const auto step = minimax_step(distances, lengths, emin_, upper, movable_.size(), radius);
      bool kept = false, cut = false;
      if (step) {
        for (std::size_t m = 0; m < movable_.size(); ++m) {
          start[m] = mesh_.point(movable_[m]);
          mesh_.point(movable_[m]) = start[m] + (*step)[m];
        }
        if (rules_hold()) {
          const Farthest moved = forward_farthest();
          moved_nearest = sample_distances(&nearest);
          const double now = std::max(moved.distance, moved_nearest.max);
          if (now < best * (1 - kGain)) {
            best = now;
            farthest = moved;
            std::swap(nearest, moved_nearest);
            kept = true;
          } else if (moved.distance >= best * (1 - kGain) && tries < kCuts) {
            cuts.push_back(locate(to_vec(moved.at)));
            cut = true;
          }
        }
        if (!kept)
          for (std::size_t m = 0; m < movable_.size(); ++m) mesh_.point(movable_[m]) = start[m];
      }
      if (kept) {
        ++steps;
        cuts.clear();
        tries = 0;
      } else if (cut) {
        ++tries;
      } else {
        radius *= 0.5;
        tries = 0;
      }
    }
    return steps;
  }

  // The region face nearest p, and p's barycentric weights on it.
  std::pair<std::size_t, std::array<double, 3>> locate(const Vec3& p) const {
    const auto triangles = bounded(mesh_, faces_);
    std::size_t hint = triangles.size();
    nearest_distance(p, triangles, std::numeric_limits<double>::infinity(), hint);
    if (hint >= triangles.size()) return {0, {1.0 / 3, 1.0 / 3, 1.0 / 3}};
    const auto& t = triangles[hint];
    return {hint, geometry::barycentric(closest_point_on_triangle(p, t.a, t.b, t.c), t.a, t.b, t.c)};
  }

  // The row of a point of a region face (its position in faces_, its barycentric weights), if farther than `reach`.
  void point_row(const std::pair<std::size_t, std::array<double, 3>>& point, double reach,
                 std::vector<LinearRow>& rows) const {
    const auto [face, weights] = point;
    Vec3 a, b, c;
    geometry::face_points(mesh_, faces_[face], a, b, c);
    const Vec3 p = weights[0] * a + weights[1] * b + weights[2] * c;
    const Vec3 q = to_vec(input_tree_.closest_point(to_point(p)));
    const double d = (p - q).norm();
    if (d <= reach || d <= 0) return;
    LinearRow row;
    row.value = d;
    add_terms(movable_corners(faces_[face]), weights, (p - q) / d, row);
    rows.push_back(std::move(row));
  }

  // The region faces' farthest point from the input (bracketed, as the check).
  Farthest forward_farthest() const {
    Triangles triangles;
    for (auto f : faces_) {
      Vec3 a, b, c;
      geometry::face_points(mesh_, f, a, b, c);
      triangles.emplace_back(to_point(a), to_point(b), to_point(c));
    }
    return farthest_point(triangles, input_tree_, kTolerance, kPiecesPerFace * triangles.size());
  }

  // The search's input samples' distances to the region (or its ring, if nearer: face -1), and the largest.
  struct Nearest {
    std::vector<double> distance;
    std::vector<int> face;  // positions in faces_
    double max = 0;
  };

  // `before` (the same samples, another position of the vertices) gives each sample's first face to try.
  Nearest sample_distances(const Nearest* before = nullptr) const {
    const auto triangles = bounded(mesh_, faces_);
    Nearest out;
    out.distance.resize(samples_.points.size());
    out.face.resize(samples_.points.size());
    for (std::size_t k = 0; k < samples_.points.size(); ++k) {
      std::size_t hint = before && before->face[k] >= 0 ? static_cast<std::size_t>(before->face[k]) : triangles.size();
      const double d = nearest_distance(samples_.points[k], triangles, samples_.ring[k], hint);
      out.distance[k] = d;
      out.face[k] = d < samples_.ring[k] && hint < triangles.size() ? static_cast<int>(hint) : -1;
      out.max = std::max(out.max, d);
    }
    return out;
  }

  // The movable vertices' positions in movable_ of a face's corners (face_points' order; -1: the corner stays).
  std::array<int, 3> movable_corners(TriMesh::FaceHandle f) const {
    std::array<int, 3> out{};
    auto h = mesh_.halfedge_handle(f);
    for (int j = 0; j < 3; ++j, h = mesh_.next_halfedge_handle(h)) {
      const auto it = std::find(movable_.begin(), movable_.end(), mesh_.to_vertex_handle(h));
      out[static_cast<std::size_t>(j)] = it == movable_.end() ? -1 : static_cast<int>(it - movable_.begin());
    }
    return out;
  }

  static void add_terms(const std::array<int, 3>& corners, const std::array<double, 3>& weights, const Vec3& g,
                        LinearRow& row) {
    for (std::size_t j = 0; j < 3; ++j)
      if (corners[j] >= 0 && weights[j] != 0)
        row.terms.emplace_back(static_cast<std::size_t>(corners[j]), weights[j] * g);
  }

  // The search's samples of the region faces, farther than `reach` from the input faces near the region: the distance
  // grows along (p - c) / |p - c|, c the nearest input point, at the face's corners by their barycentric weights.
  void forward_rows(double reach, std::vector<LinearRow>& rows) const {
    for (auto f : faces_) {
      Vec3 a, b, c;
      geometry::face_points(mesh_, f, a, b, c);
      const auto corners = movable_corners(f);
      std::size_t hint = input_near_.size();
      for (int i = 0; i <= grid_; ++i)
        for (int j = 0; j <= grid_ - i; ++j) {
          const double u = static_cast<double>(i) / grid_, v = static_cast<double>(j) / grid_;
          const Vec3 p = (1 - u - v) * a + u * b + v * c;
          const double d = nearest_distance(p, input_near_, std::numeric_limits<double>::infinity(), hint);
          if (d <= reach || d <= 0 || hint >= input_near_.size()) continue;
          const auto& t = input_near_[hint];
          LinearRow row;
          row.value = d;
          add_terms(corners, {1 - u - v, u, v}, (p - closest_point_on_triangle(p, t.a, t.b, t.c)) / d, row);
          rows.push_back(std::move(row));
        }
    }
  }

  // The input samples farther than `reach` from the region and nearer it than the ring: the distance grows along
  // (q - y) / |q - y|, q the nearest point of the region, at its face's corners by q's barycentric weights.
  void backward_rows(const Nearest& nearest, double reach, std::vector<LinearRow>& rows) const {
    for (std::size_t k = 0; k < samples_.points.size(); ++k) {
      const double d = nearest.distance[k];
      if (d <= reach || d <= 0 || nearest.face[k] < 0) continue;
      const auto face = faces_[static_cast<std::size_t>(nearest.face[k])];
      Vec3 a, b, c;
      geometry::face_points(mesh_, face, a, b, c);
      const Vec3& y = samples_.points[k];
      const Vec3 q = closest_point_on_triangle(y, a, b, c);
      LinearRow row;
      row.value = d;
      add_terms(movable_corners(face), geometry::barycentric(q, a, b, c), (q - y) / d, row);
      rows.push_back(std::move(row));
    }
  }

  // The edges at the movable vertices: the length grows along the unit edge vector at one end, against it at the other.
  void length_rows(std::vector<LinearRow>& rows) const {
    for (std::size_t m = 0; m < movable_.size(); ++m)
      for (auto w : mesh_.vv_range(movable_[m])) {
        const auto it = std::find(movable_.begin(), movable_.end(), w);
        const auto other = static_cast<std::size_t>(it - movable_.begin());
        if (it != movable_.end() && other < m) continue;  // taken from the other end
        const Vec3 e = mesh_.point(movable_[m]) - mesh_.point(w);
        LinearRow row;
        row.value = e.norm();
        const Vec3 unit = e / row.value;
        row.terms.emplace_back(m, unit);
        if (it != movable_.end()) row.terms.emplace_back(other, -unit);
        rows.push_back(std::move(row));
      }
  }

  // The rules of a move (try_position's), at every movable vertex.
  bool rules_hold() const {
    for (std::size_t m = 0; m < movable_.size(); ++m) {
      if (!geometry::star_inside(mesh_, movable_[m], emin_, emax_)) return false;
      for (const int i : at_vertex_[m])
        if (OpenMesh::dot(geometry::face_normal(mesh_, faces_[static_cast<std::size_t>(i)]),
                          normals_[static_cast<std::size_t>(i)]) < geometry::kMaxNormalTurnCos)
          return false;
    }
    return true;
  }

  // Samples of the input faces under the region that are nearer a region face than any face of the ring around
  // it (the others are the ring's, which no move changes), with their distance to the ring.
  struct Samples {
    std::vector<Vec3> points;
    std::vector<double> ring;
  };

  Samples input_samples(int grid) const {
    std::vector<Vec3> all;
    for (const int k : inputs_) {
      Vec3 a, b, c;
      geometry::face_points(input_, TriMesh::FaceHandle(k), a, b, c);
      dense_samples(a, b, c, grid, all);
    }
    Samples out;
    const auto region_triangles = bounded(mesh_, faces_), ring_triangles = bounded(mesh_, ring_);
    for (const Vec3& y : all) {
      const double region = nearest_distance(y, region_triangles, std::numeric_limits<double>::infinity());
      const double ring = nearest_distance(y, ring_triangles, std::numeric_limits<double>::infinity());
      if (region < ring) {
        out.points.push_back(y);
        out.ring.push_back(ring);
      }
    }
    return out;
  }

  // The region's largest distance: over every point of its faces to the input (bracketed: attained and bound), and
  // over the input samples to the region (or its ring).
  std::pair<double, double> largest_distance(const Samples& samples) const {
    Triangles triangles;
    for (auto f : faces_) {
      Vec3 a, b, c;
      geometry::face_points(mesh_, f, a, b, c);
      triangles.emplace_back(to_point(a), to_point(b), to_point(c));
    }
    const Farthest forward = farthest_point(triangles, input_tree_, kTolerance, kPiecesPerFace * triangles.size());
    double backward = 0;
    const auto region_triangles = bounded(mesh_, faces_);
    for (std::size_t k = 0; k < samples.points.size(); ++k)
      backward = std::max(backward, nearest_distance(samples.points[k], region_triangles, samples.ring[k]));
    return {std::max(forward.distance, backward), std::max(forward.bound, backward)};
  }

  void collect(TriMesh::FaceHandle spot, bool wide) {
    region_of(mesh_, fixed_, spot, movable_, faces_, wide);
    ring_.clear();
    auto contains = [](const std::vector<TriMesh::FaceHandle>& list, TriMesh::FaceHandle f) {
      return std::find(list.begin(), list.end(), f) != list.end();
    };
    for (auto f : faces_)
      for (auto v : mesh_.fv_range(f))
        for (auto g : mesh_.vf_range(v))
          if (!contains(faces_, g) && !contains(ring_, g)) ring_.push_back(g);
    // The faces at each movable vertex, as positions in faces_.
    at_vertex_.assign(movable_.size(), {});
    for (std::size_t m = 0; m < movable_.size(); ++m)
      for (auto f : mesh_.vf_range(movable_[m]))
        at_vertex_[m].push_back(static_cast<int>(std::find(faces_.begin(), faces_.end(), f) - faces_.begin()));
    // The faces' starting normals (the turn test); the input faces under them.
    normals_.clear();
    inputs_.clear();
    for (auto f : faces_) {
      normals_.push_back(geometry::face_normal(mesh_, f));
      input_faces_under(f, inputs_);
      const auto& near = scan_.input_faces[static_cast<std::size_t>(f.idx())];
      inputs_.insert(inputs_.end(), near.begin(), near.end());
    }
    std::sort(inputs_.begin(), inputs_.end());
    inputs_.erase(std::unique(inputs_.begin(), inputs_.end()), inputs_.end());
    // The search measures the faces' distance to these input faces only: those under the region and the ones
    // around them (a face moved farther would be measured farther than it is, never nearer).
    std::vector<int> near = inputs_;
    for (const int k : inputs_)
      for (auto v : input_.fv_range(TriMesh::FaceHandle(k)))
        for (auto g : input_.vf_range(v)) near.push_back(g.idx());
    std::sort(near.begin(), near.end());
    near.erase(std::unique(near.begin(), near.end()), near.end());
    input_near_.clear();
    for (const int k : near) input_near_.push_back(bounded(input_, TriMesh::FaceHandle(k)));
  }

  // Appends the input faces nearest the face's samples (found in the AABB tree, each sample's hit the next's hint).
  void input_faces_under(TriMesh::FaceHandle f, std::vector<int>& out) const {
    Vec3 a, b, c;
    geometry::face_points(mesh_, f, a, b, c);
    std::vector<Vec3> samples;
    dense_samples(a, b, c, kGrid, samples);
    Tree::Point_and_primitive_id hint;
    bool hinted = false;
    for (const Vec3& p : samples) {
      hint = hinted ? input_tree_.closest_point_and_primitive(to_point(p), hint)
                    : input_tree_.closest_point_and_primitive(to_point(p));
      hinted = true;
      out.push_back(static_cast<int>(hint.second - first_triangle_));
    }
  }

  // The distances of the face's samples to the input faces near the region (the search's measure).
  Value face_forward_near(TriMesh::FaceHandle f) const {
    Vec3 a, b, c;
    geometry::face_points(mesh_, f, a, b, c);
    std::vector<Vec3> samples;
    dense_samples(a, b, c, grid_, samples);
    Value value;
    std::size_t hint = input_near_.size();
    for (const Vec3& p : samples)
      value.add(nearest_distance(p, input_near_, std::numeric_limits<double>::infinity(), hint), level_);
    return value;
  }

  // The distances of the input samples to the triangles, or their bounds if those are nearer.
  Value backward(const std::vector<BoundedTriangle>& triangles, const std::vector<double>& bounds) const {
    Value value;
    for (std::size_t k = 0; k < samples_.points.size(); ++k)
      value.add(nearest_distance(samples_.points[k], triangles, bounds[k]), level_);
    return value;
  }

  // The region's distances with the faces as they are (the search's samples).
  Value objective() const {
    Value value;
    for (auto f : faces_) value.add(face_forward_near(f));
    value.add(backward(bounded(mesh_, faces_), samples_.ring));
    return value;
  }

  // Before the tries of vertex m: the distances that its moves do not change (of and to the faces away from it).
  void save(std::size_t m) {
    std::vector<TriMesh::FaceHandle> others;
    other_forward_ = Value{};
    for (std::size_t i = 0; i < faces_.size(); ++i) {
      if (std::find(at_vertex_[m].begin(), at_vertex_[m].end(), static_cast<int>(i)) != at_vertex_[m].end())
        continue;
      others.push_back(faces_[i]);
      other_forward_.add(forward_[i]);
    }
    const auto triangles = bounded(mesh_, others);
    other_backward_.resize(samples_.points.size());
    for (std::size_t k = 0; k < samples_.points.size(); ++k)
      other_backward_[k] = nearest_distance(samples_.points[k], triangles, samples_.ring[k]);
  }

  // Moves vertex m to p; false if the move breaks a rule, else the region's distances in `value`.
  bool try_position(std::size_t m, const Vec3& p, Value& value) {
    const auto v = movable_[m];
    mesh_.point(v) = p;
    if (!geometry::star_inside(mesh_, v, emin_, emax_)) return false;
    for (const int i : at_vertex_[m])
      if (OpenMesh::dot(geometry::face_normal(mesh_, faces_[static_cast<std::size_t>(i)]),
                        normals_[static_cast<std::size_t>(i)]) < geometry::kMaxNormalTurnCos)
        return false;
    value = other_forward_;
    std::vector<TriMesh::FaceHandle> moved;
    moved_forward_.clear();
    for (const int i : at_vertex_[m]) {
      const auto f = faces_[static_cast<std::size_t>(i)];
      moved_forward_.push_back(face_forward_near(f));
      value.add(moved_forward_.back());
      moved.push_back(f);
    }
    value.add(backward(bounded(mesh_, moved), other_backward_));
    return true;
  }

  TriMesh& mesh_;
  const std::vector<char>* fixed_;
  const TriMesh& input_;
  Triangles::const_iterator first_triangle_;
  const Tree& input_tree_;
  const Scan& scan_;
  double emin_, emax_;
  double level_ = 0;  // the excess level of this region's search
  int grid_ = kGrid;  // and its samples a face (the grid's step is 1 / grid_)
  std::vector<TriMesh::VertexHandle> movable_;
  std::vector<TriMesh::FaceHandle> faces_, ring_;
  std::vector<std::vector<int>> at_vertex_;
  std::vector<int> inputs_;
  std::vector<Vec3> normals_;
  Samples samples_;
  std::vector<BoundedTriangle> input_near_;
  std::vector<Value> forward_, moved_forward_;  // by face of the region; of the faces at the vertex tried
  Value other_forward_;
  std::vector<double> other_backward_;
};

}  // namespace

MinimaxFitResult minimax_fit(TriMesh& mesh, const TriMesh& surface, double emin, double emax,
                             const MinimaxFitSettings& settings, const std::vector<char>* fixed,
                             const SurfaceTree* surface_tree) {
  MinimaxFitResult result;
  if (mesh.n_faces() == 0 || surface.n_faces() == 0) return result;
  std::optional<SurfaceTree> own;  // (built before the threads query it)
  const SurfaceTree& input_surface = surface_tree ? *surface_tree : own.emplace(surface);
  const Triangles& input_triangles = input_surface.triangles();
  const Tree& input_tree = input_surface.tree();
  ScanMemory memory;
  std::vector<char> moved;  // by face index: a corner moved in the last round's searches
  std::vector<Vec3> positions;
  for (int round = 0; round <= settings.rounds; ++round) {
    // Farther than an edge, a part of the input was cut off (RemeshResult::farthest_input): not for this search.
    const auto scan_start = std::chrono::steady_clock::now();
    const Scan found = scan(mesh, surface, input_tree, input_triangles.begin(), settings.share, settings.tolerance,
                            emax, memory, round == 0 ? nullptr : &moved, round < settings.rounds);
    result.scan_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - scan_start).count();
    if (round == 0) result.max_before = found.max;
    result.max_after = found.max;
    if (round == settings.rounds) break;
    // The spots searched: farthest first, each unless the region of an earlier one has its face, kMaxSpots at most.
    std::vector<char> touched(mesh.n_faces(), 0);
    std::vector<TriMesh::FaceHandle> spots;
    std::vector<Vec3> centres;
    std::vector<TriMesh::VertexHandle> movable;
    std::vector<TriMesh::FaceHandle> faces;
    for (const auto& [unused, index] : found.spots) {
      if (spots.size() == kMaxSpots) break;
      if (touched[static_cast<std::size_t>(index)]) continue;
      const TriMesh::FaceHandle spot(index);
      region_of(mesh, fixed, spot, movable, faces);
      for (auto f : faces) touched[static_cast<std::size_t>(f.idx())] = 1;
      Vec3 a, b, c;
      geometry::face_points(mesh, spot, a, b, c);
      spots.push_back(spot);
      centres.push_back((a + b + c) / 3.0);
    }
    result.spots += spots.size();
    // On every thread, with the result of one (OrderedSchedule): a search reads the mesh within 3.6 edges of its
    // spot's centroid (its region and the ring around it), and its vertices move by the sum of its steps at most.
    const double radius = 4 * emax + (kSweeps + std::sqrt(3.0) * kJointSteps) * kFirstStep * emin;
    std::vector<Region> regions(static_cast<std::size_t>(max_threads()),
                                Region(mesh, fixed, surface, input_triangles, input_tree, found, emin, emax));
    std::vector<std::size_t> moves(spots.size(), 0);
    positions.resize(mesh.n_vertices());
    for (std::size_t i = 0; i < positions.size(); ++i)
      positions[i] = mesh.point(TriMesh::VertexHandle(static_cast<int>(i)));
    std::vector<double> largest(spots.size(), 0);
    OrderedSchedule(centres, radius).run([&](std::size_t k, int thread) {
      moves[k] = regions[static_cast<std::size_t>(thread)].optimize(spots[k], false, largest[k]);
    });
    // The region left farthest, if still farther than the tolerance, once more with its vertices' neighbours movable
    // too (where its own vertices are held by edges at the ends of the interval, the ring around can make room).
    if (!spots.empty()) {
      const double searched = out_of_reach(emin, emax);  // farther regions were left (Region::optimize)
      std::size_t worst = spots.size();                    // the farthest of those searched
      for (std::size_t k = 0; k < spots.size(); ++k)
        if (largest[k] <= searched && (worst == spots.size() || largest[k] > largest[worst])) worst = k;
      if (worst < spots.size() && largest[worst] > settings.tolerance) {
        double after = 0;
        const auto t0 = std::chrono::steady_clock::now();
        const std::size_t wide = regions[0].optimize(spots[worst], true, after);
        spdlog::debug("minimax fit: the farthest region searched again with its ring movable, {:.4f} -> {:.4f}, "
                      "{} moves, {:.3f}s", largest[worst], after, wide,
                      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        moves[worst] += wide;
        result.wide_moves += wide;
      }
    }
    std::size_t kept = 0;
    for (const std::size_t m : moves) kept += m;
    result.moves += kept;
    if (kept == 0) break;  // the surface did not change: max_after stands
    moved.assign(mesh.n_faces(), 0);
    for (auto f : mesh.faces())
      for (auto v : mesh.fv_range(f))
        if (mesh.point(v) != positions[static_cast<std::size_t>(v.idx())])
          moved[static_cast<std::size_t>(f.idx())] = 1;
  }
  return result;
}

}  // namespace carbonmesh
