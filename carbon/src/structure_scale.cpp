#include "carbonmesh/carbon/structure_scale.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "carbonmesh/remesh/error.hpp"

namespace carbonmesh {

double target_edge(double bond) { return std::sqrt(3.0) * bond; }

double area_per_atom(double bond) {
  const double a = target_edge(bond);
  return std::sqrt(3.0) / 4.0 * a * a;
}

namespace {
double longest_side(const TriMesh& mesh) {
  const double inf = std::numeric_limits<double>::infinity();
  Vec3 lo(inf, inf, inf), hi(-inf, -inf, -inf);
  for (auto v : mesh.vertices()) {
    lo.minimize(mesh.point(v));
    hi.maximize(mesh.point(v));
  }
  return std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
}
}  // namespace

StructureScale structure_scale(const TriMesh& mesh, const ScaleSettings& settings) {
  if (!(settings.bond > 0) || !std::isfinite(settings.bond))
    throw InputError(fmt::format("bond length {} must be positive", settings.bond));
  if (!(settings.low > 0) || !(settings.low < settings.high))
    throw InputError(fmt::format("edge interval factors {} .. {} must satisfy 0 < low < high", settings.low,
                                 settings.high));
  if (settings.mode != ScaleMode::None && (!(settings.value > 0) || !std::isfinite(settings.value)))
    throw InputError(fmt::format("the size, scale or atom count {} must be positive", settings.value));
  const double area = surface_area(mesh);
  const double side = longest_side(mesh);
  if (mesh.n_faces() == 0 || !(area > 0) || !(side > 0)) throw InputError("cannot scale a mesh without area");

  StructureScale s;
  switch (settings.mode) {
    case ScaleMode::None: s.factor = 1; break;
    case ScaleMode::Size: s.factor = settings.value / side; break;
    case ScaleMode::Factor: s.factor = settings.value; break;
    case ScaleMode::Atoms: s.factor = std::sqrt(settings.value * area_per_atom(settings.bond) / area); break;
  }
  s.edge = target_edge(settings.bond);
  s.emin = settings.low * s.edge;
  s.emax = settings.high * s.edge;
  s.area = area * s.factor * s.factor;
  s.longest_side = side * s.factor;
  s.expected_atoms = s.area / area_per_atom(settings.bond);
  return s;
}

void scale_mesh(TriMesh& mesh, double factor) {
  for (auto v : mesh.vertices()) mesh.set_point(v, mesh.point(v) * factor);
  mesh.update_normals();
}

nlohmann::json to_json(const StructureScale& s) {
  return {{"factor", s.factor}, {"edge", s.edge},         {"emin", s.emin},
          {"emax", s.emax},     {"area", s.area},         {"longest_side", s.longest_side},
          {"expected_atoms", s.expected_atoms}};
}

}  // namespace carbonmesh
