// libFuzzer target: the mesh loader (every format) must either build a valid mesh or throw InputError.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const char* extensions[] = {".off", ".obj", ".ply", ".stl"};
  const std::string path = "/tmp/carbonmesh-fuzz-" + std::to_string(::getpid()) + extensions[data[0] % 4];
  {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  try {
    const carbonmesh::TriMesh mesh = carbonmesh::load_mesh(path);
    for (auto v : mesh.vertices())
      if (!mesh.is_manifold(v)) __builtin_trap();  // validation promised a manifold mesh
  } catch (const carbonmesh::InputError&) {
  }
  std::remove(path.c_str());
  return 0;
}
