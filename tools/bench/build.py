#!/usr/bin/python3
"""End-to-end benchmark (not a test): `carbonmesh build` of the built-in sphere and of fertility
(../shared/models/fertility.off) at --atoms 10000, 100000 and 1000000; seconds per stage (summary.json), wall
seconds and peak RSS of the whole process (/usr/bin/time), atoms, bond statistics after the dual optimisation.
Writes its section of docs/benchmarks.md. Goal (issue 5): 1M atoms end to end in <= 60 s and <= 4 GB.

Usage: tools/bench/build.py [--build build] [--models DIR] [--atoms 10000 100000 1000000] [--only sphere fertility]
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_common import machine_line, replace_section  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
STAGES = ["load", "scale", "remesh", "dual", "coarse optimize", "optimize", "write"]


def timed_with_limit(command, limit):
    """Runs a command under /usr/bin/time; returns (wall seconds, peak RSS in MiB), or None after `limit` s."""
    with tempfile.NamedTemporaryFile(mode="r", suffix=".time") as t:
        full = ["/usr/bin/time", "-f", "%e %M", "-o", t.name] + [str(c) for c in command]
        try:
            result = subprocess.run(full, capture_output=True, text=True, timeout=limit)
        except subprocess.TimeoutExpired:
            return None
        if result.returncode != 0:
            sys.stderr.write(result.stderr)
            raise RuntimeError("failed: " + " ".join(str(c) for c in command))
        seconds, kib = t.read().split()[-2:]
    return float(seconds), int(kib) / 1024.0


def git_head():
    try:
        return subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                              text=True).stdout.strip() or "unknown"
    except OSError:
        return "unknown"


def load_average():
    try:
        return open("/proc/loadavg").read().split()[0]
    except OSError:
        return "?"


def row(model, atoms, wall, rss, s):
    sec, opt = s["seconds"], s["optimization"]
    b = opt["bonds_after"]
    rings = " ".join(f"{k}:{v}" for k, v in sorted(s["rings_by_size"].items(), key=lambda kv: int(kv[0])))
    per_million = wall / s["atoms"] * 1e6
    return (f"| {model} | {atoms} | {s['atoms']} | " + " | ".join(f"{sec.get(st, 0):.2f}" for st in STAGES) +
            f" | {sec['total']:.2f} | {wall:.2f} | {per_million:.1f} | {rss:.0f} | {opt['iterations']} | "
            f"{b['min']:.4f} / {b['mean']:.4f} / {b['std']:.4f} / {b['max']:.4f} | "
            f"{s['percent_three_bonds']:.2f} | {rings} |")


def write(lines, loads, notes):
    text = lines + ["", f"1-minute load average before and after each run: {', '.join(loads)} (2 cores shared "
                    "with other builds and benchmarks: wall times are inflated when the load is above 2)."]
    if notes:
        text += [""] + notes
    replace_section(os.path.join(ROOT, "docs", "benchmarks.md"), "build", "\n".join(text))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--models", default=os.path.join(ROOT, "..", "shared", "models"))
    ap.add_argument("--atoms", nargs="*", type=int, default=[10000, 100000, 1000000])
    ap.add_argument("--only", nargs="*")
    ap.add_argument("--timeout", type=float, default=1800, help="seconds per run before it is stopped")
    args = ap.parse_args()
    cli = os.path.join(args.build, "tools", "carbonmesh", "carbonmesh")
    if not os.path.exists(cli):
        print(f"build benchmark: {cli} is missing (build first: cmake --build {args.build})")
        return 1
    cases = [("sphere", None)]
    fertility = os.path.join(args.models, "fertility.off")
    notes = []
    if os.path.exists(fertility):
        cases.append(("fertility", fertility))
    else:
        msg = f"fertility skipped: {fertility} is missing (the shared models are needed)"
        print(msg)
        notes.append(msg)
    if args.only:
        cases = [c for c in cases if c[0] in args.only]
    work = tempfile.mkdtemp(prefix="carbonmesh-bench-build-")
    loads = [load_average()]
    lines = ["## carbonmesh build end to end (tools/bench/build.py)", "",
             f"Machine: {machine_line()}; HEAD {git_head()}. `carbonmesh build [fertility.off] -o DIR --atoms N "
             "--no-report` (defaults otherwise: remesh to sqrt(3) 1.42 [0.8, 1.2], dual, dual optimisation, "
             "structure files). Stage seconds are wall clock from summary.json (`seconds`); wall and peak RSS "
             "are the whole process under /usr/bin/time; s/M atoms = wall seconds per million atoms. Bonds "
             "after the dual optimisation, Angstrom. Goal: 1M atoms in <= 60 s and <= 4 GB.", "",
             "| model | --atoms | atoms | " + " | ".join(STAGES) + " | total | wall | s/M atoms | peak RSS MiB | "
             "L-BFGS iterations | bonds min / mean / std / max | % three bonds | rings |",
             "|---|" + "---|" * (len(STAGES) + 10)]
    for name, path in cases:
        for atoms in args.atoms:
            out = os.path.join(work, f"{name}-{atoms}")
            command = [cli, "-q", "build"] + ([path] if path else []) + ["-o", out, "--atoms", str(atoms),
                                                                       "--no-report"]
            measured = timed_with_limit(command, args.timeout)
            if measured is None:
                lines.append(f"| {name} | {atoms} | stopped after {args.timeout:.0f} s wall |" + " |" * 14)
            else:
                wall, rss = measured
                with open(os.path.join(out, "summary.json")) as f:
                    summary = json.load(f)
                lines.append(row(name, atoms, wall, rss, summary))
            print(lines[-1], flush=True)
            loads.append(load_average())
            shutil.rmtree(out, ignore_errors=True)
            write(lines, loads, notes)  # after every run, so a long run keeps the ones before it
    shutil.rmtree(work, ignore_errors=True)
    print("wrote docs/benchmarks.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
