#include "carbonmesh/carbon/pdb.hpp"

#include <fmt/format.h>
#include <fmt/os.h>

#include <cmath>
#include <stdexcept>

#include "carbonmesh/remesh/atomic_file.hpp"

namespace carbonmesh {

std::string hybrid36_serial(long value) {
  constexpr long width_limit = 100000;  // 10^5
  constexpr long block = 26L * 36 * 36 * 36 * 36;
  if (value < 0) throw std::runtime_error("PDB serial must not be negative");
  if (value < width_limit) return fmt::format("{:5d}", value);
  long n = value - width_limit;
  const char* digits = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ";
  if (n >= block) {
    n -= block;
    if (n >= block) throw std::runtime_error("too many atoms for PDB serial numbers");
    digits = "0123456789abcdefghijklmnopqrstuvwxyz";
  }
  n += 10L * 36 * 36 * 36 * 36;  // the first letter: 'A' (or 'a')
  std::string s(5, '0');
  for (int k = 4; k >= 0; --k) {
    s[static_cast<std::size_t>(k)] = digits[n % 36];
    n /= 36;
  }
  return s;
}

void write_pdb(const CarbonStructure& s, const std::filesystem::path& file) {
  for (const auto& p : s.positions)
    for (int k = 0; k < 3; ++k)
      if (!(std::abs(p[k]) < 9999.0)) throw std::runtime_error("PDB: a coordinate does not fit 8.3f columns");
  std::vector<std::vector<int>> neighbours(s.atoms());
  for (const auto& b : s.bonds) {
    neighbours[static_cast<std::size_t>(b[0])].push_back(b[1]);
    neighbours[static_cast<std::size_t>(b[1])].push_back(b[0]);
  }
  write_atomically(file, [&](const std::filesystem::path& tmp) {
    auto out = fmt::output_file(tmp.string());
    out.print("REMARK   1 carbonmesh: {} atoms ({} C, {} H), {} bonds\n", s.atoms(), s.count(Element::C),
              s.count(Element::H), s.bonds.size());
    for (std::size_t i = 0; i < s.atoms(); ++i) {
      const Vec3& p = s.positions[i];
      const char* el = element_symbol(s.elements[i]);
      out.print("HETATM{:>5} {:<4} CNM A   1    {:8.3f}{:8.3f}{:8.3f}  1.00  0.00          {:>2}\n",
                hybrid36_serial(static_cast<long>(i + 1)), fmt::format(" {}", el), p[0], p[1], p[2], el);
    }
    for (std::size_t i = 0; i < s.atoms(); ++i) {
      const auto& nb = neighbours[i];
      for (std::size_t k = 0; k < nb.size(); k += 4) {
        out.print("CONECT{}", hybrid36_serial(static_cast<long>(i + 1)));
        for (std::size_t j = k; j < std::min(nb.size(), k + 4); ++j)
          out.print("{}", hybrid36_serial(static_cast<long>(nb[j] + 1)));
        out.print("\n");
      }
    }
    out.print("END\n");
    out.close();
  });
}

}  // namespace carbonmesh
