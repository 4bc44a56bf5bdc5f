#pragma once
// The OpenMP team size and thread number, 1 and 0 without OpenMP. Internal.
#ifdef _OPENMP
#include <omp.h>
#endif

namespace carbonmesh {

inline int max_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

inline int thread_index() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

}  // namespace carbonmesh
