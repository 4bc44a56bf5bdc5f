// The peer in the remeshing benchmark: CGAL's isotropic_remeshing on the same input, timed in-process.
// Usage: cgal_remesh IN OUT --target 1.5 --iterations 10   (borders protected). Prints one JSON object.
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/io.hpp"

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Simple_cartesian<double>;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: cgal_remesh IN OUT [--target L] [--iterations N]\n";
    return 2;
  }
  double target = 1.5;
  unsigned iterations = 10;
  for (int i = 3; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    if (key == "--target") target = std::stod(argv[i + 1]);
    else if (key == "--iterations") iterations = static_cast<unsigned>(std::stoul(argv[i + 1]));
  }
  try {
    const carbonmesh::TriMesh input = carbonmesh::load_mesh(argv[1]);
    SurfaceMesh sm;
    std::vector<SurfaceMesh::Vertex_index> vertex(input.n_vertices());
    for (auto v : input.vertices()) {
      const auto& p = input.point(v);
      vertex[static_cast<std::size_t>(v.idx())] = sm.add_vertex(Kernel::Point_3(p[0], p[1], p[2]));
    }
    for (auto f : input.faces()) {
      std::vector<SurfaceMesh::Vertex_index> corners;
      for (auto v : input.fv_range(f)) corners.push_back(vertex[static_cast<std::size_t>(v.idx())]);
      sm.add_face(corners);
    }
    const auto start = std::chrono::steady_clock::now();
    std::vector<SurfaceMesh::Edge_index> border;
    PMP::border_halfedges(faces(sm), sm, boost::make_function_output_iterator([&](SurfaceMesh::Halfedge_index h) {
                            border.push_back(sm.edge(h));
                          }));
    PMP::split_long_edges(border, target, sm);
    PMP::isotropic_remeshing(faces(sm), target, sm,
                             CGAL::parameters::number_of_iterations(iterations).protect_constraints(true));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    sm.collect_garbage();
    carbonmesh::TriMesh output;
    std::vector<carbonmesh::TriMesh::VertexHandle> handle(sm.number_of_vertices());
    for (auto v : sm.vertices()) {
      const auto& p = sm.point(v);
      handle[v.idx()] = output.add_vertex(carbonmesh::Vec3(p.x(), p.y(), p.z()));
    }
    for (auto f : sm.faces()) {
      std::vector<carbonmesh::TriMesh::VertexHandle> corners;
      for (auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) corners.push_back(handle[v.idx()]);
      output.add_face(corners);
    }
    carbonmesh::save_mesh(output, argv[2]);
    std::cout << nlohmann::json{{"seconds", seconds}, {"target", target}, {"iterations", iterations}}.dump() << "\n";
  } catch (const carbonmesh::InputError& e) {
    std::cerr << "cgal_remesh: error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
