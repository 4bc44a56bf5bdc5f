// Section 4.2: valence optimizer with a priority list (Algorithm 2).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>
#include <vector>

#include <spdlog/spdlog.h>

#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/remesh_steps.hpp"
#include "flip_quad.hpp"
#include "local_region.hpp"
#include "ordered_schedule.hpp"
#include "per_element.hpp"
#include "remesh_geometry.hpp"
#include "threads.hpp"

namespace carbonmesh {
namespace {

int sq(int x) { return x * x; }

// A flip is kept only if the smallest angle does not drop below half of its value (section 3.5.3) and
// neither new triangle turns against the old ones (no fold).
bool flip_geometry_ok(const TriMesh& mesh, const FlipQuad& q) {
  return geometry::flip_keeps_shape(mesh.point(q.a), mesh.point(q.b), mesh.point(q.c), mesh.point(q.d));
}

}  // namespace

namespace {

// Eq 4.3 from cached valences: J_mp = E_val before - E_val after over the four vertices that change.
int improvement(const FlipQuad& q, const std::vector<int>& valence, const std::vector<int>& ideal) {
  auto at = [](const std::vector<int>& a, TriMesh::VertexHandle v) { return a[static_cast<std::size_t>(v.idx())]; };
  const int va = at(valence, q.a), vb = at(valence, q.b), vc = at(valence, q.c), vd = at(valence, q.d);
  const int ia = at(ideal, q.a), ib = at(ideal, q.b), ic = at(ideal, q.c), id = at(ideal, q.d);
  const int before = sq(ia - va) + sq(ib - vb) + sq(ic - vc) + sq(id - vd);  // Eq 4.2 on the four vertices
  const int after = sq(ia - (va - 1)) + sq(ib - (vb - 1)) + sq(ic - (vc + 1)) + sq(id - (vd + 1));
  return before - after;
}

// Valence and ideal valence of every vertex, kept up to date by the flips, and the J_mp of an edge from them.
struct ValenceTable {
  std::vector<int> valence, ideal;
  explicit ValenceTable(const TriMesh& mesh) : valence(mesh.n_vertices(), 0), ideal(mesh.n_vertices(), 0) {
    const int n = static_cast<int>(mesh.n_vertices());
#pragma omp parallel for schedule(static) if (n > 4096)
    for (int i = 0; i < n; ++i) {
      const TriMesh::VertexHandle v(i);
      if (mesh.status(v).deleted()) continue;
      valence[static_cast<std::size_t>(i)] = geometry::valence(mesh, v);
      ideal[static_cast<std::size_t>(i)] = ideal_valence(mesh, v);
    }
  }
  int gain(const TriMesh& mesh, TriMesh::EdgeHandle e) const {
    if (mesh.status(e).deleted() || mesh.is_boundary(e)) return 0;
    return improvement(quad(mesh, e), valence, ideal);
  }
};

}  // namespace

int valence_improvement(const TriMesh& mesh, TriMesh::EdgeHandle e) {
  if (mesh.status(e).deleted() || mesh.is_boundary(e)) return 0;
  const FlipQuad q = quad(mesh, e);
  // improvement() read from the mesh (no tables of every vertex: the feature snap calls this per flip it considers)
  auto off = [&](TriMesh::VertexHandle v, int change) {
    return sq(ideal_valence(mesh, v) - (geometry::valence(mesh, v) + change));
  };
  return off(q.a, 0) + off(q.b, 0) + off(q.c, 0) + off(q.d, 0) -
         (off(q.a, -1) + off(q.b, -1) + off(q.c, 1) + off(q.d, 1));
}

std::size_t correct_valence(TriMesh& mesh, double m, const EdgeInterval* keep) {
  struct Entry {
    int gain;
    double distance;  // | |e| - m |: farther from the interval centre first on equal gain
    int edge;
  };
  ValenceTable table(mesh);
  std::vector<int>& valence = table.valence;
  auto gain = [&](TriMesh::EdgeHandle e) { return table.gain(mesh, e); };
  std::size_t total = 0;
  // A flip refused once is refused again while no flip has touched its quad (valences, connectivity and
  // positions are the same): `failed[e]` is the flip count when e was refused, `touched[v]` the flip count when v
  // was last in a flipped quad. Skipping those re-checks gives the same flips (stanford-bunny's first iteration:
  // 15 passes over a list of 19000-67000 edges, most of them refused every time).
  std::vector<unsigned> failed(mesh.n_edges(), 0), touched(mesh.n_vertices(), 0);
  unsigned clock = 1;
  auto unchanged_since_refused = [&](TriMesh::EdgeHandle e) {
    const unsigned at = failed[static_cast<std::size_t>(e.idx())];
    if (at == 0) return false;
    const FlipQuad q = quad(mesh, e);
    for (auto v : {q.a, q.b, q.c, q.d})
      if (touched[static_cast<std::size_t>(v.idx())] > at) return false;
    return true;
  };
  for (int pass = 0; pass < 100; ++pass) {
    // The gains of every edge on every thread, listed in edge order (the same list for any thread count).
    const std::vector<int> gains = per_element(mesh.n_edges(), [&](int i) { return gain(TriMesh::EdgeHandle(i)); });
    std::vector<Entry> list;
    for (int i = 0; i < static_cast<int>(gains.size()); ++i) {
      const int g = gains[static_cast<std::size_t>(i)];
      const TriMesh::EdgeHandle e(i);
      if (g > 0) list.push_back({g, std::abs(geometry::edge_length(mesh, e) - m), i});
    }
    std::sort(list.begin(), list.end(), [](const Entry& x, const Entry& y) {
      if (x.gain != y.gain) return x.gain > y.gain;
      if (x.distance != y.distance) return x.distance > y.distance;
      return x.edge < y.edge;
    });
    std::size_t flips = 0;
    auto refuse = [&](TriMesh::EdgeHandle e) { failed[static_cast<std::size_t>(e.idx())] = clock; };
    for (const Entry& entry : list) {
      const TriMesh::EdgeHandle e(entry.edge);
      if (unchanged_since_refused(e)) continue;
      if (gain(e) <= 0 || !mesh.is_flip_ok(e)) {
        refuse(e);
        continue;
      }
      const FlipQuad q = quad(mesh, e);
      if (!flip_geometry_ok(mesh, q)) {  // the undo of Algorithm 2, checked beforehand
        refuse(e);
        continue;
      }
      if (keep) {  // do not trade an edge inside the interval for one outside
        const double before = geometry::edge_length(mesh, e);
        const double after = (mesh.point(q.c) - mesh.point(q.d)).norm();
        const bool inside_before = before >= keep->emin && before <= keep->emax;
        if (inside_before && (after < keep->emin || after > keep->emax)) {
          refuse(e);
          continue;
        }
      }
      mesh.flip(e);
      ++clock;
      for (auto v : {q.a, q.b, q.c, q.d}) touched[static_cast<std::size_t>(v.idx())] = clock;
      --valence[static_cast<std::size_t>(q.a.idx())];
      --valence[static_cast<std::size_t>(q.b.idx())];
      ++valence[static_cast<std::size_t>(q.c.idx())];
      ++valence[static_cast<std::size_t>(q.d.idx())];
      ++flips;
    }
    total += flips;
    if (flips == 0) break;
  }
  return total;
}

namespace {

// How many E_val-neutral flips may precede the flip that lowers E_val in a chain (regularize).
constexpr int kChainDepth = 4;

// Some vertex of the flip quad is irregular (only then can a flip pair lower E_val).
bool valence_defect(const FlipQuad& q, const std::vector<int>& valence, const std::vector<int>& ideal) {
  for (auto v : {q.a, q.b, q.c, q.d})
    if (valence[static_cast<std::size_t>(v.idx())] != ideal[static_cast<std::size_t>(v.idx())]) return true;
  return false;
}

// What regularize's flips share: the mesh and its valences, the vertices changed in this pass, and the limits.
struct FlipContext {
  TriMesh& mesh;
  const ProjectionTarget& target;
  ValenceTable& table;
  std::vector<char>& changed;
  int kn;
  double emin, emax;
  // With an anchor (the chain stage), a settle that leaves a vertex farther than max_drift from its anchor is undone.
  const std::vector<Vec3>* anchor = nullptr;
  double max_drift = std::numeric_limits<double>::infinity();
};

// One thread's flips (settle() and the chains of flips) with their scratch space.
class Flipper {
 public:
  explicit Flipper(FlipContext& c) : c_(c) {}

  std::size_t kept = 0;

  void count_flip(const FlipQuad& q, int sign) {
    auto& valence = c_.table.valence;
    valence[static_cast<std::size_t>(q.a.idx())] -= sign;
    valence[static_cast<std::size_t>(q.b.idx())] -= sign;
    valence[static_cast<std::size_t>(q.c.idx())] += sign;
    valence[static_cast<std::size_t>(q.d.idx())] += sign;
  }

  // Flips `edges` (already flipped in the mesh, quads `quads`) are kept if every edge around is inside, after
  // relaxing the kn-stars of the new edges and projecting, with no vertex drifted from its anchor; else
  // everything is restored.
  bool settle(const std::vector<TriMesh::EdgeHandle>& edges, const std::vector<FlipQuad>& quads) {
    TriMesh& mesh = c_.mesh;
    auto all_inside = [&] {
      for (const FlipQuad& q : quads)
        for (auto v : {q.a, q.b, q.c, q.d})
          if (!geometry::star_inside(mesh, v, c_.emin, c_.emax)) return false;
      return true;
    };
    if (all_inside()) {
      mark_changed(quads);
      return true;
    }
    saved_.clear();
    for (auto e : edges) {
      optimize_edge_region(mesh, e, c_.kn, c_.emin, c_.emax, moved_);
      saved_.insert(saved_.end(), moved_.begin(), moved_.end());
      for (const auto& [v, before] : moved_) project_with_ring(mesh, c_.target, v, neighbors_);
    }
    bool ok = all_inside();
    for (const auto& [v, before] : saved_)
      ok = ok && geometry::star_inside(mesh, v, c_.emin, c_.emax) &&
           (!c_.anchor || (mesh.point(v) - (*c_.anchor)[static_cast<std::size_t>(v.idx())]).norm() <= c_.max_drift);
    if (ok) {
      mark_changed(quads);
      for (const auto& [v, before] : saved_) c_.changed[static_cast<std::size_t>(v.idx())] = 1;
      return true;
    }
    for (auto it = saved_.rbegin(); it != saved_.rend(); ++it) mesh.set_point(it->first, it->second);
    for (std::size_t i = edges.size(); i-- > 0;) {
      mesh.flip(edges[i]);
      count_flip(quads[i], -1);
    }
    return false;
  }

  // The chain from the E_val-neutral flip of e.
  void chain_from(TriMesh::EdgeHandle e) {
    TriMesh& mesh = c_.mesh;
    const auto& valence = c_.table.valence;
    const auto& ideal = c_.table.ideal;
    if (mesh.status(e).deleted() || mesh.is_boundary(e)) return;
    const FlipQuad q = quad(mesh, e);
    if (improvement(q, valence, ideal) != 0 || !mesh.is_flip_ok(e) || !flip_geometry_ok(mesh, q)) return;
    mesh.flip(e);
    count_flip(q, 1);
    chain_.assign(1, e);
    chain_quads_.assign(1, q);
    if (extend(kChainDepth)) {
      ++kept;
    } else if (!chain_.empty()) {
      mesh.flip(e);
      count_flip(q, -1);
    }
  }

 private:
  void mark_changed(const std::vector<FlipQuad>& quads) {
    for (const FlipQuad& q : quads)
      for (auto v : {q.a, q.b, q.c, q.d}) c_.changed[static_cast<std::size_t>(v.idx())] = 1;
  }

  // Depth-first: flip `e` (E_val unchanged), then look at the edges at its quad's vertices for a flip lowering
  // E_val (kept with the whole chain if settle() accepts), else go one E_val-neutral flip deeper.
  bool extend(int depth) {
    TriMesh& mesh = c_.mesh;
    const auto& valence = c_.table.valence;
    const auto& ideal = c_.table.ideal;
    const FlipQuad last = chain_quads_.back();
    TriMesh::EdgeHandle second;
    int best = 0;
    std::vector<TriMesh::EdgeHandle> neutral;
    for (auto v : {last.a, last.b, last.c, last.d})
      for (auto h : mesh.voh_range(v)) {
        const auto f = mesh.edge_handle(h);
        if (mesh.is_boundary(f) || std::find(chain_.begin(), chain_.end(), f) != chain_.end()) continue;
        const int g = improvement(quad(mesh, f), valence, ideal);
        if (g > best || (g == best && g > 0 && f.idx() < second.idx())) best = g, second = f;
        if (g == 0 && depth > 0) neutral.push_back(f);
      }
    if (best > 0 && mesh.is_flip_ok(second) && flip_geometry_ok(mesh, quad(mesh, second))) {
      const FlipQuad q2 = quad(mesh, second);
      mesh.flip(second);
      count_flip(q2, 1);
      chain_.push_back(second);
      chain_quads_.push_back(q2);
      if (settle(chain_, chain_quads_)) return true;  // settle() undid every flip of the chain otherwise
      chain_.clear();
      chain_quads_.clear();
      return false;
    }
    std::sort(neutral.begin(), neutral.end(), [](auto x, auto y) { return x.idx() < y.idx(); });
    neutral.erase(std::unique(neutral.begin(), neutral.end()), neutral.end());
    for (auto f : neutral) {
      const FlipQuad qf = quad(mesh, f);
      if (!mesh.is_flip_ok(f) || !flip_geometry_ok(mesh, qf)) continue;
      mesh.flip(f);
      count_flip(qf, 1);
      chain_.push_back(f);
      chain_quads_.push_back(qf);
      const std::size_t size = chain_.size();
      if (extend(depth - 1)) return true;
      if (chain_.size() < size) return false;  // a deeper settle() failed and restored everything
      mesh.flip(f);
      count_flip(qf, -1);
      chain_.pop_back();
      chain_quads_.pop_back();
    }
    return false;
  }

  FlipContext& c_;
  std::vector<std::pair<TriMesh::VertexHandle, Vec3>> moved_, saved_;
  std::vector<Vec3> neighbors_;
  std::vector<TriMesh::EdgeHandle> chain_;
  std::vector<FlipQuad> chain_quads_;
};

}  // namespace

std::size_t regularize(TriMesh& mesh, const ProjectionTarget& target, int kn, double emin, double emax,
                       int max_passes) {
  ValenceTable table(mesh);
  const std::vector<int>& valence = table.valence;
  const std::vector<int>& ideal = table.ideal;
  auto gain = [&](TriMesh::EdgeHandle e) { return table.gain(mesh, e); };
  // A chain reads the mesh within `reach` rings of its first edge: its flips' quads lie within kChainDepth + 2
  // rings of that edge's ends (each flip is of an edge at the previous quad), settle() relaxes kn - 1 rings around
  // their new edges, reading one ring beyond those and the faces across their outer edges.
  const int reach = kChainDepth + kn + 3;
  // A chain that failed fails again unless the mesh changed within its reach. After the first pass, the
  // E_val-neutral starts are tried only near a vertex that a kept flip changed or moved in the previous pass
  // (1 million atoms: the passes after the first took 1.3 s, most of it on chains that had already failed).
  const std::size_t nv = mesh.n_vertices();
  std::vector<char> changed(nv, 0), near(nv, 1);
  std::vector<int> ring(nv, -1);
  auto spread_near = [&] {  // near = within `reach` rings of a changed vertex (breadth first)
    std::fill(near.begin(), near.end(), 0);
    std::fill(ring.begin(), ring.end(), -1);
    std::vector<int> queue;
    for (std::size_t v = 0; v < nv; ++v)
      if (changed[v]) ring[v] = 0, queue.push_back(static_cast<int>(v));
    for (std::size_t k = 0; k < queue.size(); ++k) {
      const auto v = TriMesh::VertexHandle(queue[k]);
      near[static_cast<std::size_t>(v.idx())] = 1;
      const int r = ring[static_cast<std::size_t>(v.idx())];
      if (r == reach) continue;
      for (auto w : mesh.vv_range(v)) {
        int& rw = ring[static_cast<std::size_t>(w.idx())];
        if (rw < 0) rw = r + 1, queue.push_back(w.idx());
      }
    }
    std::fill(changed.begin(), changed.end(), 0);
  };
  FlipContext context{mesh, target, table, changed, kn, emin, emax};
  std::vector<Flipper> flippers;
  for (int t = 0; t < max_threads(); ++t) flippers.emplace_back(context);
  std::size_t total = 0;
  auto seconds_since = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  };
  for (int pass = 0; pass < max_passes; ++pass) {
    const auto pass_start = std::chrono::steady_clock::now();
    struct Entry {
      int gain;
      int edge;
    };
    // Gains and the E_val-neutral starts below on every thread, listed in edge order.
    const std::vector<int> gains = per_element(mesh.n_edges(), [&](int i) { return gain(TriMesh::EdgeHandle(i)); });
    std::vector<Entry> list;
    for (int i = 0; i < static_cast<int>(gains.size()); ++i)
      if (gains[static_cast<std::size_t>(i)] > 0) list.push_back({gains[static_cast<std::size_t>(i)], i});
    std::sort(list.begin(), list.end(), [](const Entry& x, const Entry& y) {
      return x.gain != y.gain ? x.gain > y.gain : x.edge < y.edge;
    });
    for (auto& f : flippers) f.kept = 0;
    Flipper& first = flippers[0];
    for (const Entry& entry : list) {
      const TriMesh::EdgeHandle e(entry.edge);
      if (gain(e) <= 0 || !mesh.is_flip_ok(e)) continue;
      const FlipQuad q = quad(mesh, e);
      if (!flip_geometry_ok(mesh, q)) continue;
      mesh.flip(e);
      first.count_flip(q, 1);
      if (first.settle({e}, {q})) ++first.kept;
    }
    const std::size_t single = first.kept;
    const double single_seconds = seconds_since(pass_start);
    const auto chains_start = std::chrono::steady_clock::now();
    // Pairs: a flip that leaves E_val unchanged (moving a 5-7 pair) followed by a flip of an edge at one of
    // its four vertices, together lowering E_val.
    auto is_near = [&](const FlipQuad& q) {
      for (auto v : {q.a, q.b, q.c, q.d})
        if (near[static_cast<std::size_t>(v.idx())]) return true;
      return false;
    };
    const std::vector<char> start = per_element(mesh.n_edges(), [&](int i) -> char {
      const TriMesh::EdgeHandle e(i);
      return !mesh.status(e).deleted() && !mesh.is_boundary(e) && improvement(quad(mesh, e), valence, ideal) == 0 &&
             valence_defect(quad(mesh, e), valence, ideal) && is_near(quad(mesh, e));
    });
    std::vector<int> zero;
    for (int i = 0; i < static_cast<int>(start.size()); ++i)
      if (start[static_cast<std::size_t>(i)]) zero.push_back(i);
    // The chains on every thread, with the result of one thread taking them in order (OrderedSchedule): chains
    // that run side by side touch nothing in common. No edge is longer than `longest` here or after a kept chain
    // (settle() keeps every edge at the vertices it changes inside), and the chains keep every vertex within `longest`
    // of where it is here, so the `reach` rings a chain reads lie within `radius` of its first edge's midpoint here
    // (its centre); it writes within `reach` - 2 rings. A chain B whose centre is farther than 2 `radius` from a
    // running chain A's reaches none of A's vertices: a path from B's first edge into A's rings meets first a vertex
    // of their outer ring, which A neither moves nor reconnects and which lies within `radius` of A's centre, so
    // beyond B's reach. The chains are taken by colour of cells wider than 2 `radius` (8 colours, each cell's chains
    // in edge order), and the chains of cells of one colour run side by side. The outputs follow the cells: those of
    // side 2 (reach + 5) longest are the ones measured in docs/benchmarks.md (with side 2 radius bunny's farthest
    // input vertex went 0.60 -> 0.77: the triangulation at its base rim follows the order of the flips).
    const double longest = std::max(emax, edge_stats(mesh).max);
    std::vector<Vec3> anchor(nv);
    for (std::size_t v = 0; v < nv; ++v) anchor[v] = mesh.point(TriMesh::VertexHandle(static_cast<int>(v)));
    context.anchor = &anchor;
    context.max_drift = longest;
    const double radius = (reach + 2) * longest;  // (reach + 1.5: the first edge's ends may have moved)
    const double side = 2 * (reach + 5) * longest;
    struct Start {
      int colour;
      std::array<long, 3> cell;
      int edge;
      Vec3 centre;
    };
    std::vector<Start> starts;
    Vec3 origin(0, 0, 0);
    for (const int edge : zero) {
      const auto h = mesh.halfedge_handle(TriMesh::EdgeHandle(edge), 0);
      const Vec3 centre = 0.5 * (mesh.point(mesh.from_vertex_handle(h)) + mesh.point(mesh.to_vertex_handle(h)));
      for (int a = 0; a < 3; ++a) origin[a] = starts.empty() ? centre[a] : std::min(origin[a], centre[a]);
      starts.push_back({0, {}, edge, centre});
    }
    for (Start& s : starts)
      for (int a = 0; a < 3; ++a) {
        s.cell[static_cast<std::size_t>(a)] = static_cast<long>(std::floor((s.centre[a] - origin[a]) / side));
        s.colour = 2 * s.colour + static_cast<int>(s.cell[static_cast<std::size_t>(a)] & 1);
      }
    std::sort(starts.begin(), starts.end(), [](const Start& x, const Start& y) {
      return std::tie(x.colour, x.cell, x.edge) < std::tie(y.colour, y.cell, y.edge);
    });
    std::vector<Vec3> centres;
    for (const Start& s : starts) centres.push_back(s.centre);
    OrderedSchedule(centres, radius).run([&](std::size_t k, int thread) {
      flippers[static_cast<std::size_t>(thread)].chain_from(TriMesh::EdgeHandle(starts[k].edge));
    });
    context.anchor = nullptr;
    std::size_t flips = 0;
    for (auto& f : flippers) flips += f.kept;
    spdlog::debug("regularize, pass {}: {} single flips, {:.3f}s; {} chains kept of {} starts, {:.3f}s", pass + 1,
                  single, single_seconds, flips - single, starts.size(), seconds_since(chains_start));
    total += flips;
    if (flips == 0) break;
    spread_near();
  }
  return total;
}

}  // namespace carbonmesh
