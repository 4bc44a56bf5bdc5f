#!/usr/bin/env bash
# Installs the build tree into a temporary prefix and builds and runs tests/consumer against it.
set -euo pipefail
build_dir=$1
source_dir=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build_dir" --prefix "$work/prefix" > "$work/install.log"
test -x "$work/prefix/bin/carbonmesh"
# The static libraries of a sanitizer build (make test-asan) call the ASan/UBSan runtimes: link them too.
extra=()
if grep -q '^CARBONMESH_SANITIZE:BOOL=ON' "$build_dir/CMakeCache.txt"; then
  extra=(-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined)
fi
# The consumer is built with the build's own compiler: the static libraries call its OpenMP runtime (GCC's
# libgomp, or LLVM's libomp for a clang build), which another compiler's -fopenmp does not link.
compiler=$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$build_dir/CMakeCache.txt")
if [ -n "$compiler" ]; then extra+=("-DCMAKE_CXX_COMPILER=$compiler"); fi
cmake -S "$source_dir/consumer" -B "$work/build" -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release \
  "${extra[@]}" > "$work/configure.log"
cmake --build "$work/build" -j 2 > "$work/build.log"
"$work/build/consumer"
"$work/prefix/bin/carbonmesh" --version
