#pragma once
// An OpenMesh importer that records the raw points and polygons a reader produces, without building any
// topology, so that carbonmesh validates the input itself (OpenMesh's own importer silently re-adds faces
// it refuses as detached triangles).
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>

#include "carbonmesh/remesh/io.hpp"

namespace carbonmesh::detail {

class SoupImporter : public OpenMesh::IO::BaseImporter {
 public:
  explicit SoupImporter(PolygonSoup& soup) : soup_(soup) {}

  using VertexHandle = OpenMesh::VertexHandle;
  using HalfedgeHandle = OpenMesh::HalfedgeHandle;
  using FaceHandle = OpenMesh::FaceHandle;
  using EdgeHandle = OpenMesh::EdgeHandle;

  VertexHandle add_vertex(const OpenMesh::Vec3f& p) override { return add_vertex(OpenMesh::Vec3d(p)); }
  VertexHandle add_vertex(const OpenMesh::Vec3d& p) override {
    soup_.points.emplace_back(p[0], p[1], p[2]);
    return VertexHandle(static_cast<int>(soup_.points.size()) - 1);
  }
  VertexHandle add_vertex() override { return add_vertex(OpenMesh::Vec3d(0, 0, 0)); }
  HalfedgeHandle add_edge(VertexHandle, VertexHandle) override { return HalfedgeHandle(); }
  FaceHandle add_face(const VHandles& indices) override {
    std::vector<int> polygon;
    polygon.reserve(indices.size());
    for (const auto& vh : indices) polygon.push_back(vh.idx());
    soup_.polygons.push_back(std::move(polygon));
    return FaceHandle(static_cast<int>(soup_.polygons.size()) - 1);
  }
  FaceHandle add_face(HalfedgeHandle) override { return FaceHandle(); }
  void set_point(VertexHandle vh, const OpenMesh::Vec3f& p) override { set_point_d(vh, OpenMesh::Vec3d(p)); }
  void set_point_d(VertexHandle vh, const OpenMesh::Vec3d& p) {
    if (vh.idx() >= 0 && static_cast<std::size_t>(vh.idx()) < soup_.points.size())
      soup_.points[static_cast<std::size_t>(vh.idx())] = Vec3(p[0], p[1], p[2]);
  }

  // Attributes carbonmesh does not use.
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec2f>&) override {}
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec3f>&) override {}
  void set_face_texindex(FaceHandle, int) override {}
  void set_halfedge(VertexHandle, HalfedgeHandle) override {}
  void set_normal(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_normal(VertexHandle, const OpenMesh::Vec3d&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec4f&) override {}
  void set_texcoord(VertexHandle, const OpenMesh::Vec2f&) override {}
  void set_status(VertexHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_next(HalfedgeHandle, HalfedgeHandle) override {}
  void set_face(HalfedgeHandle, FaceHandle) override {}
  void request_face_texcoords2D() override {}
  void set_texcoord(HalfedgeHandle, const OpenMesh::Vec2f&) override {}
  void set_texcoord(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_texcoord(HalfedgeHandle, const OpenMesh::Vec3f&) override {}
  void set_status(HalfedgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec3f&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec4f&) override {}
  void set_status(EdgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3f&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3d&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec3f&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec4f&) override {}
  void set_status(FaceHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void add_texture_information(int, std::string) override {}

  bool is_triangle_mesh() const override { return false; }
  size_t n_vertices() const override { return soup_.points.size(); }
  size_t n_faces() const override { return soup_.polygons.size(); }
  size_t n_edges() const override { return 0; }

 private:
  PolygonSoup& soup_;
};

}  // namespace carbonmesh::detail
