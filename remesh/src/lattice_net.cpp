// The triangular lattice folded onto a net of lattice triangles (lattice_net.hpp).
#include "lattice_net.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>
#include <utility>

namespace carbonmesh::lattice_net {

long det(LatticePoint a, LatticePoint b) { return a[0] * b[1] - a[1] * b[0]; }

LatticePoint turned(LatticePoint p, int sixths) {
  sixths = ((sixths % 6) + 6) % 6;
  for (int s = 0; s < sixths; ++s) p = {-p[1], p[0] + p[1]};  // e1 -> e2, e2 -> e2 - e1
  return p;
}

LatticePoint operator+(LatticePoint a, LatticePoint b) { return {a[0] + b[0], a[1] + b[1]}; }
LatticePoint operator-(LatticePoint a, LatticePoint b) { return {a[0] - b[0], a[1] - b[1]}; }
LatticePoint operator*(long s, LatticePoint a) { return {s * a[0], s * a[1]}; }
long squared_length(LatticePoint a) { return a[0] * a[0] + a[0] * a[1] + a[1] * a[1]; }

namespace {

using Weights = std::array<long, 3>;

// The crossing of an edge: the face on the other side and the map of f's chart onto its chart, y -> R (y - from) + to.
struct Crossing {
  int face = -1;
  int sixths = 0;
  LatticePoint from{}, to{};
};

class Folding {
 public:
  Folding(int corner_count, const std::vector<NetFace>& faces) : corner_count_(corner_count), faces_(faces) {
    struct Side {
      int face, slot;  // the edge from corner slot to slot + 1 of face
    };
    std::map<std::pair<int, int>, std::vector<Side>> sides;
    for (std::size_t f = 0; f < faces_.size(); ++f) {
      const NetFace& t = faces_[f];
      if (det(t.at[1] - t.at[0], t.at[2] - t.at[0]) <= 0)
        throw std::logic_error(fmt::format("lattice net: face {} is not counter-clockwise in its chart", f));
      for (int c = 0; c < 3; ++c) {
        const int u = t.corners[static_cast<std::size_t>(c)], x = t.corners[static_cast<std::size_t>((c + 1) % 3)];
        if (u < 0 || u >= corner_count || x < 0 || x >= corner_count || u == x)
          throw std::logic_error(fmt::format("lattice net: face {} has a bad corner", f));
        sides[std::minmax(u, x)].push_back({static_cast<int>(f), c});
      }
    }
    crossings_.assign(faces_.size(), {});
    long base = corner_count_;
    for (const auto& [key, list] : sides) {
      if (list.size() != 2)
        throw std::logic_error(fmt::format("lattice net: edge {}-{} has {} faces", key.first, key.second, list.size()));
      const NetFace &a = faces_[static_cast<std::size_t>(list[0].face)], &b = faces_[static_cast<std::size_t>(list[1].face)];
      const auto corner = [](const NetFace& t, int slot) { return t.corners[static_cast<std::size_t>(slot % 3)]; };
      const auto at = [](const NetFace& t, int slot) { return t.at[static_cast<std::size_t>(slot % 3)]; };
      if (corner(a, list[0].slot) != corner(b, list[1].slot + 1) || corner(a, list[0].slot + 1) != corner(b, list[1].slot))
        throw std::logic_error(fmt::format("lattice net: edge {}-{} runs the same way in both faces", key.first,
                                           key.second));
      // a's edge u -> x is b's x -> u: the turn R with R (b's x - b's u) = a's x - a's u maps b's chart onto a's.
      const LatticePoint va = at(a, list[0].slot + 1) - at(a, list[0].slot), vb = at(b, list[1].slot) - at(b, list[1].slot + 1);
      int sixths = -1;
      for (int s = 0; s < 6 && sixths < 0; ++s)
        if (turned(vb, s) == va) sixths = s;
      if (sixths < 0)
        throw std::logic_error(fmt::format("lattice net: edge {}-{} has different lattice vectors in its two faces",
                                           key.first, key.second));
      // In face f the edge from slot s to s + 1 lies opposite corner s + 2.
      crossings_[static_cast<std::size_t>(list[0].face)][static_cast<std::size_t>((list[0].slot + 2) % 3)] =
          Crossing{list[1].face, (6 - sixths) % 6, at(a, list[0].slot), at(b, list[1].slot + 1)};
      crossings_[static_cast<std::size_t>(list[1].face)][static_cast<std::size_t>((list[1].slot + 2) % 3)] =
          Crossing{list[0].face, sixths, at(b, list[1].slot + 1), at(a, list[0].slot)};
      edges_.emplace(key, Edge{0, std::gcd(std::labs(va[0]), std::labs(va[1]))});
    }
    // The edges' points numbered edge by edge in the order the faces name the edges (face by face, corner by corner).
    for (const NetFace& t : faces_)
      for (std::size_t c = 0; c < 3; ++c) {
        Edge& e = edges_.at(std::minmax(t.corners[c], t.corners[(c + 1) % 3]));
        if (e.base > 0) continue;
        e.base = base;
        base += e.steps - 1;
      }
    // The lattice points strictly inside each face, ranked row by row (a row's are consecutive).
    rows_.resize(faces_.size());
    for (std::size_t f = 0; f < faces_.size(); ++f) {
      Rows& rows = rows_[f];
      const NetFace& t = faces_[f];
      rows.j0 = std::min({t.at[0][1], t.at[1][1], t.at[2][1]});
      const long j1 = std::max({t.at[0][1], t.at[1][1], t.at[2][1]});
      rows.base = base;
      long inner = 0;
      for (long j = rows.j0; j <= j1; ++j) {
        const auto [lo, hi] = inner_range(static_cast<int>(f), j);
        rows.lo.push_back(lo);
        rows.hi.push_back(hi);
        rows.before.push_back(inner);
        inner += std::max(0L, hi - lo + 1);
      }
      base += inner;
    }
    places_.assign(static_cast<std::size_t>(base), Place{});
  }

  Folded fold() {
    Folded out;
    for (std::size_t f = 0; f < faces_.size(); ++f) {
      const Rows& rows = rows_[f];
      const long j1 = rows.j0 + static_cast<long>(rows.lo.size()) - 1;
      for (long j = rows.j0 - 1; j <= j1; ++j) {
        // The unit triangles between rows j and j + 1 whose centroid can lie in the face: the face's extent there is
        // that of its sections at the two rows (its corners lie on rows).
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (long row : {j, j + 1}) {
          const auto [a, b] = section(static_cast<int>(f), row);
          if (a <= b) lo = std::min(lo, a), hi = std::max(hi, b);
        }
        if (!(lo <= hi)) continue;
        for (long i = static_cast<long>(std::floor(lo)) - 1; i <= static_cast<long>(std::ceil(hi)); ++i) {
          add_if_inside(out.triangles, static_cast<int>(f), {{{i, j}, {i + 1, j}, {i, j + 1}}}, {3 * i + 1, 3 * j + 1});
          add_if_inside(out.triangles, static_cast<int>(f), {{{i + 1, j}, {i + 1, j + 1}, {i, j + 1}}},
                        {3 * i + 2, 3 * j + 2});
        }
      }
    }
    for (std::size_t v = 0; v < places_.size(); ++v)
      if (places_[v].face < 0) throw std::logic_error(fmt::format("lattice net: vertex {} is on no triangle", v));
    out.places = std::move(places_);
    return out;
  }

 private:
  struct Edge {
    long base, steps;  // the ids of its inner points: base + s - 1 for s = 1 .. steps - 1 from its smaller corner
  };
  struct Rows {  // the inner points of a face: on row j0 + r, i from lo[r] to hi[r], ranked from base + before[r]
    long j0 = 0, base = 0;
    std::vector<long> lo, hi, before;
  };

  // Each weight of the point (i, j) in face f's chart is W_c(0) + i s_c: the pairs (W_c(0), s_c).
  std::array<std::pair<long, long>, 3> row_weights(int f, long j) const {
    const Weights at0 = weights(f, {0, j}, 1), at1 = weights(f, {1, j}, 1);
    return {{{at0[0], at1[0] - at0[0]}, {at0[1], at1[1] - at0[1]}, {at0[2], at1[2] - at0[2]}}};
  }

  // The i with every weight of (i, j) positive: [lo, hi], empty when lo > hi.
  std::pair<long, long> inner_range(int f, long j) const {
    long lo = std::numeric_limits<long>::min() / 4, hi = std::numeric_limits<long>::max() / 4;
    for (const auto& [w0, slope] : row_weights(f, j)) {
      if (slope > 0) lo = std::max(lo, floor_div(-w0, slope) + 1);         // w0 + i slope > 0
      else if (slope < 0) hi = std::min(hi, ceil_div(w0, -slope) - 1);    // w0 - i |slope| > 0
      else if (w0 <= 0) return {1, 0};
    }
    return {lo, hi};
  }

  // The real i with every weight of (i, j) at least 0 (the face's section by row j): [lo, hi], empty when lo > hi.
  std::pair<double, double> section(int f, long j) const {
    double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
    for (const auto& [w0, slope] : row_weights(f, j)) {
      if (slope > 0) lo = std::max(lo, static_cast<double>(-w0) / static_cast<double>(slope));
      else if (slope < 0) hi = std::min(hi, static_cast<double>(w0) / static_cast<double>(-slope));
      else if (w0 < 0) return {1, 0};
    }
    return {lo, hi};
  }

  static long floor_div(long a, long b) { return a / b - ((a % b != 0) && ((a < 0) != (b < 0)) ? 1 : 0); }
  static long ceil_div(long a, long b) { return -floor_div(-a, b); }

  // The barycentric weights of the point x / scale in face f's chart, times scale^2 det (integers).
  Weights weights(int f, LatticePoint x, long scale) const {
    const NetFace& t = faces_[static_cast<std::size_t>(f)];
    const LatticePoint a = scale * t.at[0] - x, b = scale * t.at[1] - x, c = scale * t.at[2] - x;
    return {det(b, c), det(c, a), det(a, b)};
  }

  LatticePoint cross(const Crossing& c, LatticePoint x, long scale) const {
    return turned(x - scale * c.from, c.sixths) + scale * c.to;
  }

  void add_if_inside(std::vector<std::array<int, 3>>& out, int f, const std::array<LatticePoint, 3>& corners,
                     LatticePoint centroid3) {
    const Weights w = weights(f, centroid3, 3);
    for (std::size_t c = 0; c < 3; ++c) {
      if (w[c] < 0) return;
      if (w[c] == 0 && crossings_[static_cast<std::size_t>(f)][c].face < f) return;  // on an edge: the smaller face's
    }
    std::array<int, 3> ids{};
    for (std::size_t c = 0; c < 3; ++c) ids[c] = vertex(f, corners[c], centroid3);
    out.push_back(ids);
  }

  // The vertex at lattice point p of face f's chart, reached from the centroid (times 3) of a lattice triangle inside
  // f along the straight segment between them, face by face (the segment lies in the lattice triangle, which holds no
  // lattice point but its corners, so it crosses edges, never corners; the centroid itself may lie on an edge).
  int vertex(int f, LatticePoint p, LatticePoint centroid3) {
    int face = f;
    for (std::size_t step = 0; step <= faces_.size(); ++step) {
      const Weights wp = weights(face, p, 1);
      if (wp[0] >= 0 && wp[1] >= 0 && wp[2] >= 0) return classify(face, p, wp);
      const Weights wc = weights(face, centroid3, 3);
      // It leaves the face where a weight falls to zero first: at s = wc / (wc - 9 wp) along the segment (at once
      // where the centroid lies on that edge, as with (h, h): its edges run through centroids).
      std::size_t exit = 3;
      for (std::size_t c = 0; c < 3; ++c) {
        if (wp[c] >= 0) continue;
        if (wc[c] < 0) throw std::logic_error("lattice net: a segment that misses a face it crosses");
        if (exit == 3 || wc[c] * (wc[exit] - 9 * wp[exit]) < wc[exit] * (wc[c] - 9 * wp[c])) exit = c;
      }
      const Crossing& c = crossings_[static_cast<std::size_t>(face)][exit];
      p = cross(c, p, 1);
      centroid3 = cross(c, centroid3, 3);
      face = c.face;
    }
    throw std::logic_error("lattice net: a lattice point beyond every face");
  }

  int classify(int f, LatticePoint p, const Weights& w) {
    const NetFace& t = faces_[static_cast<std::size_t>(f)];
    const long d = w[0] + w[1] + w[2];
    int zeros = 0;
    for (long x : w) zeros += x == 0 ? 1 : 0;
    long id = -1;
    if (zeros == 2) {
      for (std::size_t c = 0; c < 3; ++c)
        if (w[c] == d) id = t.corners[c];
    } else if (zeros == 1) {
      std::size_t c = 0;
      while (w[c] != 0) ++c;
      const int u = t.corners[(c + 1) % 3], x = t.corners[(c + 2) % 3];
      const Edge& e = edges_.at(std::minmax(u, x));
      const long toward_larger = u < x ? w[(c + 2) % 3] : w[(c + 1) % 3];  // the weight of the larger corner
      const long step = toward_larger * e.steps / d;
      if (step * d != toward_larger * e.steps || step < 1 || step >= e.steps)
        throw std::logic_error("lattice net: an edge point off the lattice");
      id = e.base + step - 1;
    } else {
      const Rows& rows = rows_[static_cast<std::size_t>(f)];
      const long r = p[1] - rows.j0;
      if (r < 0 || r >= static_cast<long>(rows.lo.size()) || p[0] < rows.lo[static_cast<std::size_t>(r)] ||
          p[0] > rows.hi[static_cast<std::size_t>(r)])
        throw std::logic_error("lattice net: an inner point not ranked");
      id = rows.base + rows.before[static_cast<std::size_t>(r)] + (p[0] - rows.lo[static_cast<std::size_t>(r)]);
    }
    if (id < 0) throw std::logic_error("lattice net: a corner not found");
    Place& place = places_[static_cast<std::size_t>(id)];
    if (place.face < 0)
      place = {f, {static_cast<double>(w[0]) / static_cast<double>(d), static_cast<double>(w[1]) / static_cast<double>(d),
                   static_cast<double>(w[2]) / static_cast<double>(d)}};
    return static_cast<int>(id);
  }

  int corner_count_;
  const std::vector<NetFace>& faces_;
  std::vector<std::array<Crossing, 3>> crossings_;
  std::map<std::pair<int, int>, Edge> edges_;
  std::vector<Rows> rows_;
  std::vector<Place> places_;
};

}  // namespace

Folded fold_lattice(int corner_count, const std::vector<NetFace>& faces) {
  return Folding(corner_count, faces).fold();
}

}  // namespace carbonmesh::lattice_net
