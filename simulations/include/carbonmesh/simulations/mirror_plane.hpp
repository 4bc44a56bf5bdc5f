#pragma once
// Mirror planes: parsing --plane, finding the best mirror plane of a shape (PCA candidates refined by
// minimising the Hausdorff distance between the shape and its mirror image) and counting rings on each side.
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "carbonmesh/remesh/hausdorff.hpp"
#include "carbonmesh/remesh/mesh.hpp"
#include "carbonmesh/simulations/ring_structure.hpp"

namespace carbonmesh {

struct Plane {
  Vec3 normal{1, 0, 0};  // unit
  double offset = 0;     // points x with normal . x = offset
  double signed_distance(const Vec3& p) const { return OpenMesh::dot(normal, p) - offset; }
};

// "x", "y", "z" (through `center`) or "nx,ny,nz,d" (normal . x = d; the normal is normalised).
// Throws InputError for anything else or a zero normal.
Plane parse_plane(const std::string& text, const Vec3& center);

// The mirror image of a mesh in a plane (faces reversed so it stays outward-oriented).
TriMesh mirror_mesh(const TriMesh& mesh, const Plane& plane);

struct MirrorSettings {
  std::size_t search_samples = 1500;    // surface samples while refining (reflected, against one AABB tree)
  std::size_t final_samples = 100000;   // Hausdorff samples a side for the reported residual (hausdorff_distance)
  int evaluations_per_candidate = 100;  // pattern-search budget per PCA candidate
};

struct MirrorCandidate {
  Plane start, refined;
  double start_distance = 0, refined_distance = 0;  // search objective: max over samples p of d(mirror(p), shape)
  int evaluations = 0;
};

struct MirrorResult {
  Plane plane;
  HausdorffResult residual;  // shape vs its mirror image in `plane`
  double diagonal = 0;       // bounding-box diagonal, for scale
  std::vector<MirrorCandidate> candidates;  // the three PCA axes, best first
};

MirrorResult find_mirror_plane(const TriMesh& shape, const MirrorSettings& settings = {});

// Residual of a given plane.
HausdorffResult mirror_residual(const TriMesh& shape, const Plane& plane, std::size_t samples);

// A triangle mesh of a ring structure's surface for the mirror search: the mesh itself for mesh input,
// otherwise each closed ring fanned from its centre (faces OpenMesh refuses are skipped).
TriMesh surface_of(const RingStructure& rs);

struct SideCounts {
  std::map<int, std::size_t> positive, negative, on_plane;  // ring size -> irregular (closed, != 6) rings
  std::size_t positive_total = 0, negative_total = 0, on_plane_total = 0;
};
// Irregular rings by the side of `plane` their centre lies on (|distance| <= tolerance: on the plane).
SideCounts count_sides(const RingStructure& rs, const Plane& plane, double tolerance);

}  // namespace carbonmesh
