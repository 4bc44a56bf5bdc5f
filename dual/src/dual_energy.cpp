#include "dual_energy.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <tuple>

namespace carbonmesh::detail {

DualEnergy::DualEnergy(const std::vector<AtomPair>& bonds, const std::vector<AtomTriple>& angles,
                       const std::vector<double>& target_cosines, const SurfaceProjector& projector, double radius,
                       std::vector<int> faces, const DualOptimizeSettings& s)
    : projector_(projector), radius_(radius), faces_(std::move(faces)), s_(s),
      slots_(bond_adjacency(faces_.size(), bonds)),
      contacts_(slots_, std::numbers::sqrt2 * s.bond, s.contact_weight), target_cosines_(target_cosines) {
  const std::size_t n = faces_.size();
  for (std::size_t i = 0; i < n; ++i)
    if (slots_.first[i + 1] - slots_.first[i] > kMaxBonds)
      throw std::invalid_argument("optimize_dual: an atom has more than " + std::to_string(kMaxBonds) + " bonds");
  // Angles by centre (the caller sorts them so), each as its two neighbour slots of the centre.
  first_angle_.assign(n + 1, 0);
  for (const auto& t : angles) ++first_angle_[static_cast<std::size_t>(t[1]) + 1];
  for (std::size_t i = 0; i < n; ++i) first_angle_[i + 1] += first_angle_[i];
  auto slot_of = [&](int centre, int atom) {
    const auto c = static_cast<std::size_t>(centre);
    for (std::uint32_t k = slots_.first[c]; k < slots_.first[c + 1]; ++k)
      if (slots_.atom[k] == static_cast<std::uint32_t>(atom)) return k;
    throw std::invalid_argument("optimize_dual: an angle's arm is not a bond");
  };
  angle_slots_.resize(angles.size());
  for (std::size_t a = 0; a < angles.size(); ++a) {
    const AtomTriple& t = angles[a];
    if (a > 0 && angles[a - 1][1] > t[1]) throw std::invalid_argument("optimize_dual: angles not sorted by centre");
    angle_slots_[a] = {slot_of(t[1], t[0]), slot_of(t[1], t[2])};
  }
  // The pair at an angle's ends gets the contact term from the first angle it ends (in a 4-ring two angles
  // share it), and none if it is bonded (a 3-ring).
  angle_contact_.assign(angles.size(), 0);
  std::vector<std::tuple<int, int, std::size_t>> ends(angles.size());
  for (std::size_t a = 0; a < angles.size(); ++a) ends[a] = {angles[a][0], angles[a][2], a};
  std::sort(ends.begin(), ends.end());
  for (std::size_t k = 0; k < ends.size(); ++k) {
    const auto [i, j, a] = ends[k];
    const bool repeat = k > 0 && std::get<0>(ends[k - 1]) == i && std::get<1>(ends[k - 1]) == j;
    angle_contact_[a] = !repeat && !slots_.bonded(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j));
  }
  // The slots that name each atom, by centre ascending.
  first_gather_.assign(n + 1, 0);
  for (std::uint32_t a : slots_.atom) ++first_gather_[a + 1];
  for (std::size_t i = 0; i < n; ++i) first_gather_[i + 1] += first_gather_[i];
  gather_.resize(slots_.atom.size());
  std::vector<std::uint32_t> at(first_gather_.begin(), first_gather_.end() - 1);
  for (std::size_t c = 0; c < n; ++c)
    for (std::uint32_t k = slots_.first[c]; k < slots_.first[c + 1]; ++k) gather_[at[slots_.atom[k]]++] = k;
  slot_gradient_.assign(3 * slots_.atom.size(), 0.0);
}

double DualEnergy::operator()(const Eigen::VectorXd& x, Eigen::VectorXd& g) {
  const std::size_t n = faces_.size();
  g.resize(x.size());
  const double* px = x.data();
  double* pg = g.data();
  const double b = s_.bond;
  const double s = scale(x);
  const double window = s_.bond_window, window_weight = s_.bond_window_weight;
  const double wa = s_.angle_weight * b * b;
  const double ws = s_.surface_weight * s * s;
  const double wc = s_.contact_weight, rc = std::numbers::sqrt2 * b;
  constexpr std::size_t kChunk = 4096;
  const long chunks = static_cast<long>((n + kChunk - 1) / kChunk);
  partial_sums_.assign(static_cast<std::size_t>(chunks), {0.0, 0.0, 0.0});
  double* slots = slot_gradient_.data();
  // Parallel only for large structures: on a loaded machine a parallel region costs more than a small loop.
#pragma omp parallel if (parallel())
  {
#pragma omp for schedule(static)
    for (long chunk = 0; chunk < chunks; ++chunk) {
      // Energy of the bonds, angles and contacts, its dE/ds, the squared surface distances.
      double ce = 0, cg = 0, cd = 0;
      const std::size_t end = std::min(n, static_cast<std::size_t>(chunk + 1) * kChunk);
      for (std::size_t c = static_cast<std::size_t>(chunk) * kChunk; c < end; ++c) {
        const std::uint32_t first = slots_.first[c], degree = slots_.first[c + 1] - first;
        const Eigen::Map<const Eigen::Vector3d> xc(px + 3 * c);
        std::array<Eigen::Vector3d, kMaxBonds> arm, push;  // x_j - x_c, and the gradient on neighbour j
        std::array<double, kMaxBonds> arm2;
        Eigen::Vector3d gc = Eigen::Vector3d::Zero();
        for (std::uint32_t k = 0; k < degree; ++k) {
          const std::uint32_t j = slots_.atom[first + k];
          arm[k] = Eigen::Map<const Eigen::Vector3d>(px + 3 * j) - xc;
          arm2[k] = arm[k].squaredNorm();
          push[k].setZero();
          const double length = std::sqrt(arm2[k]);
          if (length == 0) continue;
          // (diff)^2 plus the window hinge w_h (|diff| - delta)^2 outside b +- delta: dE/d(diff) = de.
          const double diff = s * length - b;
          double de = 2 * diff, energy = diff * diff;
          const double over = std::abs(diff) - window;
          if (over > 0) {
            energy += window_weight * over * over;
            de += 2 * window_weight * over * (diff > 0 ? 1 : -1);
          }
          if (c < j) ce += energy, cg += de * length;
          gc -= (de * s / length) * arm[k];
        }
        for (std::uint32_t a = first_angle_[c]; a < first_angle_[c + 1]; ++a) {
          const std::uint32_t ku = angle_slots_[a][0] - first, kv = angle_slots_[a][1] - first;
          const Eigen::Vector3d& u = arm[ku];
          const Eigen::Vector3d& v = arm[kv];
          const double lu2 = arm2[ku], lv2 = arm2[kv];
          if (wa > 0 && lu2 > 0 && lv2 > 0) {
            const double inv = 1.0 / std::sqrt(lu2 * lv2);
            const double cosine = u.dot(v) * inv;
            const double diff = cosine - target_cosines_[a];
            ce += wa * diff * diff;
            const double de = 2 * wa * diff;
            const Eigen::Vector3d du = de * (v * inv - (cosine / lu2) * u);
            const Eigen::Vector3d dv = de * (u * inv - (cosine / lv2) * v);
            push[ku] += du;
            push[kv] += dv;
            gc -= du + dv;
          }
          if (wc > 0 && angle_contact_[a]) {  // the pair at the ends, two bonds apart
            const Eigen::Vector3d w = u - v;
            const double length = w.norm();
            if (length == 0) continue;
            const double de = contact_derivative(rc, wc, s * length, ce);  // dE/d(s length)
            if (de == 0) continue;
            cg += de * length;
            const Eigen::Vector3d f = (de * s / length) * w;
            push[ku] += f;
            push[kv] -= f;
          }
        }
        for (std::uint32_t k = 0; k < degree; ++k) Eigen::Map<Eigen::Vector3d>(slots + 3 * (first + k)) = push[k];
        if (ws > 0) {
          const Vec3 p(xc[0], xc[1], xc[2]);
          const Vec3 d = p - projector_.closest_point_near(p, faces_[c]);
          cd += d.sqrnorm();
          for (int i = 0; i < 3; ++i) gc[i] += 2 * ws * d[i];
        }
        Eigen::Map<Eigen::Vector3d>(pg + 3 * c) = gc;
      }
      partial_sums_[static_cast<std::size_t>(chunk)] = {ce, cg, cd};
    }
#pragma omp for schedule(static)
    for (long i = 0; i < static_cast<long>(n); ++i) {
      Eigen::Map<Eigen::Vector3d> gi(pg + 3 * i);
      const auto atom = static_cast<std::size_t>(i);
      for (std::uint32_t k = first_gather_[atom]; k < first_gather_[atom + 1]; ++k)
        gi += Eigen::Map<const Eigen::Vector3d>(slots + 3 * gather_[k]);
    }
  }
  double e = 0, gs = 0, d2 = 0;  // gs = dE/ds
  for (const auto& [pe, pgs, pd] : partial_sums_) e += pe, gs += pgs, d2 += pd;
  e += ws * d2;
  gs += 2 * s_.surface_weight * s * d2;
  e += contacts_.add(px, s, pg, gs);
  if (s_.free_scale) pg[x.size() - 1] = gs / radius_;
  return e;
}

}  // namespace carbonmesh::detail
