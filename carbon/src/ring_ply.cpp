#include "carbonmesh/carbon/ring_ply.hpp"

#include <fmt/os.h>

#include "carbonmesh/remesh/atomic_file.hpp"

namespace carbonmesh {

std::array<unsigned char, 3> ring_colour(int ring_size) {
  switch (ring_size) {
    case 5: return {220, 40, 40};
    case 6: return {170, 170, 170};
    case 7: return {40, 80, 220};
    default: return {240, 200, 30};
  }
}

void write_ring_ply(const DualMesh& mesh, const std::filesystem::path& file) {
  write_atomically(file, [&](const std::filesystem::path& tmp) {
    auto out = fmt::output_file(tmp.string());
    out.print("ply\nformat ascii 1.0\n");
    out.print("comment carbonmesh dual mesh: atoms are vertices, rings are faces\n");
    out.print("comment face colour by ring size: 5 red, 6 grey, 7 blue, other yellow\n");
    out.print("element vertex {}\nproperty double x\nproperty double y\nproperty double z\n", mesh.n_vertices());
    out.print("element face {}\nproperty list uchar int vertex_indices\n", mesh.n_faces());
    out.print("property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n");
    for (auto v : mesh.vertices()) {
      const auto& p = mesh.point(v);
      out.print("{:.10g} {:.10g} {:.10g}\n", p[0], p[1], p[2]);
    }
    for (auto f : mesh.faces()) {
      const int n = static_cast<int>(mesh.valence(f));
      out.print("{}", n);
      for (auto v : mesh.fv_range(f)) out.print(" {}", v.idx());
      const auto c = ring_colour(n);
      out.print(" {} {} {}\n", c[0], c[1], c[2]);
    }
    out.close();
  });
}

}  // namespace carbonmesh
