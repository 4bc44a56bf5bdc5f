#pragma once
// Whether two Eigen results hold the same doubles bit for bit (same shape, memcmp): the solver tests that compare a
// replica of Eigen's arithmetic with Eigen's own.
#include <cstddef>
#include <cstring>

#include <Eigen/Core>

namespace carbonmesh::testing {

template <typename A, typename B>
bool same_bits(const Eigen::DenseBase<A>& a, const Eigen::DenseBase<B>& b) {
  const typename A::PlainObject x = a;
  const typename B::PlainObject y = b;
  return x.rows() == y.rows() && x.cols() == y.cols() &&
         std::memcmp(x.data(), y.data(), sizeof(double) * static_cast<std::size_t>(x.size())) == 0;
}

}  // namespace carbonmesh::testing
