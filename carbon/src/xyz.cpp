#include "carbonmesh/carbon/xyz.hpp"

#include <fmt/os.h>

#include "carbonmesh/remesh/atomic_file.hpp"

namespace carbonmesh {

void write_extended_xyz(const CarbonStructure& s, const std::filesystem::path& file, double vacuum) {
  const Box box = vacuum_box(s.positions, vacuum);
  const Vec3 size = box.hi - box.lo;
  write_atomically(file, [&](const std::filesystem::path& tmp) {
    auto out = fmt::output_file(tmp.string());
    out.print("{}\n", s.atoms());
    out.print("Lattice=\"{:.8f} 0 0 0 {:.8f} 0 0 0 {:.8f}\" Origin=\"{:.8f} {:.8f} {:.8f}\" "
              "Properties=species:S:1:pos:R:3 pbc=\"F F F\" comment=\"carbonmesh: {} bonds\"\n",
              size[0], size[1], size[2], box.lo[0], box.lo[1], box.lo[2], s.bonds.size());
    for (std::size_t i = 0; i < s.atoms(); ++i) {
      const Vec3& p = s.positions[i];
      out.print("{} {:.8f} {:.8f} {:.8f}\n", element_symbol(s.elements[i]), p[0], p[1], p[2]);
    }
    out.close();
  });
}

}  // namespace carbonmesh
