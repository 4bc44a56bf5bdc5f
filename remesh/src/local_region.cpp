#include "local_region.hpp"

#include "remesh_geometry.hpp"

namespace carbonmesh {

void project_with_ring(TriMesh& mesh, const ProjectionTarget& target, TriMesh::VertexHandle v,
                       std::vector<Vec3>& neighbors) {
  neighbors.clear();
  for (auto w : mesh.vv_range(v)) neighbors.push_back(mesh.point(w));
  mesh.set_point(v, target.project(mesh.point(v), neighbors));
}

void LocalRegion::collect(const TriMesh& mesh, TriMesh::VertexHandle v, int rings,
                          std::vector<TriMesh::VertexHandle>& out) {
  if (vertex_mark_.size() < mesh.n_vertices()) vertex_mark_.resize(mesh.n_vertices(), 0);
  ++stamp_;
  out.assign(1, v);
  vertex_mark_[static_cast<std::size_t>(v.idx())] = stamp_;
  for (std::size_t begin = 0, ring = 0; ring < static_cast<std::size_t>(rings); ++ring) {
    const std::size_t end = out.size();
    for (std::size_t i = begin; i < end; ++i)
      for (auto w : mesh.vv_range(out[i]))
        if (vertex_mark_[static_cast<std::size_t>(w.idx())] != stamp_) {
          vertex_mark_[static_cast<std::size_t>(w.idx())] = stamp_;
          out.push_back(w);
        }
    begin = end;
  }
}

std::size_t LocalRegion::flaws(const TriMesh& mesh, const std::vector<TriMesh::VertexHandle>& vertices) {
  if (edge_mark_.size() < mesh.n_edges()) edge_mark_.resize(mesh.n_edges(), 0);
  if (face_mark_.size() < mesh.n_faces()) face_mark_.resize(mesh.n_faces(), 0);
  ++stamp_;
  std::size_t count = 0;
  for (auto v : vertices) {
    if (mesh.status(v).deleted()) continue;
    for (auto h : mesh.voh_range(v)) {
      const auto e = mesh.edge_handle(h);
      if (edge_mark_[static_cast<std::size_t>(e.idx())] != stamp_) {
        edge_mark_[static_cast<std::size_t>(e.idx())] = stamp_;
        const double l = mesh.calc_edge_length(e);
        count += l < emin_ || l > emax_ ? 1 : 0;
      }
      const auto f = mesh.face_handle(h);
      if (f.is_valid() && face_mark_[static_cast<std::size_t>(f.idx())] != stamp_) {
        face_mark_[static_cast<std::size_t>(f.idx())] = stamp_;
        Vec3 a, b, c;
        geometry::face_points(mesh, f, a, b, c);
        count += geometry::min_angle(a, b, c) < geometry::kMinAngle ? 1 : 0;
      }
    }
  }
  return count;
}

void LocalRegion::faces(const TriMesh& mesh, const std::vector<TriMesh::VertexHandle>& vertices,
                        std::vector<TriMesh::FaceHandle>& out) {
  if (face_mark_.size() < mesh.n_faces()) face_mark_.resize(mesh.n_faces(), 0);
  ++stamp_;
  out.clear();
  for (auto v : vertices) {
    if (mesh.status(v).deleted()) continue;
    for (auto f : mesh.vf_range(v))
      if (face_mark_[static_cast<std::size_t>(f.idx())] != stamp_) {
        face_mark_[static_cast<std::size_t>(f.idx())] = stamp_;
        out.push_back(f);
      }
  }
}

}  // namespace carbonmesh
