#include "contact_term.hpp"

#include "carbonmesh/remesh/cell_grid.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace carbonmesh::detail {

constexpr std::size_t kChunk = 8192;  // atoms per parallel chunk

BondAdjacency bond_adjacency(std::size_t atoms, const std::vector<std::array<int, 2>>& bonds) {
  BondAdjacency a;
  a.first.assign(atoms + 1, 0);
  for (const auto& b : bonds)
    ++a.first[static_cast<std::size_t>(b[0]) + 1], ++a.first[static_cast<std::size_t>(b[1]) + 1];
  for (std::size_t i = 0; i < atoms; ++i) a.first[i + 1] += a.first[i];
  a.atom.resize(a.first[atoms]);
  std::vector<std::uint32_t> fill(a.first.begin(), a.first.end() - 1);
  for (const auto& b : bonds) {
    a.atom[fill[static_cast<std::size_t>(b[0])]++] = static_cast<std::uint32_t>(b[1]);
    a.atom[fill[static_cast<std::size_t>(b[1])]++] = static_cast<std::uint32_t>(b[0]);
  }
  for (std::size_t i = 0; i < atoms; ++i) std::sort(a.atom.begin() + a.first[i], a.atom.begin() + a.first[i + 1]);
  return a;
}

bool BondAdjacency::bonded(std::uint32_t i, std::uint32_t j) const {
  return std::binary_search(atom.begin() + first[i], atom.begin() + first[i + 1], j);
}

ContactTerm::ContactTerm(const BondAdjacency& bonds, double cutoff, double weight)
    : atoms_(bonds.atoms()), cutoff_(cutoff), weight_(weight), skin_(0.25 * cutoff), bonds_(bonds) {}

bool ContactTerm::within_two_bonds(int i, int j) const {
  const auto a = static_cast<std::uint32_t>(i), b = static_cast<std::uint32_t>(j);
  if (bonds_.bonded(a, b)) return true;
  for (std::uint32_t k = bonds_.first[a]; k < bonds_.first[a + 1]; ++k)
    if (bonds_.bonded(bonds_.atom[k], b)) return true;
  return false;
}

// Every pair more than two bonds apart closer than (r_c + skin) / s in y, from a CellGrid of at least that cell size;
// pairs in atom order (deterministic).
void ContactTerm::rebuild(const double* y, double s) {
  ++rebuilds_;
  built_at_.assign(y, y + 3 * atoms_);
  built_scale_ = s;
  pairs_.clear();
  if (atoms_ == 0) return;
  const double reach = (cutoff_ + skin_) / s;
  std::vector<Vec3> points(atoms_);
  std::vector<int> ids(atoms_);
  for (std::size_t i = 0; i < atoms_; ++i) points[i] = Vec3(y[3 * i], y[3 * i + 1], y[3 * i + 2]);
  std::iota(ids.begin(), ids.end(), 0);
  // At most 4 cells per atom (fertility's cells are then twice the reach; 16 per atom made them 1.25 times the
  // reach, but a rebuild took twice as long: the grid no longer fits the cache).
  const CellGrid grid(points, ids, reach, 4.0 * static_cast<double>(atoms_) + 64);
  const auto& size = grid.size();
  const double reach2 = reach * reach;
  // Each pair once: atom i looks at the later atoms of its own cell and at every atom of the 13 cells of the
  // half shell after it. Fixed chunks of atoms in parallel; the pairs are sorted at the end (the list is in
  // (i, j) order for any thread count).
  const long chunks = static_cast<long>((atoms_ + kChunk - 1) / kChunk);
  std::vector<std::vector<std::array<int, 2>>> found(static_cast<std::size_t>(chunks));
  auto visit = [&](std::size_t i, const Vec3& p, std::size_t cell, bool own, std::vector<std::array<int, 2>>& out) {
    for (int k = grid.begin(cell); k < grid.begin(cell + 1); ++k) {
      const int j = grid.id(k);
      if (own && j <= static_cast<int>(i)) continue;
      if ((p - grid.point(k)).sqrnorm() < reach2 && !within_two_bonds(static_cast<int>(i), j))
        out.push_back({std::min(static_cast<int>(i), j), std::max(static_cast<int>(i), j)});
    }
  };
#pragma omp parallel for schedule(dynamic, 1) if (atoms_ >= 2 * kChunk)
  for (long chunk = 0; chunk < chunks; ++chunk) {
    auto& out = found[static_cast<std::size_t>(chunk)];
    const std::size_t end = std::min(atoms_, static_cast<std::size_t>(chunk + 1) * kChunk);
    for (std::size_t i = static_cast<std::size_t>(chunk) * kChunk; i < end; ++i) {
      const Vec3& p = points[i];
      const int c[3] = {grid.coordinate(p, 0), grid.coordinate(p, 1), grid.coordinate(p, 2)};
      visit(i, p, grid.cell_index(c[0], c[1], c[2]), true, out);
      for (int dx = 0; dx <= 1; ++dx)
        for (int dy = dx == 0 ? 0 : -1; dy <= 1; ++dy)
          for (int dz = dx == 0 && dy == 0 ? 1 : -1; dz <= 1; ++dz) {
            const int x = c[0] + dx, y1 = c[1] + dy, z = c[2] + dz;
            if (x >= size[0] || y1 < 0 || y1 >= size[1] || z < 0 || z >= size[2]) continue;
            visit(i, p, grid.cell_index(x, y1, z), false, out);
          }
    }
  }
  std::size_t total = 0;
  for (const auto& f : found) total += f.size();
  pairs_.reserve(total);
  for (const auto& f : found) pairs_.insert(pairs_.end(), f.begin(), f.end());
  std::sort(pairs_.begin(), pairs_.end());
}

double ContactTerm::add(const double* y, double s, double* gradient, double& gradient_scale) {
  if (weight_ <= 0 || atoms_ == 0) return 0;
  // A pair outside the list was at least (r_c + skin) apart: it comes within r_c only after its two atoms moved
  // by skin between them (at most the two largest moves since the rebuild, times s) or the scale shrank; rebuild
  // before that can happen.
  bool stale = built_at_.size() != 3 * atoms_;
  if (!stale) {
    const long chunks = static_cast<long>((atoms_ + kChunk - 1) / kChunk);
    std::vector<std::array<double, 2>> top(static_cast<std::size_t>(chunks), {0.0, 0.0});  // squared, largest first
#pragma omp parallel for schedule(static) if (atoms_ >= 2 * kChunk)
    for (long chunk = 0; chunk < chunks; ++chunk) {
      auto& t = top[static_cast<std::size_t>(chunk)];
      const std::size_t end = std::min(atoms_, static_cast<std::size_t>(chunk + 1) * kChunk);
      for (std::size_t i = static_cast<std::size_t>(chunk) * kChunk; i < end; ++i) {
        const double a = y[3 * i] - built_at_[3 * i], b = y[3 * i + 1] - built_at_[3 * i + 1],
                     c = y[3 * i + 2] - built_at_[3 * i + 2];
        const double d2 = a * a + b * b + c * c;
        if (d2 > t[1]) t[1] = std::min(d2, t[0]), t[0] = std::max(d2, t[0]);
      }
    }
    double first = 0, second = 0;
    for (const auto& t : top)
      for (double d2 : t)
        if (d2 > second) second = std::min(d2, first), first = std::max(d2, first);
    const double shrink = std::max(0.0, built_scale_ - s) / built_scale_ * (cutoff_ + skin_);
    stale = (std::sqrt(first) + std::sqrt(second)) * std::max(s, built_scale_) + shrink >= skin_;
  }
  if (stale) rebuild(y, s);
  double e = 0;
  for (const auto& [i, j] : pairs_) {
    const double* p = y + 3 * static_cast<std::size_t>(i);
    const double* q = y + 3 * static_cast<std::size_t>(j);
    const double r0 = p[0] - q[0], r1 = p[1] - q[1], r2 = p[2] - q[2];
    const double length = std::sqrt(r0 * r0 + r1 * r1 + r2 * r2);
    if (length == 0) continue;
    const double de = contact_derivative(cutoff_, weight_, s * length, e);  // dE/d(s length)
    if (de == 0) continue;
    gradient_scale += de * length;
    const double k = de * s / length;
    double* gp = gradient + 3 * static_cast<std::size_t>(i);
    double* gq = gradient + 3 * static_cast<std::size_t>(j);
    gp[0] += k * r0, gp[1] += k * r1, gp[2] += k * r2;
    gq[0] -= k * r0, gq[1] -= k * r1, gq[2] -= k * r2;
  }
  return e;
}

}  // namespace carbonmesh::detail
