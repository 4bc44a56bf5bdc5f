#pragma once
// f(i) for every element index i in [0, n), on every thread, each into its own slot: the caller then reduces the
// slots in index order, so its figures do not depend on the thread count. Internal.
#include <cstddef>
#include <vector>

namespace carbonmesh {

template <typename F>
auto per_element(std::size_t n, F&& f) {
  using R = decltype(f(0));
  std::vector<R> out(n);
  const int count = static_cast<int>(n);
#pragma omp parallel for schedule(static) if (count > 4096)  // small meshes on one thread
  for (int i = 0; i < count; ++i) out[static_cast<std::size_t>(i)] = f(i);
  return out;
}

}  // namespace carbonmesh
