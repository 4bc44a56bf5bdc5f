#include "carbonmesh/dual/dual_mesh.hpp"

#include <spdlog/spdlog.h>

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

namespace carbonmesh {

std::vector<Vec3> Dual::positions() const {
  std::vector<Vec3> out;
  out.reserve(mesh.n_vertices());
  for (auto v : mesh.vertices()) out.push_back(mesh.point(v));
  return out;
}

void Dual::set_positions(const std::vector<Vec3>& positions) {
  if (positions.size() != mesh.n_vertices()) throw std::invalid_argument("Dual::set_positions: wrong atom count");
  for (auto v : mesh.vertices()) mesh.set_point(v, positions[static_cast<std::size_t>(v.idx())]);
}

namespace {

// Faces around `v` counter-clockwise (seen from the side the primal normals point to). For a border vertex the
// chain starts right after the border gap, so it is the open ring in order.
std::vector<TriMesh::FaceHandle> faces_ccw(const TriMesh& primal, TriMesh::VertexHandle v) {
  TriMesh::HalfedgeHandle start = primal.halfedge_handle(v);
  for (auto h : primal.voh_range(v))
    if (primal.is_boundary(h)) {
      start = h;
      break;
    }
  std::vector<TriMesh::FaceHandle> faces;
  TriMesh::HalfedgeHandle h = start;
  do {
    h = primal.ccw_rotated_halfedge_handle(h);
    if (!primal.is_boundary(h)) faces.push_back(primal.face_handle(h));
  } while (h != start && faces.size() <= primal.n_faces());
  return faces;
}

}  // namespace

Dual build_dual(const TriMesh& primal) {
  Dual dual;
  dual.face_atom.assign(primal.n_faces(), -1);
  for (auto f : primal.faces()) {
    Vec3 c(0, 0, 0);
    for (auto v : primal.fv_range(f)) c += primal.point(v);
    const auto atom = dual.mesh.add_vertex(c / 3.0);
    dual.face_atom[static_cast<std::size_t>(f.idx())] = atom.idx();
    dual.atom_face.push_back(f.idx());
  }

  for (auto e : primal.edges()) {
    if (primal.is_boundary(e)) continue;
    int a = dual.face_atom[static_cast<std::size_t>(primal.face_handle(primal.halfedge_handle(e, 0)).idx())];
    int b = dual.face_atom[static_cast<std::size_t>(primal.face_handle(primal.halfedge_handle(e, 1)).idx())];
    if (a > b) std::swap(a, b);
    dual.bonds.push_back({a, b});
    dual.bond_edge.push_back(e.idx());
  }

  dual.vertex_ring.assign(primal.n_vertices(), -1);
  for (auto v : primal.vertices()) {
    if (primal.is_isolated(v)) continue;
    const auto faces = faces_ccw(primal, v);
    std::vector<int> ring;
    ring.reserve(faces.size());
    for (auto f : faces) ring.push_back(dual.face_atom[static_cast<std::size_t>(f.idx())]);
    const bool closed = !primal.is_boundary(v);
    int face = -1;
    if (closed) {
      std::vector<DualMesh::VertexHandle> corners;
      for (int a : ring) corners.push_back(dual.mesh.vertex_handle(static_cast<unsigned>(a)));
      const auto fh = dual.mesh.add_face(corners);
      if (!fh.is_valid())
        throw std::runtime_error("build_dual: the ring of primal vertex " + std::to_string(v.idx()) +
                                 " does not fit a manifold dual (non-manifold input?)");
      face = fh.idx();
    }
    dual.vertex_ring[static_cast<std::size_t>(v.idx())] = static_cast<int>(dual.rings.size());
    dual.rings.push_back(std::move(ring));
    dual.ring_closed.push_back(closed);
    dual.ring_vertex.push_back(v.idx());
    dual.ring_face.push_back(face);
  }
  dual.mesh.update_face_normals();
  dual.counts = count_dual(dual);
  spdlog::info("dual: {} atoms, {} bonds, {} closed rings, {} open rings, {} border atoms", dual.counts.atoms,
               dual.counts.bonds, dual.counts.closed_rings, dual.counts.open_rings, dual.counts.border_atoms);
  return dual;
}

DualCounts count_dual(const Dual& dual) {
  DualCounts c;
  c.atoms = dual.atoms();
  c.bonds = dual.bonds.size();
  std::vector<int> degree(c.atoms, 0);
  for (const auto& b : dual.bonds) {
    ++degree[static_cast<std::size_t>(b[0])];
    ++degree[static_cast<std::size_t>(b[1])];
  }
  std::size_t three = 0;
  for (int d : degree) {
    ++c.coordination[d];
    if (d < 3) ++c.border_atoms;
    if (d == 3) ++three;
  }
  c.percent_three_bonds = c.atoms == 0 ? 0.0 : 100.0 * static_cast<double>(three) / static_cast<double>(c.atoms);
  for (std::size_t r = 0; r < dual.rings.size(); ++r) {
    if (dual.ring_closed[r]) {
      ++c.closed_rings;
      ++c.ring_sizes[static_cast<int>(dual.rings[r].size())];
    } else {
      ++c.open_rings;
    }
  }
  return c;
}

nlohmann::json to_json(const DualCounts& c) {
  nlohmann::json sizes = nlohmann::json::object(), coordination = nlohmann::json::object();
  for (const auto& [size, n] : c.ring_sizes) sizes[std::to_string(size)] = n;
  for (const auto& [d, n] : c.coordination) coordination[std::to_string(d)] = n;
  return {{"atoms", c.atoms},
          {"bonds", c.bonds},
          {"closed_rings", c.closed_rings},
          {"open_rings", c.open_rings},
          {"rings_by_size", sizes},
          {"atoms_by_bond_count", coordination},
          {"border_atoms", c.border_atoms},
          {"percent_three_bonds", c.percent_three_bonds}};
}

}  // namespace carbonmesh
