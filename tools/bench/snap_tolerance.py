#!/usr/bin/python3
"""The snap tolerance study: the remeshing protocol of tools/bench/remesh.py with `--snap-tolerance` set to a few
fractions of emin, on the seed-protocol models and on the generated shapes of tools/bench/remesh_shapes.py (scaled
to mean edge 2.25 the same way). The tolerance decides which input points count as cut off by the remeshed surface:
the feature snap, the flips toward the input, the caps and the minimax fit work on the points and faces farther than
it. Per input and tolerance: seconds (the fastest of --repeat runs, the tolerances taking turns), edges outside,
% regular and the Hausdorff figures of `carbonmesh stats --ref`. Writes its section of docs/benchmarks.md.

Usage: tools/bench/snap_tolerance.py [--build build] [--models DIR] [--tolerances 0.25 0.33 0.42] [--repeat 3]
       [--no-shapes]
"""
import argparse
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, ".."))
from bench_common import machine_line, replace_section  # noqa: E402
from remesh import PROTOCOL, fastest_of, stats  # noqa: E402
from remesh_shapes import scaled_shape_files  # noqa: E402

ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))


def inputs(args, cli, work):
    """(name, path) of every input: the seed-protocol models (when present), then the generated shapes."""
    out = []
    if os.path.isdir(args.models):
        out += [(m[:-4], os.path.join(args.models, m)) for m in sorted(os.listdir(args.models)) if m.endswith(".off")]
    else:
        print(f"{args.models} is missing: the seed-protocol models are skipped")
    if not args.no_shapes:
        out += list(scaled_shape_files(cli, work))
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--models", default=os.path.join(ROOT, "..", "shared", "models", "seed-protocol"))
    ap.add_argument("--tolerances", nargs="+", default=["0.25", "0.33", "0.42"])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--no-shapes", action="store_true", help="only the seed-protocol models")
    args = ap.parse_args()
    cli = os.path.join(args.build, "tools", "carbonmesh", "carbonmesh")
    work = tempfile.mkdtemp(prefix="carbonmesh-snap-tolerance-")
    lines = ["## Remeshing: the snap tolerance", "",
             f"Machine: {machine_line()}. The protocol of the first table (`carbonmesh remesh IN OUT` with its "
             "parameters) with `--snap-tolerance t`: the input points and faces farther than t emin from the "
             "remeshed surface are what the feature snap, the flips toward the input, the caps and the minimax fit "
             "work on. Inputs: the seed-protocol models and the generated shapes of the table above. Seconds: the "
             f"fastest of {args.repeat} runs, the tolerances taking turns. Hausdorff: `carbonmesh stats --ref`, as "
             "in the first table. Written by tools/bench/snap_tolerance.py.", "",
             "| input | tolerance (x emin) | seconds | long | short | % regular | Hausdorff max | Hausdorff RMS |",
             "|---|---|---|---|---|---|---|---|"]
    totals = {t: 0.0 for t in args.tolerances}
    for name, src in inputs(args, cli, work):
        outs = [os.path.join(work, f"out-{t}.off") for t in args.tolerances]
        runs = fastest_of([[cli, "-q", "remesh", src, out, "--json", "--snap-tolerance", t] + PROTOCOL
                           for t, out in zip(args.tolerances, outs)], args.repeat)
        for t, out, (result, _) in zip(args.tolerances, outs, runs):
            s = stats(cli, out, src)
            h = s["hausdorff"]
            totals[t] += result["seconds"]
            lines.append(f"| {name} | {t} | {result['seconds']:.2f} | {result['long']} | {result['short']} | "
                         f"{result['percent_regular']:.2f} | {h['max']:.4f} | {h['rms']:.4f} |")
            print(lines[-1], flush=True)
    lines += ["", "Seconds summed over the inputs: " +
              ", ".join(f"tolerance {t}: {s:.2f}" for t, s in totals.items()) + "."]
    replace_section(os.path.join(ROOT, "docs", "benchmarks.md"), "remesh-snap-tolerance", "\n".join(lines))
    print("wrote docs/benchmarks.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
