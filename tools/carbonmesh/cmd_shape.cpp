// `carbonmesh shape sphere|geodesic|torus|helix|capsule|capped-tube|tube [size options] -o OUT`
#include <spdlog/spdlog.h>

#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/io.hpp"
#include "carbonmesh/remesh/shapes.hpp"
#include "commands.hpp"

namespace carbonmesh::cli {

void add_shape_command(CLI::App& app, Action& action) {
  struct Options {
    std::string name, output;
    SphereShape sphere;
    GeodesicSphereShape geodesic;
    TorusShape torus;
    HelixShape helix;
    CapsuleShape capsule;
    TubeShape tube;
    std::vector<int> indices;  // geodesic: Goldberg-Coxeter (h, k)
    std::vector<int> chirality{5, 5};  // capped-tube: (n, m)
    double edge = 0;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("shape", "write a built-in shape, closed but for the open tube (sizes in the mesh's units, e.g. A)");
  cmd->add_option("name", opt->name, "sphere | geodesic | torus | helix | capsule | capped-tube (the dual of a capped nanotube) | tube (an open "
                  "cylinder)")
      ->required()
      ->check(CLI::IsMember(shape_names()));
  cmd->add_option("-o,--output", opt->output, "output mesh (.off .obj .ply .stl)")->required();
  cmd->add_option("--radius", opt->sphere.radius, "sphere and geodesic radius / helix radius / capsule and tube radius (mesh units, e.g. A)")
      ->capture_default_str();
  cmd->add_option("--subdivisions", opt->sphere.subdivisions, "sphere: icosahedron subdivisions (0-9; 20*4^k faces)")
      ->capture_default_str();
  cmd->add_option("--frequency", opt->geodesic.frequency,
                  "geodesic: divisions of each icosahedron edge (1-1000; 20 f^2 faces, the dual of C_20f^2)")
      ->capture_default_str();
  auto* sqrt3 = cmd->add_flag("--sqrt3", opt->geodesic.sqrt3, "geodesic: one sqrt(3) step after (60 f^2 faces: f 1, 2, 3, 4 give the duals of C60, C240, C540, C960)");
  cmd->add_option("--indices", opt->indices,
                  "geodesic: Goldberg-Coxeter indices H,K instead of --frequency (20 T faces, T = H^2 + HK + K^2, the "
                  "dual of the icosahedral fullerene C_20T; H,0 is frequency H, H,H frequency H with --sqrt3, "
                  "0 < K < H a chiral cage; default: none, --frequency is used)")
      ->expected(2)
      ->delimiter(',')
      ->excludes(sqrt3)
      ->excludes(cmd->get_option("--frequency"));
  cmd->add_option("--major", opt->torus.major_radius, "torus: radius of the centre circle (mesh units)")->capture_default_str();
  cmd->add_option("--minor", opt->torus.minor_radius, "torus: tube radius (mesh units)")->capture_default_str();
  cmd->add_option("--pitch", opt->helix.pitch, "helix: rise per turn (mesh units)")->capture_default_str();
  cmd->add_option("--turns", opt->helix.turns, "helix: number of turns (may be fractional)")->capture_default_str();
  cmd->add_option("--tube-radius", opt->helix.tube_radius, "helix: tube radius (mesh units)")->capture_default_str();
  cmd->add_option("--chirality", opt->chirality,
                  "capped-tube: chiral indices N,M of the tube (both multiples of 5: its caps are the halves of the "
                  "icosahedral fullerene C_20T, T = (N^2 + NM + M^2) / 25, 5,5 from C60; otherwise each cap is "
                  "five lattice triangles around a pentagon with five more on their rim; default 5,5)")
      ->expected(2)
      ->delimiter(',');
  cmd->add_option("--length", opt->capsule.length,
                  "capsule: length of the straight part; capped-tube: the same, to the nearest whole period of the "
                  "tube (N, M multiples of 5) or the nearest lattice row; tube: length (mesh units)")
      ->capture_default_str();
  cmd->add_option("--edge", opt->edge,
                  "torus/helix/capsule/tube: target edge length, mesh units (0: default resolution); capped-tube: the "
                  "lattice edge (0: 2.4595, sqrt(3) times a C-C bond of 1.42 A, the mesh's units taken as A)")
      ->capture_default_str();
  cmd->callback([&action, opt, cmd] {
    action = [opt, cmd]() -> int {
      TriMesh mesh;
      const bool radius_given = cmd->count("--radius") > 0;
      if (opt->name == "sphere") {
        mesh = make_icosphere(opt->sphere);
      } else if (opt->name == "geodesic") {
        opt->geodesic.radius = opt->sphere.radius;
        mesh = opt->indices.empty()
                   ? make_geodesic_sphere(opt->geodesic)
                   : make_goldberg_coxeter_sphere({opt->sphere.radius, opt->indices[0], opt->indices[1]});
      } else if (opt->name == "torus") {
        opt->torus.edge = opt->edge;
        mesh = make_torus(opt->torus);
      } else if (opt->name == "helix") {
        if (radius_given) opt->helix.radius = opt->sphere.radius;
        opt->helix.edge = opt->edge;
        mesh = make_helix(opt->helix);
      } else if (opt->name == "capped-tube") {
        if (radius_given)
          throw InputError("shape capped-tube: --radius is not an option of it (its radius is edge |N e1 + M e2| / "
                           "(2 pi), from --chirality and --edge)");
        const CappedTube tube = make_capped_tube(
            {opt->chirality[0], opt->chirality[1], opt->capsule.length, opt->edge > 0 ? opt->edge : CappedTubeShape{}.edge});
        if (tube.caps != CapKind::icosahedral)
          spdlog::info("capped tube ({}, {}): radius {:.4f}, straight part {:.4f} (period {:.4f}), closed by {}, its "
                       "dual C{} with 12 pentagons",
                       opt->chirality[0], opt->chirality[1], tube.radius, tube.straight_length, tube.period,
                       cap_kind_description(tube.caps), tube.mesh.n_faces());
        else
          spdlog::info("capped tube ({}, {}): radius {:.4f}, straight part {:.4f} ({} periods of {:.4f} added to "
                       "C{}), its dual C{} with 12 pentagons",
                       opt->chirality[0], opt->chirality[1], tube.radius, tube.straight_length, tube.periods,
                       tube.period, 20 * triangulation_number(opt->chirality[0] / 5, opt->chirality[1] / 5),
                       tube.mesh.n_faces());
        mesh = tube.mesh;
      } else if (opt->name == "capsule") {
        if (radius_given) opt->capsule.radius = opt->sphere.radius;
        opt->capsule.edge = opt->edge;
        mesh = make_capsule(opt->capsule);
      } else {
        opt->tube = {radius_given ? opt->sphere.radius : opt->tube.radius, opt->capsule.length, opt->edge};
        mesh = make_open_tube(opt->tube);
      }
      save_mesh(mesh, opt->output);
      spdlog::info("{}: {} with {} vertices, {} faces", opt->output, opt->name, mesh.n_vertices(), mesh.n_faces());
      return 0;
    };
  });
}

}  // namespace carbonmesh::cli
