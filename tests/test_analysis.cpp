// Defect analysis: SP rings, ring structures, distances, 5-7 pairs, topological floor, mirror plane, data files.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>

#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/shapes.hpp"
#include "carbonmesh/simulations/analysis.hpp"
#include "carbonmesh/simulations/defect_stats.hpp"
#include "carbonmesh/simulations/lammps_atoms.hpp"
#include "carbonmesh/simulations/mirror_plane.hpp"
#include "carbonmesh/simulations/ring_structure.hpp"
#include "carbonmesh/simulations/sp_rings.hpp"
#include "test_meshes.hpp"

using namespace carbonmesh;
namespace fs = std::filesystem;
using carbonmesh::test::mesh_from;

namespace {

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("carbonmesh_test_analysis_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// Ring as a set of atoms (for comparing ring sets regardless of start and direction).
std::set<std::vector<int>> as_sets(const std::vector<std::vector<int>>& rings) {
  std::set<std::vector<int>> out;
  for (auto r : rings) {
    std::sort(r.begin(), r.end());
    out.insert(r);
  }
  return out;
}

std::vector<std::vector<int>> closed_rings(const RingStructure& rs) {
  std::vector<std::vector<int>> out;
  for (std::size_t r = 0; r < rs.size(); ++r)
    if (!rs.open[r]) out.push_back(rs.rings[r]);
  return out;
}

std::map<int, std::size_t> size_counts(const std::vector<std::vector<int>>& rings) {
  std::map<int, std::size_t> m;
  for (const auto& r : rings) ++m[static_cast<int>(r.size())];
  return m;
}

// A planar triangulated patch whose rows above y = 0 hold one more lattice column than the rows below: an edge
// dislocation. Its dual is a graphene patch with a single 5-7 pair.
TriMesh lattice_with_dislocation(int columns, int rows_above, int rows_below) {
  std::vector<std::vector<int>> row_ids;
  std::vector<Vec3> points;
  const double h = std::sqrt(3.0) / 2;
  for (int j = -rows_below; j <= rows_above; ++j) {
    const bool even = (j % 2 == 0);
    const bool upper = j >= 0;
    const int m = upper ? columns : columns - 1;  // lattice columns in this half
    const double s = upper ? 1.0 : double(columns) / (columns - 1);
    std::vector<int> ids;
    const int count = even ? m + 1 : m;
    for (int i = 0; i < count; ++i) {
      ids.push_back(static_cast<int>(points.size()));
      points.emplace_back((i + (even ? 0.0 : 0.5)) * s, j * h, 0.0);
    }
    row_ids.push_back(ids);
  }
  std::vector<std::array<int, 3>> tris;
  for (std::size_t r = 0; r + 1 < row_ids.size(); ++r) {
    const auto& bottom = row_ids[r];
    const auto& top = row_ids[r + 1];
    std::size_t p = 0, q = 0;
    while (p + 1 < top.size() || q + 1 < bottom.size()) {
      const bool advance_top = q + 1 >= bottom.size() ||
                               (p + 1 < top.size() && points[top[p + 1]][0] < points[bottom[q + 1]][0]);
      if (advance_top) {
        tris.push_back({bottom[q], top[p + 1], top[p]});
        ++p;
      } else {
        tris.push_back({bottom[q], bottom[q + 1], top[p]});
        ++q;
      }
    }
  }
  return mesh_from(points, tris);
}

// A disk of `layers` rings of triangles around a centre of valence `sectors`: `sectors` wedges of the triangular
// lattice glued cyclically. Every other interior vertex has valence 6 (its dual: one n-gon among hexagons).
TriMesh disclination_disk(int sectors, int layers) {
  auto id = [&](int k, int s, int j) {
    if (k == 0) return 0;
    if (j == k) {
      s = (s + 1) % sectors;
      j = 0;
    }
    return 1 + sectors * k * (k - 1) / 2 + s * k + j;
  };
  std::vector<Vec3> points(1 + sectors * layers * (layers + 1) / 2);
  const double pi = std::acos(-1.0);
  for (int k = 1; k <= layers; ++k)
    for (int s = 0; s < sectors; ++s)
      for (int j = 0; j < k; ++j) {
        const double angle = 2 * pi * (s + double(j) / k) / sectors;
        points[id(k, s, j)] = Vec3(k * std::cos(angle), k * std::sin(angle), 0);
      }
  std::vector<std::array<int, 3>> tris;
  for (int k = 0; k < layers; ++k)
    for (int s = 0; s < sectors; ++s) {
      for (int j = 0; j <= k; ++j) tris.push_back({id(k, s, j), id(k + 1, s, j), id(k + 1, s, j + 1)});
      for (int j = 0; j < k; ++j) tris.push_back({id(k, s, j), id(k + 1, s, j + 1), id(k, s, j + 1)});
    }
  return mesh_from(points, tris);
}

// "Smallest ring per bond": for every bond, one shortest cycle through it. The method the issue rules out.
std::vector<std::vector<int>> smallest_ring_per_bond(const AtomGraph& g) {
  std::vector<std::vector<int>> rings;
  for (const auto& b : g.bonds) {
    std::vector<int> pred(g.atoms(), -2);
    std::vector<int> queue{b[0]};
    pred[b[0]] = -1;
    for (std::size_t q = 0; q < queue.size() && pred[b[1]] == -2; ++q)
      for (const int* it = g.begin(queue[q]); it != g.end(queue[q]); ++it) {
        if (queue[q] == b[0] && *it == b[1]) continue;  // not the bond itself
        if (pred[*it] == -2) {
          pred[*it] = queue[q];
          queue.push_back(*it);
        }
      }
    if (pred[b[1]] == -2) continue;
    std::vector<int> ring;
    for (int v = b[1]; v != -1; v = pred[v]) ring.push_back(v);
    rings.push_back(ring);
  }
  const auto sets = as_sets(rings);
  return {sets.begin(), sets.end()};
}

void write_data(const fs::path& file, const std::vector<Vec3>& atoms, bool full) {
  std::ofstream out(file);
  out << "carbonmesh test structure\n\n" << atoms.size() << " atoms\n1 atom types\n\n";
  out << "-50 50 xlo xhi\n-50 50 ylo yhi\n-50 50 zlo zhi\n\nMasses\n\n1 12.011\n\n";
  out << (full ? "Atoms # full\n\n" : "Atoms # atomic\n\n");
  for (std::size_t i = 0; i < atoms.size(); ++i) {
    if (full)
      out << i + 1 << " 1 1 0.0 " << atoms[i][0] << " " << atoms[i][1] << " " << atoms[i][2] << " 0 0 0\n";
    else
      out << i + 1 << " 1 " << atoms[i][0] << " " << atoms[i][1] << " " << atoms[i][2] << "\n";
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------------- SP rings

TEST(SpRings, DualOfIcosphereHasTwelvePentagonsAndOnlyHexagonsBesides) {
  for (int s : {0, 1, 2}) {
    const RingStructure mesh_rings = rings_from_mesh(make_icosphere({10.0, s}));
    // s = 0 is the dodecahedron (C20): its ten-atom Petrie polygons are SP rings too (graph diameter 5), so
    // search up to size 9 there.
    SpRingSettings settings;
    settings.max_size = s == 0 ? 9 : 10;
    const SpRingResult sp = find_sp_rings(mesh_rings.atoms, settings);
    EXPECT_EQ(as_sets(sp.rings), as_sets(mesh_rings.rings)) << "subdivisions " << s;
    const auto counts = size_counts(sp.rings);
    EXPECT_EQ(counts.at(5), 12u);
    const std::size_t hexagons = 10 * (1u << (2 * s)) + 2 - 12;  // V - 12
    EXPECT_EQ(counts.size(), hexagons ? 2u : 1u);
    if (hexagons) {
      EXPECT_EQ(counts.at(6), hexagons);
    }
    EXPECT_EQ(sp.truncated_ends, 0u);
  }
}

TEST(SpRings, GraphenePatchWithOneEmbeddedFiveSevenPair) {
  const TriMesh primal = lattice_with_dislocation(12, 6, 6);
  const RingStructure expected = rings_from_mesh(primal);
  const auto expected_counts = size_counts(closed_rings(expected));
  ASSERT_EQ(expected_counts.at(5), 1u);
  ASSERT_EQ(expected_counts.at(7), 1u);
  ASSERT_EQ(expected_counts.size(), 3u);  // 5, 6, 7

  const SpRingResult sp = find_sp_rings(expected.atoms);
  EXPECT_EQ(as_sets(sp.rings), as_sets(closed_rings(expected)));
  const RingStructure rs = rings_from_graph(expected.atoms, sp.rings);
  const PairStats pairs = pentagon_heptagon_pairs(rs);
  EXPECT_EQ(pairs.pentagons, 1u);
  EXPECT_EQ(pairs.heptagons, 1u);
  EXPECT_EQ(pairs.adjacent_pairs, 1u);
  EXPECT_EQ(pairs.matched_pairs, 1u);
  // An open patch: no topological floor.
  EXPECT_FALSE(topological_floor(rs).closed);
  EXPECT_EQ(topological_floor(rs).sum_six_minus_size, 0);
}

TEST(SpRings, FindsAHeptagonWhoseEveryBondIsSharedWithHexagons) {
  const RingStructure expected = rings_from_mesh(disclination_disk(7, 4));
  const auto expected_counts = size_counts(closed_rings(expected));
  ASSERT_EQ(expected_counts.at(7), 1u);
  ASSERT_EQ(expected_counts.size(), 2u);
  // The heptagon's seven neighbours are hexagons.
  for (std::size_t r = 0; r < expected.size(); ++r)
    if (expected.sizes[r] == 7) {
      for (int s : expected.neighbors[r]) EXPECT_EQ(expected.sizes[s], 6);
    }

  const SpRingResult sp = find_sp_rings(expected.atoms);
  const auto counts = size_counts(sp.rings);
  EXPECT_EQ(counts.at(7), 1u);
  EXPECT_EQ(counts.at(6), expected_counts.at(6));
  EXPECT_EQ(counts.size(), 2u);
  EXPECT_EQ(as_sets(sp.rings), as_sets(closed_rings(expected)));
  // What "smallest ring per bond" would report: no heptagon at all.
  EXPECT_EQ(size_counts(smallest_ring_per_bond(expected.atoms)).count(7), 0u);

  // Same with a pentagon (cone) and an octagon.
  for (int n : {5, 8}) {
    const RingStructure other = rings_from_mesh(disclination_disk(n, 4));
    EXPECT_EQ(as_sets(find_sp_rings(other.atoms).rings), as_sets(closed_rings(other))) << n;
  }
}

TEST(SpRings, SettingsAreChecked) {
  const AtomGraph g = make_atom_graph(3, {{0, 1}, {1, 2}, {0, 2}});
  EXPECT_EQ(find_sp_rings(g).rings.size(), 1u);
  SpRingSettings s;
  s.max_size = 2;
  EXPECT_THROW(find_sp_rings(g, s), std::invalid_argument);
  EXPECT_THROW(make_atom_graph(2, {{0, 5}}), std::invalid_argument);
}

// ------------------------------------------------------------------------------------- mesh input, floor

TEST(MeshRings, IcosphereNearestPentagonIsTwoToTheSubdivisionsSteps) {
  for (int s = 0; s <= 4; ++s) {
    const RingStructure rs = rings_from_mesh(make_icosphere({10.0, s}));
    const NearestDistances d = nearest_same_size(rs, 5);
    ASSERT_EQ(d.rings.size(), 12u);
    EXPECT_EQ(d.unreachable, 0u);
    ASSERT_EQ(d.histogram.size(), 1u) << "subdivisions " << s;
    EXPECT_EQ(d.histogram.begin()->first, 1 << s);
    EXPECT_EQ(d.histogram.begin()->second, 12u);
    const TopologicalFloor f = topological_floor(rs);
    EXPECT_TRUE(f.closed);
    EXPECT_EQ(f.sum_six_minus_size, 12);
    EXPECT_EQ(f.six_chi.value(), 12);
    EXPECT_EQ(f.floor.value(), 12);
    EXPECT_EQ(f.non_hexagons, 12u);
    EXPECT_EQ(nearest_same_size(rs, 7).rings.size(), 0u);
  }
}

TEST(MeshRings, TorusFloorIsZero) {
  const RingStructure rs = rings_from_mesh(make_torus({}));
  const TopologicalFloor f = topological_floor(rs);
  EXPECT_TRUE(f.closed);
  EXPECT_EQ(f.euler.value(), 0);
  EXPECT_EQ(f.sum_six_minus_size, 0);
  EXPECT_EQ(f.six_chi.value(), 0);
  EXPECT_EQ(f.floor.value(), 0);
  // The same from the SP rings of its dual graph.
  const RingStructure sp = rings_from_graph(rs.atoms, find_sp_rings(rs.atoms).rings);
  EXPECT_TRUE(sp.closed_surface);
  EXPECT_EQ(topological_floor(sp).sum_six_minus_size, 0);
  EXPECT_EQ(topological_floor(sp).six_chi.value(), 0);
}

TEST(MeshRings, BorderVerticesAreOpenRings) {
  const RingStructure rs = rings_from_mesh(disclination_disk(6, 3));
  const RingSizeCounts c = ring_size_counts(rs);
  std::size_t open = 0;
  for (const auto& [k, v] : c.open) open += v;
  EXPECT_EQ(open, 18u);  // the outer layer
  EXPECT_EQ(c.closed.size(), 1u);
  EXPECT_EQ(c.closed.at(6), 19u);
}

TEST(Distances, MatchBruteForceOnAGrid) {
  // A 20 x 20 grid of rings with random sizes 5/6/7.
  RingStructure rs;
  const int n = 20;
  std::mt19937 rng(7);
  for (int i = 0; i < n * n; ++i) {
    const int r = static_cast<int>(rng() % 10);
    rs.sizes.push_back(r == 0 ? 5 : r == 1 ? 7 : 6);
    rs.rings.emplace_back(rs.sizes.back(), 0);
    rs.open.push_back(false);
    rs.centers.emplace_back(i % n, i / n, 0);
    std::vector<int> nb;
    if (i % n > 0) nb.push_back(i - 1);
    if (i % n < n - 1) nb.push_back(i + 1);
    if (i / n > 0) nb.push_back(i - n);
    if (i / n < n - 1) nb.push_back(i + n);
    std::sort(nb.begin(), nb.end());
    rs.neighbors.push_back(nb);
  }
  for (int size : {5, 7}) {
    const NearestDistances d = nearest_same_size(rs, size);
    for (std::size_t k = 0; k < d.rings.size(); ++k) {
      const int a = d.rings[k];
      int best = -1;
      for (int b = 0; b < n * n; ++b)
        if (b != a && rs.sizes[b] == size) {
          const int dist = std::abs(a % n - b % n) + std::abs(a / n - b / n);
          if (best < 0 || dist < best) best = dist;
        }
      ASSERT_TRUE(d.distance[k].has_value());
      EXPECT_EQ(*d.distance[k], best);
    }
  }
}

// ------------------------------------------------------------------------------------------ mirror plane

TEST(MirrorPlane, FindsThePlaneOfARotatedSymmetricShapeWithZeroResidual) {
  // An ellipsoid bent along x (x += 0.08 y^2): mirror-symmetric in y and in z only; then rotated and shifted.
  TriMesh mesh = make_icosphere({1.0, 3});
  const double c = std::cos(0.5), s = std::sin(0.5), c2 = std::cos(0.3), s2 = std::sin(0.3);
  auto rotate = [&](Vec3 p) {
    p = Vec3(c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]);
    return Vec3(p[0], c2 * p[1] - s2 * p[2], s2 * p[1] + c2 * p[2]);
  };
  for (auto v : mesh.vertices()) {
    Vec3 p = mesh.point(v);
    p = Vec3(6 * p[0], 3 * p[1], 2 * p[2]);
    p[0] += 0.08 * p[1] * p[1];
    mesh.set_point(v, rotate(p) + Vec3(1, -2, 3));
  }
  MirrorSettings settings;
  settings.search_samples = 1500;
  settings.final_samples = 5000;
  settings.evaluations_per_candidate = 100;
  const MirrorResult r = find_mirror_plane(mesh, settings);
  EXPECT_LT(r.residual.max, 1e-3 * r.diagonal);
  const Vec3 ey = rotate(Vec3(0, 1, 0)), ez = rotate(Vec3(0, 0, 1));
  const double along = std::max(std::abs(OpenMesh::dot(r.plane.normal, ey)), std::abs(OpenMesh::dot(r.plane.normal, ez)));
  EXPECT_GT(along, 0.9999);
  // The rotated x plane through the centre is not a mirror plane of the bent shape.
  Plane x;
  x.normal = rotate(Vec3(1, 0, 0));
  x.offset = OpenMesh::dot(x.normal, Vec3(1, -2, 3));
  EXPECT_GT(mirror_residual(mesh, x, 5000).max, 0.02 * r.diagonal);
}

TEST(MirrorPlane, ParsesAndCountsSides) {
  const Plane p = parse_plane("0,0,2,4", Vec3(0, 0, 0));
  EXPECT_DOUBLE_EQ(p.normal[2], 1.0);
  EXPECT_DOUBLE_EQ(p.offset, 2.0);
  EXPECT_DOUBLE_EQ(parse_plane("y", Vec3(1, 2, 3)).offset, 2.0);
  EXPECT_THROW(parse_plane("0,0,0,1", Vec3(0, 0, 0)), InputError);
  EXPECT_THROW(parse_plane("1,2", Vec3(0, 0, 0)), InputError);
  EXPECT_THROW(parse_plane("a,b,c,d", Vec3(0, 0, 0)), InputError);
  EXPECT_THROW(parse_plane("1,0,0,1,5", Vec3(0, 0, 0)), InputError);
  const RingStructure rs = rings_from_mesh(make_icosphere({10.0, 2}));
  const SideCounts sides = count_sides(rs, parse_plane("z", Vec3(0, 0, 0)), 1e-9);
  EXPECT_EQ(sides.positive_total + sides.negative_total + sides.on_plane_total, 12u);
  EXPECT_EQ(sides.positive_total, sides.negative_total);
}

// ---------------------------------------------------------------------------------------- data files

TEST(LammpsAtoms, ReadsAtomicAndFullAndFindsTheRingsOfAnIcosphereDual) {
  const RingStructure mesh_rings = rings_from_mesh(make_icosphere({1.0, 2}));
  // Scale so that the mean bond is 1.42 A.
  double mean = 0;
  for (const auto& b : mesh_rings.atoms.bonds)
    mean += (mesh_rings.atoms.positions[b[0]] - mesh_rings.atoms.positions[b[1]]).norm();
  mean /= static_cast<double>(mesh_rings.atoms.bonds.size());
  std::vector<Vec3> atoms;
  for (const auto& p : mesh_rings.atoms.positions) atoms.push_back(p * (1.42 / mean));
  const fs::path dir = temp_dir("data");
  for (bool full : {false, true}) {
    const fs::path file = dir / (full ? "full.data" : "atomic.data");
    write_data(file, atoms, full);
    const LammpsAtoms data = read_lammps_atoms(file);
    EXPECT_EQ(data.atom_style, full ? "full" : "atomic");
    ASSERT_EQ(data.positions.size(), atoms.size());
    EXPECT_NEAR(data.positions[5][1], atoms[5][1], 1e-5);
    EXPECT_DOUBLE_EQ(data.masses.at(0), 12.011);
    const Analysis a = analyze(file);
    EXPECT_EQ(a.structure.atoms.bonds.size(), mesh_rings.atoms.bonds.size());
    EXPECT_EQ(a.sizes.closed.at(5), 12u);
    EXPECT_EQ(a.sizes.closed.at(6), 150u);
    EXPECT_EQ(a.floor.sum_six_minus_size, 12);
    EXPECT_EQ(a.floor.six_chi.value(), 12);
    ASSERT_EQ(a.pentagons.histogram.size(), 1u);
    EXPECT_EQ(a.pentagons.histogram.begin()->first, 4);
  }
  // A build folder with a data file.
  fs::create_directories(dir / "build");
  write_data(dir / "build" / "structure.data", atoms, false);
  EXPECT_EQ(resolve_input(dir / "build").kind, "lammps data");
  EXPECT_EQ(analyze(dir / "build").sizes.closed.at(5), 12u);
  // Hydrogen (type 2, mass 1.008) 1.09 A outside ten atoms: left out of the rings and the coordination.
  {
    std::ofstream out(dir / "ch.data");
    out << "C and H\n\n" << atoms.size() + 10 << " atoms\n2 atom types\n-50 50 xlo xhi\n-50 50 ylo yhi\n"
        << "-50 50 zlo zhi\n\nMasses\n\n1 12.011\n2 1.008\n\nAtoms # atomic\n\n";
    for (std::size_t i = 0; i < atoms.size(); ++i)
      out << i + 1 << " 1 " << atoms[i][0] << " " << atoms[i][1] << " " << atoms[i][2] << "\n";
    for (std::size_t i = 0; i < 10; ++i) {
      const Vec3 h = atoms[i] + atoms[i].normalized() * 1.09;
      out << atoms.size() + i + 1 << " 2 " << h[0] << " " << h[1] << " " << h[2] << "\n";
    }
  }
  const Analysis ch = analyze(dir / "ch.data");
  EXPECT_EQ(ch.structure.atoms.atoms(), atoms.size());
  EXPECT_EQ(ch.coordination.size(), 1u);
  EXPECT_EQ(ch.sizes.closed.at(5), 12u);
  // A folder with rings.ply (what `carbonmesh build` writes) is read through its polygons.
  {
    std::ofstream ply(dir / "build" / "rings.ply");
    ply << "ply\nformat ascii 1.0\nelement vertex " << atoms.size() << "\nproperty double x\nproperty double y\n"
        << "property double z\nelement face " << mesh_rings.rings.size() << "\nproperty list uchar int vertex_indices\n"
        << "end_header\n";
    for (const auto& p : atoms) ply << p[0] << " " << p[1] << " " << p[2] << "\n";
    for (const auto& r : mesh_rings.rings) {
      ply << r.size();
      for (int v : r) ply << " " << v;
      ply << "\n";
    }
  }
  EXPECT_EQ(resolve_input(dir / "build").kind, "polygon mesh");
  const Analysis folder = analyze(dir / "build");
  EXPECT_EQ(folder.sizes.closed.at(5), 12u);
  EXPECT_EQ(folder.sizes.closed.at(6), 150u);
  fs::remove_all(dir);
}

TEST(LammpsAtoms, BadFilesGiveFileLineErrors) {
  const fs::path dir = temp_dir("bad");
  auto expect_error = [&](const std::string& text, const std::string& needle) {
    const fs::path f = dir / "bad.data";
    std::ofstream(f) << text;
    try {
      read_lammps_atoms(f);
      ADD_FAILURE() << "no error for: " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("bad.data:"), std::string::npos) << e.what();
    }
  };
  const std::string header = "title\n\n2 atoms\n1 atom types\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\n";
  expect_error(header + "Atoms # atomic\n\n1 1 0 0 0\n", "Atoms has 1 of 2 lines");
  expect_error(header + "Atoms # atomic\n\n1 1 0 0 0\n2 1 0 nan 0\n", ":12: coordinate 'nan'");
  expect_error(header + "Atoms # atomic\n\n1 1 0 0 0\n1 1 0 1 0\n", "duplicate atom id 1");
  expect_error(header + "Atoms # atomic\n\n1 1 0 0 0\n2 3 0 1 0\n", "atom type 3 out of range");
  expect_error(header + "Atoms # atomic\n\n1 1 0 0 0\n2 1 0 1\n", "needs 5 or 8 columns");
  expect_error(header + "Atoms # sphere\n\n", "not supported");
  expect_error("title\n\n2 atoms\n1 atom types\n0 1 xlo xhi\n\nAtoms\n\n", "ylo yhi");
  expect_error("title\n\n-2 atoms\n", "out of range");
  expect_error("title\n\n2 atoms\n5 6 7\n", ":4: unrecognised header line");
  expect_error("title\n\nfoo bar baz\n", "no 'N atoms' line");
  expect_error("title\n\n99999999999999999999 atoms\n", "not an integer");
  expect_error(header, "no Atoms section");
  expect_error(std::string("ti\0tle", 6), "binary");
  std::ofstream(dir / "empty.data");
  EXPECT_THROW(read_lammps_atoms(dir / "empty.data"), InputError);
  EXPECT_THROW(read_lammps_atoms(dir / "missing.data"), InputError);
  // Truncations of a good file at every byte never crash: either a clean read or an InputError.
  const std::string good = header + "Masses\n\n1 12.011\n\nAtoms # atomic\n\n1 1 0 0 0\n2 1 0 1.4 0 0 0 1\n";
  for (std::size_t cut = 0; cut <= good.size(); ++cut) {
    std::ofstream(dir / "cut.data") << good.substr(0, cut);
    try {
      read_lammps_atoms(dir / "cut.data");
    } catch (const InputError&) {
    }
  }
  fs::remove_all(dir);
}

// ---------------------------------------------------------------------------------------------- the CLI

TEST(AnalyzeCli, SphereReportFilesAndPolygonRoundTrip) {
  const fs::path dir = temp_dir("cli");
  const std::string cli = CARBONMESH_CLI;
  ASSERT_EQ(std::system((cli + " -q shape sphere --subdivisions 2 -o " + (dir / "s.off").string()).c_str()), 0);
  ASSERT_EQ(std::system((cli + " -q analyze " + (dir / "s.off").string() + " -o " + (dir / "r").string() +
                         " --plane z --no-plots --mirror-samples 2000 > /dev/null")
                            .c_str()),
            0);
  for (const char* f : {"report.json", "ring_sizes.csv", "rings.csv", "defect_distances.csv", "distance_histogram.csv",
                        "sides.csv", "defects.ply", "view.json"})
    EXPECT_TRUE(fs::exists(dir / "r" / f)) << f;
  // defects.ply read back as a polygon mesh: rings are its faces.
  const Analysis back = analyze(dir / "r" / "defects.ply");
  EXPECT_EQ(back.structure.source, "polygon mesh");
  EXPECT_EQ(back.sizes.closed.at(5), 12u);
  EXPECT_EQ(back.sizes.closed.at(6), 150u);
  EXPECT_EQ(back.floor.six_chi.value(), 12);
  EXPECT_EQ(back.pentagons.histogram.begin()->first, 4);
  // Bad input: one line, exit code 2.
  EXPECT_EQ(WEXITSTATUS(std::system((cli + " -q analyze " + (dir / "nothing.data").string() + " 2> /dev/null").c_str())), 2);
  fs::remove_all(dir);
}
