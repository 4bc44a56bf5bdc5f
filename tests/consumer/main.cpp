// Links carbonmesh::remesh from an installed tree: builds a sphere and prints its genus and vertex count.
#include <carbonmesh/remesh/metrics.hpp>
#include <carbonmesh/remesh/shapes.hpp>
#include <iostream>

int main() {
  const carbonmesh::TriMesh sphere = carbonmesh::make_icosphere({5.0, 2});
  const carbonmesh::Topology t = carbonmesh::topology(sphere);
  std::cout << "genus " << t.genus << " vertices " << t.vertices << "\n";
  return t.genus == 0 && t.vertices == 162 ? 0 : 1;
}
