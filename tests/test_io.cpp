// Mesh IO: round trips of every format and validation of bad input (message and exit code 2).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>
#include <algorithm>
#include <array>

#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/io.hpp"
#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/shapes.hpp"
#include "test_paths.hpp"

namespace fs = std::filesystem;
using namespace carbonmesh;

namespace {

fs::path temp_dir() {
  const auto dir = fs::temp_directory_path() / ("carbonmesh-test-io-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

fs::path write_file(const std::string& name, const std::string& text) {
  const auto path = temp_dir() / name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

struct RunResult {
  int exit_code;
  std::string output;
};

RunResult run_cli(const std::string& args) {
  const auto out = temp_dir() / "cli-output.txt";
  const std::string command = std::string(CARBONMESH_CLI) + " " + args + " > " + out.string() + " 2>&1";
  const int status = std::system(command.c_str());
  std::ifstream in(out);
  std::stringstream text;
  text << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

// An OFF file from vertex and face lines.
std::string off(const std::string& vertices, const std::string& faces, int nv, int nf) {
  return "OFF\n" + std::to_string(nv) + " " + std::to_string(nf) + " 0\n" + vertices + faces;
}

// A string literal with embedded NULs as bytes, without its terminator. (A hand-counted length of 20 for an
// 18-byte literal read past its end: found by make test-asan.)
template <std::size_t N>
std::string bytes(const char (&literal)[N]) {
  return std::string(literal, N - 1);
}

const std::string kTetraVertices = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
const std::string kTetraFaces = "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";

// The mesh of `path` loaded with --repair, after checking that it is refused without, and what the repair did.
struct Repaired {
  TriMesh mesh;
  LoadReport report;
};
Repaired load_repaired(const fs::path& path) {
  EXPECT_THROW(load_mesh(path), InputError) << path;
  LoadSettings settings;
  settings.repair = true;
  Repaired out;
  out.mesh = load_mesh(path, settings, &out.report);
  return out;
}

}  // namespace

TEST(MeshIO, RoundTripEveryFormatKeepsTheMesh) {
  const TriMesh sphere = make_icosphere({10.0, 2});
  const Topology before = topology(sphere);
  const EdgeStats edges_before = edge_stats(sphere);
  for (const std::string ext : {".off", ".obj", ".ply", ".stl"}) {
    const auto path = temp_dir() / ("sphere" + ext);
    save_mesh(sphere, path);
    const TriMesh loaded = load_mesh(path);
    const Topology after = topology(loaded);
    EXPECT_EQ(after.vertices, before.vertices) << ext;
    EXPECT_EQ(after.faces, before.faces) << ext;
    EXPECT_TRUE(after.same_type(before)) << ext;
    // OFF, OBJ and PLY are written and read in double precision; STL stores floats.
    const double tolerance = ext == ".stl" ? 1e-5 : 1e-12;
    EXPECT_NEAR(edge_stats(loaded).mean, edges_before.mean, tolerance) << ext;
  }
}

TEST(MeshIO, SaveLeavesNoPartialFile) {
  const auto dir = temp_dir() / "atomic";
  fs::create_directories(dir);
  save_mesh(make_icosphere({1.0, 1}), dir / "a.off");
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    ++files;
    EXPECT_EQ(entry.path().filename(), "a.off");
  }
  EXPECT_EQ(files, 1);
}

TEST(MeshIO, PolygonsAreTriangulated) {
  // A cube of quads.
  const auto path = write_file("cube.off", off("0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n",
                                               "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n",
                                               8, 6));
  LoadReport report;
  const TriMesh mesh = load_mesh(path, {}, &report);
  EXPECT_EQ(mesh.n_faces(), 12u);
  EXPECT_EQ(report.triangulated_polygons, 6u);
  EXPECT_EQ(topology(mesh).genus, 0);
}

// Non-convex polygons: an L-shaped hexagon listed from a corner that does not see the whole polygon (its fan would
// turn a triangle over), and a 12-corner comb. Each is triangulated by ear clipping into triangles that turn as the
// polygon does and cover its area once; a convex pentagon keeps the fan from its first corner.
TEST(MeshIO, NonConvexPolygonsAreTriangulatedWithoutOverlap) {
  auto check = [](const std::string& name, const std::string& vertices, const std::string& face, int corners,
                  double area, std::size_t nonconvex) {
    const auto path = write_file(name, off(vertices, face, corners, 1));
    LoadReport report;
    const TriMesh mesh = load_mesh(path, {}, &report);
    EXPECT_EQ(report.triangulated_polygons, 1u) << name;
    EXPECT_EQ(report.nonconvex_polygons, nonconvex) << name;
    EXPECT_EQ(mesh.n_faces(), static_cast<std::size_t>(corners - 2)) << name;
    EXPECT_NEAR(surface_area(mesh), area, 1e-12) << name;
    for (auto f : mesh.faces()) EXPECT_GT(mesh.normal(f)[2], 0.0) << name << " face " << f.idx();
    return mesh;
  };
  check("l_shape.off", "2 1 0\n1 1 0\n1 2 0\n0 2 0\n0 0 0\n2 0 0\n", "6 0 1 2 3 4 5\n", 6, 3.0, 1);
  // Teeth of width 1 and height 2 on a base 0 <= y <= 1, 0 <= x <= 5: corners listed from the top of the last tooth.
  check("comb.off",
        "5 3 0\n4 3 0\n4 1 0\n3 1 0\n3 3 0\n2 3 0\n2 1 0\n1 1 0\n1 3 0\n0 3 0\n0 0 0\n5 0 0\n",
        "12 0 1 2 3 4 5 6 7 8 9 10 11\n", 12, 5.0 + 3 * 2.0, 1);
  const TriMesh pentagon = check("pentagon.off", "0 0 0\n2 0 0\n3 1 0\n1 2 0\n-1 1 0\n", "5 0 1 2 3 4\n", 5, 5.0, 0);
  int f = 0;  // the fan: (0 1 2), (0 2 3), (0 3 4)
  for (auto fh : pentagon.faces()) {
    std::vector<int> corners;
    for (auto v : pentagon.fv_range(fh)) corners.push_back(v.idx());
    std::rotate(corners.begin(), std::min_element(corners.begin(), corners.end()), corners.end());
    EXPECT_EQ(corners, (std::vector<int>{0, f + 1, f + 2}));
    ++f;
  }
}

struct BadInput {
  std::string name;      // fixture file name
  std::string contents;  // file contents
  std::string expected;  // part of the one-line message
};

void PrintTo(const BadInput& bad, std::ostream* os) { *os << bad.name; }

class BadInputTest : public ::testing::TestWithParam<BadInput> {};

TEST_P(BadInputTest, ClearOneLineErrorAndExitCode2) {
  const BadInput& bad = GetParam();
  fs::path path = temp_dir() / bad.name;
  if (bad.name != "missing.off") path = write_file(bad.name, bad.contents);
  EXPECT_THROW(load_mesh(path), InputError);
  const RunResult result = run_cli("stats " + path.string());
  EXPECT_EQ(result.exit_code, kExitBadInput) << result.output;
  EXPECT_NE(result.output.find(path.string()), std::string::npos) << "message names the file: " << result.output;
  EXPECT_NE(result.output.find(bad.expected), std::string::npos) << result.output;
  EXPECT_EQ(std::count(result.output.begin(), result.output.end(), '\n'), 1) << "one line: " << result.output;
}

INSTANTIATE_TEST_SUITE_P(
    Classes, BadInputTest,
    ::testing::Values(
        BadInput{"missing.off", "", "no such file"},
        BadInput{"empty.off", "", "empty file"},
        BadInput{"nofaces.off", off(kTetraVertices, "", 4, 0), "no faces"},
        BadInput{"nan.off", off("0 0 0\n1 0 nan\n0 1 0\n0 0 1\n", kTetraFaces, 4, 4), "non-finite"},
        BadInput{"inf.obj", "v 0 0 0\nv 1 0 inf\nv 0 1 0\nf 1 2 3\n", "non-finite"},
        BadInput{"nonmanifold_edge.off",
                 off(kTetraVertices + "1 1 1\n", kTetraFaces + "3 0 1 4\n", 5, 5), "non-manifold edge"},
        BadInput{"pinched.off",
                 off("0 0 0\n1 0 0\n0 1 0\n-1 0 0\n0 -1 0\n", "3 0 1 2\n3 0 3 4\n", 5, 2), "non-manifold"},
        // Two tetrahedra sharing one vertex: closed fans (OpenMesh's add_face used to print "complex vertex").
        BadInput{"pinched_closed.off",
                 off(kTetraVertices + "-1 0 0\n0 -1 0\n0 0 -1\n",
                     kTetraFaces + "3 0 4 5\n3 0 6 4\n3 4 6 5\n3 0 5 6\n", 7, 8),
                 "pinched"},
        BadInput{"degenerate.off", off("0 0 0\n1 0 0\n2 0 0\n0 1 0\n", "3 0 1 2\n3 0 1 3\n", 4, 2),
                 "degenerate"},
        BadInput{"duplicate_vertex.off",
                 off("0 0 0\n1 0 0\n0 1 0\n1 0 0\n1 1 0\n", "3 0 1 2\n3 3 4 2\n", 5, 2), "duplicate vertices"},
        // Two triangles that would share the edge 1-2, but the second's copy of vertex 2 is 1e-15 off it (a seam
        // computed twice): an unwelded crack, not two borders lying on each other.
        BadInput{"unwelded_seam.off", off("0 0 0\n1 0 0\n0 1 0\n1 1 0\n1e-15 1 0\n", "3 0 1 2\n3 1 3 4\n", 5, 2),
                 "closer than"},
        // Two unit squares side by side; the right one has a vertex at the middle of the edge they share, which the
        // left one's triangle spans without it: a T-junction crack along the edge.
        BadInput{"t_junction.off",
                 off("0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 0 0\n2 1 0\n1 0.5 0\n",
                     "3 0 1 2\n3 0 2 3\n3 1 4 6\n3 6 4 5\n3 6 5 2\n", 7, 5),
                 "T-junction"},
        BadInput{"flipped.off", off("0 0 0\n1 0 0\n0 1 0\n1 1 0\n", "3 0 1 2\n3 1 2 3\n", 4, 2),
                 "inconsistent orientation"},
        BadInput{"unknown.xyz", "1 2 3\n", "unsupported format"},
        BadInput{"header_only.off", "OFF\n", "truncated"},
        BadInput{"truncated_vertices.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n", "truncated"},
        BadInput{"truncated_faces.off", off(kTetraVertices, "3 0 2 1\n", 4, 4), "truncated"},
        BadInput{"garbage.off", bytes("OFF\n\x01\x02\xff\xfe\0\0garbage"), "binary data"},
        // Binary bytes quoted in the message are escaped (\xNN), never written to the terminal raw.
        BadInput{"garbage_word.off", "t\xbd\xc0\x16x 1 2\n", "first word is 't\\xbd\\xc0\\x16x'"},
        BadInput{"garbage.obj", bytes("v 0 0 0\nv \x01\x02\0\xff"), "binary data"},
        BadInput{"words.off", "OFF\nthree four 0\n", "not an integer"},
        BadInput{"out_of_range.off", off(kTetraVertices, "3 0 1 7\n", 4, 1), "out of range"},
        BadInput{"out_of_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "out of range"},
        BadInput{"negative_counts.off", "OFF\n-4 2 0\n", "implausible counts"},
        BadInput{"repeated_corner.off", off(kTetraVertices, "3 0 1 1\n", 4, 1), "degenerate"},
        BadInput{"duplicate_face.off", off(kTetraVertices, kTetraFaces + "3 1 2 3\n", 4, 5), "duplicates"},
        BadInput{"header_only.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n", "truncated PLY header"},
        BadInput{"truncated.ply",
                 "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                 "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n",
                 "truncated"},
        BadInput{"garbage.stl", std::string(7, '\x7f'), "cannot be parsed as stl"},
        // Fuzzing findings, kept as regressions: huge announced counts in a tiny file (was: out of memory),
        // a PLY vertex index beyond int (was: undefined behaviour).
        BadInput{"huge_counts.off", "OFF\n100000000 100000000 0\n0 0 0\n", "truncated"},
        BadInput{"huge_index.ply",
                 "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                 "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                 "0 0 0\n1 0 0\n0 1 0\n3 0 1 1e12\n",
                 "invalid vertex index"}),
    [](const auto& info) {
      std::string n = info.param.name;
      std::replace(n.begin(), n.end(), '.', '_');
      return n;
    });

TEST(MeshIO, RepairMergesDuplicatesAndDropsDegenerateFaces) {
  const auto path = write_file("repairable.off", off("0 0 0\n1 0 0\n0 1 0\n1 0 0\n1 1 0\n2 0 0\n",
                                                     "3 0 1 2\n3 3 4 2\n3 0 1 5\n", 6, 3));
  const auto [mesh, report] = load_repaired(path);
  EXPECT_EQ(report.duplicate_vertices, 1u);
  EXPECT_EQ(report.degenerate_faces, 1u);
  EXPECT_EQ(mesh.n_faces(), 2u);
  EXPECT_EQ(mesh.n_vertices(), 4u);
  const RunResult result = run_cli("stats --repair " + path.string());
  EXPECT_EQ(result.exit_code, 0) << result.output;
}

// --repair welds nearly coincident vertices too: the seam above loads as one sheet with one border, and vertices
// farther apart than the tolerance stay apart.
TEST(MeshIO, RepairWeldsNearlyCoincidentVertices) {
  const auto path = write_file("seam.off", off("0 0 0\n1 0 0\n0 1 0\n1 1 0\n1e-15 1 0\n", "3 0 1 2\n3 1 3 4\n", 5, 2));
  const auto [mesh, report] = load_repaired(path);
  EXPECT_EQ(report.duplicate_vertices, 0u);
  EXPECT_EQ(report.near_duplicate_vertices, 1u);
  EXPECT_EQ(mesh.n_vertices(), 4u);
  EXPECT_EQ(topology(mesh).boundary_loops, 1u);
  // Two triangles with corners 1e-3 apart at coordinates of about 1: a real gap (the tolerance is 4 float roundings
  // of the largest coordinate, about 5e-7 here), kept: two components.
  const auto gap = write_file("gap.off", off("0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 0 1\n1e-3 1 0\n", "3 0 1 2\n3 3 4 5\n",
                                             6, 2));
  LoadReport gap_report;
  const TriMesh apart = load_mesh(gap, {}, &gap_report);
  EXPECT_EQ(gap_report.near_duplicate_vertices, 0u);
  EXPECT_EQ(gap_report.t_junctions, 0u);
  EXPECT_EQ(apart.n_vertices(), 6u);
  EXPECT_EQ(topology(apart).components, 2u);
}

// A box of side 10 whose top is a 4 x 4 grid and every other side a 3 x 3 grid, its vertices shared where they
// coincide: along the top's rim the top's vertices lie inside the sides' edges and the sides' inside the top's, 5
// vertices on each of 4 edges. Refused; --repair splits the faces there and the box is closed, and loads again as
// it is.
TEST(MeshIO, RepairSplitsTJunctions) {
  std::vector<std::array<double, 3>> points;
  std::map<std::array<double, 3>, int> index;
  std::string faces;
  int count = 0;
  auto at = [&](const std::array<double, 3>& p) {
    const auto [it, inserted] = index.emplace(p, static_cast<int>(points.size()));
    if (inserted) points.push_back(p);
    return it->second;
  };
  using V = std::array<double, 3>;
  const std::array<std::tuple<V, V, V, int>, 6> sides{{{{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, 3},
                                                        {{0, 0, 10}, {1, 0, 0}, {0, 1, 0}, 4},
                                                        {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, 3},
                                                        {{0, 10, 0}, {0, 0, 1}, {1, 0, 0}, 3},
                                                        {{0, 0, 0}, {0, 0, 1}, {0, 1, 0}, 3},
                                                        {{10, 0, 0}, {0, 1, 0}, {0, 0, 1}, 3}}};
  for (const auto& [o, u, v, n] : sides) {
    auto grid = [&, o = o, u = u, v = v, n = n](int i, int j) {
      V p{};
      for (std::size_t c = 0; c < 3; ++c) p[c] = o[c] + 10.0 * (i / double(n)) * u[c] + 10.0 * (j / double(n)) * v[c];
      return at(p);
    };
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const int a = grid(i, j), b = grid(i + 1, j), c = grid(i + 1, j + 1), d = grid(i, j + 1);
        faces += "3 " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + "\n";
        faces += "3 " + std::to_string(a) + " " + std::to_string(c) + " " + std::to_string(d) + "\n";
        count += 2;
      }
  }
  std::ostringstream vertices;
  vertices.precision(17);
  for (const auto& p : points) vertices << p[0] << " " << p[1] << " " << p[2] << "\n";
  const auto path = write_file("t_box.off", off(vertices.str(), faces, static_cast<int>(points.size()), count));
  const auto [mesh, report] = load_repaired(path);
  EXPECT_EQ(report.t_junctions, 20u);
  EXPECT_EQ(report.near_duplicate_vertices, 0u);
  EXPECT_TRUE(report.repaired);
  EXPECT_EQ(mesh.n_vertices(), points.size());  // no vertex added: every split face had one edge split
  const Topology t = topology(mesh);
  EXPECT_EQ(t.boundary_loops, 0u);
  EXPECT_EQ(t.components, 1u);
  EXPECT_EQ(t.genus, 0);
  EXPECT_NEAR(surface_area(mesh), 600.0, 1e-9);
  const auto repaired = temp_dir() / "t_box_repaired.off";
  save_mesh(mesh, repaired);
  LoadReport again;
  EXPECT_NO_THROW(load_mesh(repaired, {}, &again));
  EXPECT_EQ(again.t_junctions, 0u);
}

// A triangle whose neighbours below and to the left have a vertex at the middle of its two edges there: split from a
// new vertex at its centroid into five triangles, with the area and the orientation kept.
TEST(MeshIO, RepairSplitsAFaceWithVerticesInsideTwoEdgesAtItsCentroid) {
  const auto path = write_file("t_two_edges.off",
                               off("0 0 0\n2 0 0\n0 2 0\n1 0 0\n1 -1 0\n0 1 0\n-1 1 0\n",
                                   "3 0 1 2\n3 0 4 3\n3 3 4 1\n3 0 5 6\n3 5 2 6\n", 7, 5));
  const auto [mesh, report] = load_repaired(path);
  EXPECT_EQ(report.t_junctions, 2u);
  EXPECT_EQ(mesh.n_vertices(), 8u);
  EXPECT_EQ(mesh.n_faces(), 9u);
  EXPECT_EQ(topology(mesh).boundary_loops, 1u);
  EXPECT_NEAR(surface_area(mesh), 4.0, 1e-12);
  for (auto f : mesh.faces()) EXPECT_GT(mesh.normal(f)[2], 0.0) << f.idx();  // every face still faces +z
}

// Faces that disagree with their neighbours: --repair turns them, and each component keeps the orientation most of its
// faces had (here outward, even with the first face among the turned ones).
TEST(MeshIO, RepairOrientsFacesAlikeKeepingTheMajority) {
  const auto tetra = write_file("tetra_flipped.off", off(kTetraVertices, "3 0 2 1\n3 0 1 3\n3 3 2 1\n3 0 3 2\n", 4, 4));
  const auto [turned, report] = load_repaired(tetra);
  EXPECT_EQ(report.reversed_faces, 1u);
  EXPECT_EQ(report.split_vertices, 0u);
  EXPECT_EQ(topology(turned).boundary_loops, 0u);
  EXPECT_EQ(topology(turned).genus, 0);
  const Vec3 centre(0.25, 0.25, 0.25);
  for (auto f : turned.faces())
    EXPECT_GT(OpenMesh::dot(turned.normal(f), turned.calc_face_centroid(f) - centre), 0.0) << f.idx();

  const TriMesh sphere = make_icosphere({10.0, 1});
  std::ostringstream vertices, faces;
  vertices.precision(17);
  for (auto v : sphere.vertices())
    vertices << sphere.point(v)[0] << " " << sphere.point(v)[1] << " " << sphere.point(v)[2] << "\n";
  for (auto f : sphere.faces()) {
    std::vector<int> corners;
    for (auto v : sphere.fv_range(f)) corners.push_back(v.idx());
    if (f.idx() == 0 || f.idx() == 7 || f.idx() == 40) std::swap(corners[1], corners[2]);
    faces << "3 " << corners[0] << " " << corners[1] << " " << corners[2] << "\n";
  }
  const auto path = write_file("sphere_flipped.off", off(vertices.str(), faces.str(),
                                                         static_cast<int>(sphere.n_vertices()),
                                                         static_cast<int>(sphere.n_faces())));
  const auto [mesh, sphere_report] = load_repaired(path);
  EXPECT_EQ(sphere_report.reversed_faces, 3u);
  EXPECT_EQ(mesh.n_faces(), sphere.n_faces());
  for (auto f : mesh.faces()) EXPECT_GT(OpenMesh::dot(mesh.normal(f), mesh.calc_face_centroid(f)), 0.0) << f.idx();
}

// Two closed tetrahedra sharing one vertex (pinched) and a tetrahedron with a fin on one of its edges (an edge of three
// faces): refused, and with --repair the vertices there are split, so each part loads on its own.
TEST(MeshIO, RepairSplitsNonManifoldVerticesAndEdges) {
  const auto pinched = write_file("pinched_repair.off", off(kTetraVertices + "-1 0 0\n0 -1 0\n0 0 -1\n",
                                                           kTetraFaces + "3 0 4 5\n3 0 6 4\n3 4 6 5\n3 0 5 6\n", 7, 8));
  const auto [two, report] = load_repaired(pinched);
  EXPECT_EQ(report.split_vertices, 1u);
  EXPECT_EQ(report.reversed_faces, 0u);
  EXPECT_EQ(two.n_vertices(), 8u);
  EXPECT_EQ(topology(two).components, 2u);
  EXPECT_EQ(topology(two).boundary_loops, 0u);

  const auto fin = write_file("fin_repair.off", off(kTetraVertices + "1 1 1\n", kTetraFaces + "3 0 1 4\n", 5, 5));
  const auto [cut, fin_report] = load_repaired(fin);
  EXPECT_GE(fin_report.split_vertices, 2u);  // the two ends of the edge, for the faces cut off there
  EXPECT_EQ(cut.n_faces(), 5u);
  EXPECT_NEAR(surface_area(cut), 0.5 * 3 + std::sqrt(3.0) / 2 + std::sqrt(2.0) / 2, 1e-12);
}

TEST(Cli, BadOptionIsAnErrorWithAHint) {
  const RunResult result = run_cli("stats --no-such-option x.off");
  EXPECT_EQ(result.exit_code, kExitBadInput);
  EXPECT_NE(result.output.find("--help"), std::string::npos) << result.output;
  const RunResult bad_interval = run_cli("stats --emin 2 --emax 1 x.off");
  EXPECT_EQ(bad_interval.exit_code, kExitBadInput);
}

TEST(MeshIO, ManySmallComponentsAreValid) {
  // 45 separate tetrahedra: a valid input with 45 components.
  std::string vertices, faces;
  for (int c = 0; c < 45; ++c) {
    for (const char* v : {"0 0 0", "1 0 0", "0 1 0", "0 0 1"}) {
      std::istringstream in(v);
      double x, y, z;
      in >> x >> y >> z;
      vertices += std::to_string(x + 3 * c) + " " + std::to_string(y) + " " + std::to_string(z) + "\n";
    }
    const int b = 4 * c;
    for (const auto& f : {std::array<int, 3>{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}})
      faces += "3 " + std::to_string(b + f[0]) + " " + std::to_string(b + f[1]) + " " + std::to_string(b + f[2]) + "\n";
  }
  const auto path = write_file("many.off", off(vertices, faces, 180, 180));
  const Topology t = topology(load_mesh(path));
  EXPECT_EQ(t.components, 45u);
  EXPECT_EQ(t.genus, 0);
}

TEST(MeshIO, HugeAndTinyCoordinatesKeepTheirPrecision) {
  for (const double scale : {1e-9, 1e9}) {
    TriMesh mesh = make_icosphere({scale, 1});
    const auto path = temp_dir() / "scaled.off";
    save_mesh(mesh, path);
    const TriMesh loaded = load_mesh(path);
    EXPECT_DOUBLE_EQ(edge_stats(loaded).mean, edge_stats(mesh).mean) << scale;
  }
}

TEST(MeshIO, IsolatedVerticesAreDroppedWithAWarning) {
  const auto path = write_file("isolated.off", off(kTetraVertices + "5 5 5\n", kTetraFaces, 5, 4));
  LoadReport report;
  const TriMesh mesh = load_mesh(path, {}, &report);
  EXPECT_EQ(report.unreferenced_vertices, 1u);
  EXPECT_EQ(mesh.n_vertices(), 4u);
}
