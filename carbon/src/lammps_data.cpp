#include <cmath>
#include "carbonmesh/carbon/lammps_data.hpp"

#include <fmt/format.h>
#include <fmt/os.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "carbonmesh/remesh/atomic_file.hpp"
#include "carbonmesh/remesh/error.hpp"

namespace carbonmesh {

int lammps_type(Element e) { return e == Element::H ? 2 : 1; }

void write_lammps_data(const CarbonStructure& s, const std::filesystem::path& file,
                       const LammpsDataSettings& settings) {
  const bool hydrogen = s.has_hydrogen();
  const int types = hydrogen ? 2 : 1;
  const Box box = vacuum_box(s.positions, settings.vacuum);
  const auto angles = settings.topology ? s.angles() : std::vector<AtomTriple>{};
  write_atomically(file, [&](const std::filesystem::path& tmp) {
    auto out = fmt::output_file(tmp.string());
    out.print("LAMMPS data file from carbonmesh: {} atoms ({} C, {} H), {} bonds, units metal, atom_style {}\n\n",
              s.atoms(), s.count(Element::C), s.count(Element::H), s.bonds.size(),
              settings.topology ? "full" : "atomic");
    out.print("{} atoms\n{} atom types\n", s.atoms(), types);
    if (settings.topology)
      out.print("{} bonds\n{} bond types\n{} angles\n{} angle types\n", s.bonds.size(), types, angles.size(), types);
    out.print("\n{:.8f} {:.8f} xlo xhi\n{:.8f} {:.8f} ylo yhi\n{:.8f} {:.8f} zlo zhi\n", box.lo[0], box.hi[0],
              box.lo[1], box.hi[1], box.lo[2], box.hi[2]);
    out.print("\nMasses\n\n1 {} # C\n", element_mass(Element::C));
    if (hydrogen) out.print("2 {} # H\n", element_mass(Element::H));
    out.print("\nAtoms # {}\n\n", settings.topology ? "full" : "atomic");
    for (std::size_t i = 0; i < s.atoms(); ++i) {
      const Vec3& p = s.positions[i];
      if (settings.topology)
        out.print("{} 1 {} 0.0 {:.8f} {:.8f} {:.8f}\n", i + 1, lammps_type(s.elements[i]), p[0], p[1], p[2]);
      else
        out.print("{} {} {:.8f} {:.8f} {:.8f}\n", i + 1, lammps_type(s.elements[i]), p[0], p[1], p[2]);
    }
    if (settings.topology) {
      auto has_h = [&](int a) { return s.elements[static_cast<std::size_t>(a)] == Element::H; };
      out.print("\nBonds\n\n");
      for (std::size_t k = 0; k < s.bonds.size(); ++k) {
        const auto& b = s.bonds[k];
        out.print("{} {} {} {}\n", k + 1, has_h(b[0]) || has_h(b[1]) ? 2 : 1, b[0] + 1, b[1] + 1);
      }
      out.print("\nAngles\n\n");
      for (std::size_t k = 0; k < angles.size(); ++k) {
        const auto& t = angles[k];
        out.print("{} {} {} {} {}\n", k + 1, has_h(t[0]) || has_h(t[1]) || has_h(t[2]) ? 2 : 1, t[0] + 1, t[1] + 1,
                  t[2] + 1);
      }
    }
    out.close();
  });
}

namespace {

std::string trim_comment(const std::string& line) {
  std::string s = line.substr(0, line.find('#'));
  const auto a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

bool is_section(const std::string& word) {
  static const char* names[] = {"Masses", "Atoms", "Bonds", "Angles", "Velocities", "Pair Coeffs",
                                "Bond Coeffs", "Angle Coeffs", "Dihedrals", "Impropers"};
  for (const char* n : names)
    if (word == n) return true;
  return false;
}

}  // namespace

LammpsData read_lammps_data(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(fmt::format("{}: cannot open", file.string()));
  LammpsData d;
  std::size_t atoms = 0, bonds = 0, angles = 0;
  std::string line, section;
  int number = 0;
  std::getline(in, line);  // title
  ++number;
  auto fail = [&](const std::string& what) {
    throw InputError(fmt::format("{}:{}: {}", file.string(), number, what));
  };
  while (std::getline(in, line)) {
    ++number;
    const std::string body = trim_comment(line);
    if (body.empty()) continue;
    if (is_section(body)) {
      section = body;
      if (section == "Atoms") {
        const auto hash = line.find('#');
        if (hash != std::string::npos) {
          std::istringstream style(line.substr(hash + 1));
          style >> d.atom_style;
        }
      }
      continue;
    }
    std::istringstream ls(body);
    if (section.empty()) {  // header
      double a = 0, b = 0;
      std::string w1, w2;
      if (body.find("xlo") != std::string::npos || body.find("ylo") != std::string::npos ||
          body.find("zlo") != std::string::npos) {
        if (!(ls >> a >> b >> w1)) fail("bad box line");
        const int k = w1 == "xlo" ? 0 : w1 == "ylo" ? 1 : 2;
        d.box.lo[k] = a;
        d.box.hi[k] = b;
        continue;
      }
      std::size_t n = 0;
      if (!(ls >> n >> w1)) fail("bad header line");
      ls >> w2;
      if (w1 == "atoms") atoms = n;
      else if (w1 == "bonds") bonds = n;
      else if (w1 == "angles") angles = n;
      else if (w1 == "atom" && w2 == "types") d.atom_types = static_cast<int>(n);
      else if (w1 == "bond" && w2 == "types") d.bond_types = static_cast<int>(n);
      else if (w1 == "angle" && w2 == "types") d.angle_types = static_cast<int>(n);
      continue;
    }
    std::vector<double> v;
    for (double x; ls >> x;) v.push_back(x);
    if (!ls.eof()) fail("not a number");
    // An id, type or atom index: a whole number in a sane range (fuzzing found casts of 1e300).
    auto whole = [&](double x) {
      if (!(x >= -1e9 && x <= 1e9) || x != std::floor(x)) fail("'" + std::to_string(x) + "' is not a valid id, type or index");
      return static_cast<int>(x);
    };
    if (section == "Masses") {
      if (v.size() != 2) fail("a Masses line needs type and mass");
      const int type_number = whole(v[0]);
      if (type_number < 1 || type_number > 1000) fail("bad atom type");
      const auto t = static_cast<std::size_t>(type_number);
      if (d.masses.size() < t) d.masses.resize(t, 0.0);
      d.masses[t - 1] = v[1];
    } else if (section == "Atoms") {
      // atomic: id type x y z [ix iy iz]; full: id mol type q x y z [ix iy iz]
      if (d.atom_style.empty()) d.atom_style = (v.size() == 7 || v.size() == 10) ? "full" : "atomic";
      const bool full = d.atom_style == "full";
      if (full && v.size() != 7 && v.size() != 10) fail("an atom_style full line needs id mol type q x y z");
      if (!full && v.size() != 5 && v.size() != 8) fail("an atom_style atomic line needs id type x y z");
      const std::size_t type = full ? 2 : 1, x = full ? 4 : 2;
      d.ids.push_back(whole(v[0]));
      d.types.push_back(whole(v[type]));
      d.positions.emplace_back(v[x], v[x + 1], v[x + 2]);
    } else if (section == "Bonds") {
      if (v.size() != 4) fail("a Bonds line needs id type atom atom");
      d.bonds.push_back({whole(v[1]), whole(v[2]), whole(v[3])});
    } else if (section == "Angles") {
      if (v.size() != 5) fail("an Angles line needs id type atom atom atom");
      d.angles.push_back({whole(v[1]), whole(v[2]), whole(v[3]), whole(v[4])});
    }
  }
  if (d.positions.size() != atoms)
    throw InputError(fmt::format("{}: header says {} atoms, the Atoms section has {}", file.string(), atoms,
                                 d.positions.size()));
  if (d.bonds.size() != bonds)
    throw InputError(fmt::format("{}: header says {} bonds, found {}", file.string(), bonds, d.bonds.size()));
  if (d.angles.size() != angles)
    throw InputError(fmt::format("{}: header says {} angles, found {}", file.string(), angles, d.angles.size()));
  return d;
}

}  // namespace carbonmesh
