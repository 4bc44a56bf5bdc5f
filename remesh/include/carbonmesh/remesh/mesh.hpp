#pragma once
// The triangle mesh type of carbonmesh: an OpenMesh half-edge mesh in double precision.
#include <OpenMesh/Core/IO/MeshIO.hh>  // must precede the kernel so its readers and writers see it
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

namespace carbonmesh {

struct MeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::Normal);
  EdgeAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::PrevHalfedge);
  FaceAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::Normal);
};

using TriMesh = OpenMesh::TriMesh_ArrayKernelT<MeshTraits>;
using Vec3 = OpenMesh::Vec3d;

}  // namespace carbonmesh
