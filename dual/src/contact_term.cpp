#include "contact_term.hpp"

#include "carbonmesh/remesh/cell_grid.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace carbonmesh::detail {

ContactTerm::ContactTerm(std::size_t atoms, const std::vector<std::array<int, 2>>& bonds, double cutoff,
                         double weight)
    : atoms_(atoms), cutoff_(cutoff), weight_(weight), skin_(0.25 * cutoff), first_(atoms + 1, 0) {
  for (const auto& b : bonds) ++first_[static_cast<std::size_t>(b[0]) + 1], ++first_[static_cast<std::size_t>(b[1]) + 1];
  for (std::size_t i = 0; i < atoms; ++i) first_[i + 1] += first_[i];
  neighbours_.resize(static_cast<std::size_t>(first_[atoms]));
  std::vector<int> fill(first_.begin(), first_.end() - 1);
  for (const auto& b : bonds) {
    neighbours_[static_cast<std::size_t>(fill[static_cast<std::size_t>(b[0])]++)] = b[1];
    neighbours_[static_cast<std::size_t>(fill[static_cast<std::size_t>(b[1])]++)] = b[0];
  }
}

bool ContactTerm::bonded(int i, int j) const {
  for (int k = first_[static_cast<std::size_t>(i)]; k < first_[static_cast<std::size_t>(i) + 1]; ++k)
    if (neighbours_[static_cast<std::size_t>(k)] == j) return true;
  return false;
}

// Every non-bonded pair closer than (r_c + skin) / s in y, from a CellGrid of at least that cell size (larger
// where the structure is sparse: at most about 4 cells per atom); pairs in atom order (deterministic).
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
  const CellGrid grid(points, ids, reach, 4.0 * static_cast<double>(atoms_) + 64);
  const auto& size = grid.size();
  const double reach2 = reach * reach;
  // Fixed chunks of atoms in parallel, each atom's partners sorted, the chunks joined in order: the list is in
  // (i, j) order for any thread count.
  constexpr std::size_t kChunk = 8192;
  const long chunks = static_cast<long>((atoms_ + kChunk - 1) / kChunk);
  std::vector<std::vector<std::array<int, 2>>> found(static_cast<std::size_t>(chunks));
#pragma omp parallel for schedule(dynamic, 1) if (atoms_ >= 2 * kChunk)
  for (long chunk = 0; chunk < chunks; ++chunk) {
    auto& out = found[static_cast<std::size_t>(chunk)];
    std::vector<int> partners;
    const std::size_t end = std::min(atoms_, static_cast<std::size_t>(chunk + 1) * kChunk);
    for (std::size_t i = static_cast<std::size_t>(chunk) * kChunk; i < end; ++i) {
      const Vec3& p = points[i];
      const int c[3] = {grid.coordinate(p, 0), grid.coordinate(p, 1), grid.coordinate(p, 2)};
      partners.clear();
      for (int x = std::max(c[0] - 1, 0); x <= std::min(c[0] + 1, size[0] - 1); ++x)
        for (int z1 = std::max(c[1] - 1, 0); z1 <= std::min(c[1] + 1, size[1] - 1); ++z1)
          for (int z2 = std::max(c[2] - 1, 0); z2 <= std::min(c[2] + 1, size[2] - 1); ++z2) {
            const std::size_t cell = grid.cell_index(x, z1, z2);
            for (int k = grid.begin(cell); k < grid.begin(cell + 1); ++k) {
              const int j = grid.id(k);
              if (j > static_cast<int>(i) && (p - grid.point(k)).sqrnorm() < reach2 &&
                  !bonded(static_cast<int>(i), j))
                partners.push_back(j);
            }
          }
      std::sort(partners.begin(), partners.end());
      for (int j : partners) out.push_back({static_cast<int>(i), j});
    }
  }
  std::size_t total = 0;
  for (const auto& f : found) total += f.size();
  pairs_.reserve(total);
  for (const auto& f : found) pairs_.insert(pairs_.end(), f.begin(), f.end());
}

double ContactTerm::add(const double* y, double s, double* gradient, double& gradient_scale) {
  if (weight_ <= 0 || atoms_ == 0) return 0;
  // A pair outside the list was at least (r_c + skin) apart: it comes within r_c only after its atoms moved
  // by skin between them (2 max |dy| s) or the scale shrank; rebuild before that can happen.
  bool stale = built_at_.size() != 3 * atoms_;
  if (!stale) {
    double moved2 = 0;
    for (std::size_t i = 0; i < atoms_; ++i) {
      const double a = y[3 * i] - built_at_[3 * i], b = y[3 * i + 1] - built_at_[3 * i + 1],
                   c = y[3 * i + 2] - built_at_[3 * i + 2];
      moved2 = std::max(moved2, a * a + b * b + c * c);
    }
    const double shrink = std::max(0.0, built_scale_ - s) / built_scale_ * (cutoff_ + skin_);
    stale = 2 * std::sqrt(moved2) * std::max(s, built_scale_) + shrink >= skin_;
  }
  if (stale) rebuild(y, s);
  double e = 0;
  for (const auto& [i, j] : pairs_) {
    const double* p = y + 3 * static_cast<std::size_t>(i);
    const double* q = y + 3 * static_cast<std::size_t>(j);
    const double r0 = p[0] - q[0], r1 = p[1] - q[1], r2 = p[2] - q[2];
    const double length = std::sqrt(r0 * r0 + r1 * r1 + r2 * r2);
    const double gap = cutoff_ - s * length;
    if (gap <= 0 || length == 0) continue;
    e += weight_ * gap * gap;
    const double de = -2 * weight_ * gap;  // dE/d(s length)
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
