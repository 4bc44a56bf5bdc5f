// add_faces(): OpenMesh's PolyConnectivity::add_face() for triangles, step for step, on plain arrays.
#include "add_faces.hpp"

#include <cstddef>
#include <utility>

namespace carbonmesh {
namespace {

// The connectivity of the mesh being built: halfedge 2e and 2e + 1 are edge e's, as in OpenMesh; -1 is no handle.
class Connectivity {
 public:
  Connectivity(std::size_t vertices, std::size_t faces) : outgoing_(vertices, -1) {
    for (auto* a : {&to_, &next_, &prev_, &face_}) a->reserve(3 * faces + 6);  // (a closed surface's halfedges, 3F)
    face_halfedge_.reserve(faces);
  }

  // PolyConnectivity::add_face(v, 3).
  bool add_face(const std::array<int, 3>& v) {
    struct EdgeData {
      int halfedge;
      bool is_new, needs_adjust;
    } edge[3];
    std::pair<int, int> next_cache[18];
    int cached = 0;
    for (int i = 0, ii = 1; i < 3; ++i, ++ii, ii %= 3) {
      if (!is_boundary_vertex(v[i])) return false;  // complex vertex
      edge[i].halfedge = find_halfedge(v[i], v[ii]);
      edge[i].is_new = edge[i].halfedge < 0;
      edge[i].needs_adjust = false;
      if (!edge[i].is_new && face_[h(edge[i].halfedge)] >= 0) return false;  // complex edge
    }
    // Re-link patches if necessary.
    for (int i = 0, ii = 1; i < 3; ++i, ++ii, ii %= 3) {
      if (edge[i].is_new || edge[ii].is_new) continue;
      const int inner_prev = edge[i].halfedge, inner_next = edge[ii].halfedge;
      if (next_[h(inner_prev)] == inner_next) continue;
      // A free gap between boundary_prev and boundary_next.
      int boundary_prev = inner_next ^ 1;
      do {
        const int n = next_[h(boundary_prev)];
        if (n < 0) return false;  // (OpenMesh reads past its arrays here: no valid mesh gets here)
        boundary_prev = n ^ 1;
      } while (face_[h(boundary_prev)] >= 0);
      const int boundary_next = next_[h(boundary_prev)];
      if (boundary_prev == inner_prev) return false;  // patch re-linking failed
      const int patch_start = next_[h(inner_prev)], patch_end = prev_[h(inner_next)];
      next_cache[cached++] = {boundary_prev, patch_start};
      next_cache[cached++] = {patch_end, boundary_next};
      next_cache[cached++] = {inner_prev, inner_next};
    }
    // Missing edges.
    for (int i = 0, ii = 1; i < 3; ++i, ++ii, ii %= 3)
      if (edge[i].is_new) edge[i].halfedge = new_edge(v[i], v[ii]);
    // The face.
    const int f = static_cast<int>(face_halfedge_.size());
    face_halfedge_.push_back(edge[2].halfedge);
    // Halfedges.
    for (int i = 0, ii = 1; i < 3; ++i, ++ii, ii %= 3) {
      const int vh = v[ii];
      const int inner_prev = edge[i].halfedge, inner_next = edge[ii].halfedge;
      const int id = (edge[i].is_new ? 1 : 0) | (edge[ii].is_new ? 2 : 0);
      if (id != 0) {
        const int outer_prev = inner_next ^ 1, outer_next = inner_prev ^ 1;
        int& out = outgoing_[static_cast<std::size_t>(vh)];
        switch (id) {
          case 1:  // prev is new, next is old
            next_cache[cached++] = {prev_[h(inner_next)], outer_next};
            out = outer_next;
            break;
          case 2: {  // next is new, prev is old
            const int boundary_next = next_[h(inner_prev)];
            next_cache[cached++] = {outer_prev, boundary_next};
            out = boundary_next;
            break;
          }
          default:  // both are new
            if (out < 0) {
              out = outer_next;
              next_cache[cached++] = {outer_prev, outer_next};
            } else {
              const int boundary_next = out, boundary_prev = prev_[h(boundary_next)];
              next_cache[cached++] = {boundary_prev, outer_next};
              next_cache[cached++] = {outer_prev, boundary_next};
            }
            break;
        }
        next_cache[cached++] = {inner_prev, inner_next};  // the inner link
      } else {
        edge[ii].needs_adjust = outgoing_[static_cast<std::size_t>(vh)] == inner_next;
      }
      face_[h(edge[i].halfedge)] = f;
    }
    for (int i = 0; i < cached; ++i) set_next(next_cache[i].first, next_cache[i].second);
    for (int i = 0; i < 3; ++i)
      if (edge[i].needs_adjust) adjust_outgoing_halfedge(v[i]);
    return true;
  }

  // Sizes the mesh's arrays once and writes the connectivity into them.
  void write(TriMesh& mesh) const {
    const std::size_t halfedges = to_.size();
    mesh.resize(mesh.n_vertices(), halfedges / 2, face_halfedge_.size());
    for (std::size_t i = 0; i < halfedges; ++i) {
      const TriMesh::HalfedgeHandle hh(static_cast<int>(i));
      mesh.set_vertex_handle(hh, TriMesh::VertexHandle(to_[i]));
      if (face_[i] >= 0) mesh.set_face_handle(hh, TriMesh::FaceHandle(face_[i]));
      if (next_[i] >= 0) mesh.set_next_halfedge_handle(hh, TriMesh::HalfedgeHandle(next_[i]));
    }
    // (set_next_halfedge_handle also set the previous links; OpenMesh's are those of the last link set to each.)
    for (std::size_t i = 0; i < halfedges; ++i)
      if (prev_[i] >= 0) mesh.set_prev_halfedge_handle(TriMesh::HalfedgeHandle(static_cast<int>(i)),
                                                       TriMesh::HalfedgeHandle(prev_[i]));
    for (std::size_t i = 0; i < outgoing_.size(); ++i)
      if (outgoing_[i] >= 0)
        mesh.set_halfedge_handle(TriMesh::VertexHandle(static_cast<int>(i)), TriMesh::HalfedgeHandle(outgoing_[i]));
    for (std::size_t i = 0; i < face_halfedge_.size(); ++i)
      mesh.set_halfedge_handle(TriMesh::FaceHandle(static_cast<int>(i)), TriMesh::HalfedgeHandle(face_halfedge_[i]));
  }

 private:
  static std::size_t h(int halfedge) { return static_cast<std::size_t>(halfedge); }

  // ArrayKernel::new_edge(start, end): its first halfedge, start -> end.
  int new_edge(int start, int end) {
    const int first = static_cast<int>(to_.size());
    to_.push_back(end);
    to_.push_back(start);
    for (auto* a : {&next_, &prev_, &face_}) a->insert(a->end(), 2, -1);
    return first;
  }

  void set_next(int halfedge, int next) {
    next_[h(halfedge)] = next;
    prev_[h(next)] = halfedge;
  }

  // PolyConnectivity::is_boundary(VertexHandle): no outgoing halfedge, or one without a face.
  bool is_boundary_vertex(int v) const {
    const int out = outgoing_[static_cast<std::size_t>(v)];
    return out < 0 || face_[h(out)] < 0;
  }

  // The outgoing halfedges of v clockwise from its own (OpenMesh's VertexOHalfedgeIter): calls visit(halfedge)
  // until it returns true; returns that halfedge, or -1.
  template <typename Visit>
  int circulate(int v, Visit visit) const {
    const int start = outgoing_[static_cast<std::size_t>(v)];
    int lap = 0;
    for (int halfedge = start; halfedge >= 0 && (halfedge != start || lap == 0);) {
      if (visit(halfedge)) return halfedge;
      halfedge = next_[h(halfedge ^ 1)];  // cw_rotated_halfedge_handle
      if (halfedge == start) ++lap;
    }
    return -1;
  }

  // PolyConnectivity::find_halfedge(start, end).
  int find_halfedge(int start, int end) const {
    return circulate(start, [&](int halfedge) { return to_[h(halfedge)] == end; });
  }

  // PolyConnectivity::adjust_outgoing_halfedge(v): the first boundary halfedge around v becomes its own.
  void adjust_outgoing_halfedge(int v) {
    const int boundary = circulate(v, [&](int halfedge) { return face_[h(halfedge)] < 0; });
    if (boundary >= 0) outgoing_[static_cast<std::size_t>(v)] = boundary;
  }

  std::vector<int> outgoing_;                 // per vertex
  std::vector<int> to_, next_, prev_, face_;  // per halfedge
  std::vector<int> face_halfedge_;            // per face
};

}  // namespace

bool add_faces(TriMesh& mesh, const std::vector<std::array<int, 3>>& faces) {
  Connectivity c(mesh.n_vertices(), faces.size());
  for (const auto& f : faces)
    if (!c.add_face(f)) return false;
  c.write(mesh);
  return true;
}

std::vector<std::array<int, 3>> face_corners(const TriMesh& mesh, bool reversed) {
  std::vector<std::array<int, 3>> out;
  out.reserve(mesh.n_faces());
  for (auto f : mesh.faces()) {
    std::array<int, 3> t{};
    std::size_t i = 0;
    for (auto v : mesh.fv_range(f)) t[i++] = v.idx();
    if (reversed) std::swap(t[1], t[2]);
    out.push_back(t);
  }
  return out;
}

}  // namespace carbonmesh
