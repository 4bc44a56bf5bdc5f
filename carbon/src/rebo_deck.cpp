#include "carbonmesh/carbon/rebo_deck.hpp"

#include <fmt/format.h>
#include <fmt/os.h>

#include <stdexcept>

#include "carbonmesh/remesh/atomic_file.hpp"

namespace carbonmesh {

std::string rebo_deck(const ReboDeckSettings& s) {
  if (!(s.temperature > 0) || !(s.timestep > 0) || s.steps < 0 || s.thermo_every <= 0 || s.dump_every <= 0)
    throw std::invalid_argument("rebo_deck: temperature, timestep, thermo and dump intervals must be positive");
  long dump_every = s.dump_every;
  if (s.steps > 0)
    while (s.steps % dump_every != 0) --dump_every;
  std::string d;
  auto line = [&d](const std::string& text) { d += text + "\n"; };
  line("# REBO2 (Brenner 2002) molecular dynamics of a carbonmesh structure.");
  line("# Serial:   lmp -in in.rebo");
  line(fmt::format("# Parallel: mpirun -np {} lmp -in in.rebo", s.mpi_ranks));
  line("");
  line("units           metal");
  // Shrink-wrapped, but never smaller than the data file's box (the atoms plus vacuum): a flat sheet has no extent
  // across its plane, and a box wrapped to it alone is too thin for LAMMPS's neighbour bins.
  line("boundary        m m m");
  line(fmt::format("atom_style      {}", s.topology ? "full" : "atomic"));
  line(fmt::format("read_data       {}", s.data_file));
  if (s.topology) {
    line("# Bonds and angles are carried along for analysis; REBO finds its own neighbours, so they have zero");
    line("# styles and the special-bond weights stay 1 (bonded pairs must remain in the REBO neighbour list).");
    line("bond_style      zero");
    line("bond_coeff      *");
    line("angle_style     zero");
    line("angle_coeff     *");
    line("special_bonds   lj/coul 1.0 1.0 1.0");
  }
  line("");
  line("pair_style      rebo");
  line(fmt::format("pair_coeff      * * CH.rebo C{}", s.hydrogen ? " H" : ""));
  line("neighbor        2.0 bin");
  line("neigh_modify    delay 0 every 1 check yes");
  line("");
  line("thermo          " + std::to_string(s.thermo_every));
  line("thermo_style    custom step temp pe ke etotal press");
  line(fmt::format("dump            traj all custom {} {} id type x y z", dump_every, s.dump_file));
  line("dump_modify     traj sort id");
  line("");
  line("# Relax the geometry at 0 K.");
  line("min_style       cg");
  line(fmt::format("minimize        1.0e-10 1.0e-8 {} {}", s.minimize_iterations, 10 * s.minimize_iterations));
  line("reset_timestep  0");
  line("");
  line(fmt::format("# NVT at {} K for {} steps of {} ps.", s.temperature, s.steps, s.timestep));
  line(fmt::format("velocity        all create {} {} mom yes rot yes dist gaussian", s.temperature, s.seed));
  line(fmt::format("fix             nvt all nvt temp {} {} {}", s.temperature, s.temperature, 100 * s.timestep));
  line(fmt::format("timestep        {}", s.timestep));
  line(fmt::format("run             {}", s.steps));
  line(fmt::format("write_data      {}", s.final_data_file));
  return d;
}

void write_rebo_deck(const ReboDeckSettings& settings, const std::filesystem::path& file) {
  const std::string text = rebo_deck(settings);
  write_atomically(file, [&](const std::filesystem::path& tmp) {
    auto out = fmt::output_file(tmp.string());
    out.print("{}", text);
    out.close();
  });
}

}  // namespace carbonmesh
