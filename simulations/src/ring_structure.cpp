#include "carbonmesh/simulations/ring_structure.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/metrics.hpp"

namespace carbonmesh {
namespace {

// Ring adjacency from the rings' bonds: rings that share a bond are neighbours. Also flags bonds per ring.
void adjacency_from_bonds(RingStructure& rs) {
  std::vector<std::pair<Bond, int>> ring_bonds;
  for (std::size_t r = 0; r < rs.rings.size(); ++r) {
    const auto& ring = rs.rings[r];
    const std::size_t n = ring.size();
    const std::size_t edges = rs.open[r] ? n - 1 : n;
    for (std::size_t k = 0; k < edges; ++k) {
      const int a = ring[k], b = ring[(k + 1) % n];
      ring_bonds.push_back({Bond{std::min(a, b), std::max(a, b)}, static_cast<int>(r)});
    }
  }
  std::sort(ring_bonds.begin(), ring_bonds.end());
  rs.neighbors.assign(rs.rings.size(), {});
  bool closed = !rs.rings.empty();
  std::size_t i = 0;
  while (i < ring_bonds.size()) {
    std::size_t j = i;
    while (j < ring_bonds.size() && ring_bonds[j].first == ring_bonds[i].first) ++j;
    if (j - i != 2) closed = false;
    for (std::size_t a = i; a < j; ++a)
      for (std::size_t b = i; b < j; ++b)
        if (ring_bonds[a].second != ring_bonds[b].second) rs.neighbors[ring_bonds[a].second].push_back(ring_bonds[b].second);
    i = j;
  }
  // A bond on no ring also leaves the surface open.
  std::size_t distinct = 0;
  for (std::size_t k = 0; k < ring_bonds.size(); ++k)
    if (k == 0 || ring_bonds[k].first != ring_bonds[k - 1].first) ++distinct;
  if (distinct != rs.atoms.bonds.size()) closed = false;
  for (auto& n : rs.neighbors) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  rs.closed_surface = closed;
}

// Does the ring traverse a -> b (true) or b -> a?
bool traverses(const std::vector<int>& ring, int a, int b) {
  const std::size_t n = ring.size();
  for (std::size_t k = 0; k < n; ++k)
    if (ring[k] == a) return ring[(k + 1) % n] == b;
  return false;
}

// Orients closed rings so that two rings sharing a bond run it in opposite directions (a BFS per component;
// the first ring of a component keeps its direction). Non-orientable or branched parts stay as found.
void orient_consistently(RingStructure& rs) {
  std::vector<bool> seen(rs.size(), false);
  std::vector<int> queue;
  for (std::size_t start = 0; start < rs.size(); ++start) {
    if (seen[start] || rs.open[start]) continue;
    seen[start] = true;
    queue.assign(1, static_cast<int>(start));
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const auto& ring = rs.rings[queue[q]];
      const std::size_t n = ring.size();
      for (int s : rs.neighbors[queue[q]]) {
        if (seen[s] || rs.open[s]) continue;
        // A bond a -> b of this ring that s also has: s must run b -> a.
        for (std::size_t k = 0; k < n; ++k) {
          const int a = ring[k], b = ring[(k + 1) % n];
          const bool forward = traverses(rs.rings[s], a, b);
          if (!forward && !traverses(rs.rings[s], b, a)) continue;
          if (forward) std::reverse(rs.rings[s].begin() + 1, rs.rings[s].end());
          seen[s] = true;
          queue.push_back(s);
          break;
        }
      }
    }
  }
}

void centers_from_atoms(RingStructure& rs) {
  rs.centers.assign(rs.rings.size(), Vec3(0, 0, 0));
  if (rs.atoms.positions.empty()) return;
  for (std::size_t r = 0; r < rs.rings.size(); ++r) {
    Vec3 c(0, 0, 0);
    for (int a : rs.rings[r]) c += rs.atoms.positions[a];
    if (!rs.rings[r].empty()) c /= static_cast<double>(rs.rings[r].size());
    rs.centers[r] = c;
  }
}

}  // namespace

RingStructure rings_from_mesh(const TriMesh& mesh) {
  RingStructure rs;
  rs.source = "triangle mesh";
  std::vector<Vec3> positions;
  positions.reserve(mesh.n_faces());
  for (auto f : mesh.faces()) {
    Vec3 c(0, 0, 0);
    for (auto v : mesh.fv_range(f)) c += mesh.point(v);
    positions.push_back(c / 3.0);
  }
  std::vector<Bond> bonds;
  for (auto e : mesh.edges()) {
    if (mesh.is_boundary(e)) continue;
    const auto h = mesh.halfedge_handle(e, 0);
    bonds.push_back({mesh.face_handle(h).idx(), mesh.face_handle(mesh.opposite_halfedge_handle(h)).idx()});
  }
  rs.atoms = make_atom_graph(mesh.n_faces(), std::move(bonds), std::move(positions));
  rs.rings.resize(mesh.n_vertices());
  rs.sizes.resize(mesh.n_vertices());
  rs.open.resize(mesh.n_vertices());
  rs.centers.resize(mesh.n_vertices());
  rs.neighbors.resize(mesh.n_vertices());
  for (auto v : mesh.vertices()) {
    const int i = v.idx();
    rs.open[i] = mesh.is_boundary(v);
    rs.centers[i] = mesh.point(v);
    int valence = 0;
    for (auto w : mesh.vv_range(v)) {
      rs.neighbors[i].push_back(w.idx());
      ++valence;
    }
    std::sort(rs.neighbors[i].begin(), rs.neighbors[i].end());
    rs.sizes[i] = valence;
    // Faces around v in order; for a border vertex start after the border so the fan is contiguous.
    auto start = mesh.halfedge_handle(v);  // OpenMesh: the outgoing border halfedge if v is on a border
    auto h = start;
    do {
      if (!mesh.is_boundary(h)) rs.rings[i].push_back(mesh.face_handle(h).idx());
      h = mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(h));  // cw around v
    } while (h != start && h.is_valid());
  }
  const Topology t = topology(mesh);
  rs.euler = t.euler;
  rs.closed_surface = t.boundary_loops == 0;
  return rs;
}

RingStructure rings_from_polygons(const PolygonSoup& soup, const std::string& source) {
  const int n = static_cast<int>(soup.points.size());
  std::vector<Bond> bonds;
  std::vector<std::vector<int>> rings;
  rings.reserve(soup.polygons.size());
  for (std::size_t f = 0; f < soup.polygons.size(); ++f) {
    const auto& poly = soup.polygons[f];
    if (poly.size() < 3) throw InputError(fmt::format("{}: face {} has {} corners", source, f, poly.size()));
    for (int a : poly)
      if (a < 0 || a >= n) throw InputError(fmt::format("{}: face {} names vertex {} of {}", source, f, a, n));
    std::vector<int> sorted = poly;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
      throw InputError(fmt::format("{}: face {} repeats a corner", source, f));
    for (std::size_t k = 0; k < poly.size(); ++k) bonds.push_back({poly[k], poly[(k + 1) % poly.size()]});
    rings.push_back(poly);
  }
  RingStructure rs = rings_from_graph(make_atom_graph(soup.points.size(), std::move(bonds), soup.points), std::move(rings));
  rs.source = "polygon mesh";
  return rs;
}

RingStructure rings_from_graph(AtomGraph graph, std::vector<std::vector<int>> rings) {
  RingStructure rs;
  rs.source = "atom graph (SP rings)";
  rs.atoms = std::move(graph);
  rs.rings = std::move(rings);
  rs.sizes.resize(rs.rings.size());
  for (std::size_t r = 0; r < rs.rings.size(); ++r) rs.sizes[r] = static_cast<int>(rs.rings[r].size());
  rs.open.assign(rs.rings.size(), false);
  centers_from_atoms(rs);
  adjacency_from_bonds(rs);
  orient_consistently(rs);
  rs.euler = static_cast<long>(rs.atoms.atoms()) - static_cast<long>(rs.atoms.bonds.size()) +
             static_cast<long>(rs.rings.size());
  return rs;
}

}  // namespace carbonmesh
