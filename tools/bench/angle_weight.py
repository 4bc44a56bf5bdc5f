#!/usr/bin/python3
"""Angle-weight study (a benchmark, not a test): `carbonmesh build` with --angle-weight w_a for several w_a on the
built-in sphere (960 atoms) and, where ../shared/models is present, bunny and fertility (20000 atoms). For each:
bond and angle statistics after the dual optimisation (summary.json), the shares of angles below 90 and above
150 degrees, the optimisation's seconds and iterations, and the REBO2 energy per atom of the written structure
(LAMMPS single point, `run 0`, with the Debian `lmp`; the lower, the nearer the structure is to what REBO2
relaxes it to). Writes its section of docs/benchmarks.md.

Usage: tools/bench/angle_weight.py [--build build] [--models DIR] [--weights 0.01 0.02 0.05 0.1 0.2]
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_common import machine_line, replace_section  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))

SINGLE_POINT = """units metal
boundary s s s
atom_style atomic
read_data structure.data
pair_style rebo
pair_coeff * * CH.rebo C{h}
thermo_style custom step pe atoms
run 0
variable e equal pe/atoms
print "ENERGY_PER_ATOM ${{e}}"
"""


def angle_tails(pdb):
    """Shares (percent) of bond angles below 90 and above 150 degrees, from the PDB's atoms and CONECT records."""
    pos, neighbours = {}, {}
    with open(pdb) as f:
        for line in f:
            if line.startswith(("ATOM", "HETATM")):
                pos[int(line[6:11])] = (float(line[30:38]), float(line[38:46]), float(line[46:54]))
            elif line.startswith("CONECT"):
                ids = [int(line[k:k + 5]) for k in range(6, len(line.rstrip()), 5)]
                for j in ids[1:]:
                    neighbours.setdefault(ids[0], set()).add(j)
                    neighbours.setdefault(j, set()).add(ids[0])
    below = above = count = 0
    for c, ns in neighbours.items():
        ns = sorted(ns)
        for a in range(len(ns)):
            for b in range(a + 1, len(ns)):
                u = [pos[ns[a]][k] - pos[c][k] for k in range(3)]
                v = [pos[ns[b]][k] - pos[c][k] for k in range(3)]
                cosine = sum(u[k] * v[k] for k in range(3)) / math.sqrt(sum(x * x for x in u) * sum(x * x for x in v))
                angle = math.degrees(math.acos(max(-1.0, min(1.0, cosine))))
                count += 1
                below += angle < 90
                above += angle > 150
    return 100.0 * below / max(count, 1), 100.0 * above / max(count, 1)


def rebo_energy(folder, hydrogen):
    """REBO2 energy per atom (eV) of folder/structure.data, or None without lmp."""
    lmp = shutil.which("lmp")
    if not lmp:
        return None
    with open(os.path.join(folder, "in.single"), "w") as f:
        f.write(SINGLE_POINT.format(h=" H" if hydrogen else ""))
    out = subprocess.run([lmp, "-in", "in.single", "-log", "none"], cwd=folder, capture_output=True, text=True)
    for line in out.stdout.splitlines():
        if line.startswith("ENERGY_PER_ATOM"):
            return float(line.split()[1])
    sys.stderr.write(out.stdout[-2000:] + out.stderr[-2000:])
    raise RuntimeError("lmp gave no energy in " + folder)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--models", default=os.path.join(ROOT, "..", "shared", "models"))
    parser.add_argument("--weights", type=float, nargs="+", default=[0.01, 0.02, 0.05, 0.1, 0.2])
    parser.add_argument("--doc", default=os.path.join(ROOT, "docs", "benchmarks.md"))
    args = parser.parse_args()
    cli = os.path.join(args.build, "tools", "carbonmesh", "carbonmesh")
    cases = [("sphere (built-in)", None, 960)]
    for name in ("bunny", "fertility"):
        path = os.path.join(args.models, name + ".off")
        if os.path.exists(path):
            cases.append((name, path, 20000))
        else:
            print(f"skipping {name}: {path} not found (../shared/models is missing)", file=sys.stderr)
    rows = []
    load = os.getloadavg()[0]
    with tempfile.TemporaryDirectory() as tmp:
        for name, path, atoms in cases:
            for w in args.weights:
                out = os.path.join(tmp, f"{name.split()[0]}-{w}")
                command = [cli, "-q", "build"] + ([path] if path else []) + [
                    "-o", out, "--atoms", str(atoms), "--angle-weight", str(w), "--no-report"]
                subprocess.run(command, check=True, capture_output=True)
                with open(os.path.join(out, "summary.json")) as f:
                    s = json.load(f)
                o = s["optimization"]
                b, a = o["bonds_after"], o["angles_after_deg"]
                below, above = angle_tails(os.path.join(out, "structure.pdb"))
                energy = rebo_energy(out, s.get("hydrogen_atoms", 0) > 0)
                e = f"{energy:.4f}" if energy is not None else "n/a (no lmp)"
                rows.append(f"| {name} | {s['atoms']} | {w:g} | {b['min']:.4f} / {b['max']:.4f} / {b['std']:.4f} | "
                            f"{a['min']:.1f} / {a['max']:.1f} / {a['std']:.2f} | {below:.3f} / {above:.3f} | "
                            f"{o['iterations']} | {s['seconds']['optimize']:.2f} | {e} |")
                print(rows[-1], flush=True)
    lines = ["## Dual optimisation: angle weight w_a (tools/bench/angle_weight.py)", "",
             f"Machine: {machine_line()}, load average {load:.1f} at the start (optimize seconds are wall clock). `carbonmesh build [IN] --atoms N --angle-weight w_a --no-report` (defaults "
             "otherwise). Bonds (A) and angles (degrees) after the optimisation; angle tails: percent of bond angles "
             "below 90 / above 150 degrees; REBO2 E: energy per atom (eV) of the written structure.data, LAMMPS "
             "single point (`run 0`, pair_style rebo, CH.rebo): lower is nearer to the structure REBO2 relaxes to.",
             "",
             "| model | atoms | w_a | bonds min / max / std | angles min / max / std | % angles < 90 / > 150 | "
             "L-BFGS iterations | optimize s | REBO2 E eV/atom |",
             "|---|---|---|---|---|---|---|---|---|"] + rows
    replace_section(args.doc, "bench-angle-weight", "\n".join(lines))
    print(f"wrote {args.doc}")


if __name__ == "__main__":
    main()
