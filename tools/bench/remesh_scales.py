#!/usr/bin/python3
"""The remeshing protocol of tools/bench/remesh.py on the seed-protocol models made larger: each model scaled by a few
factors about its centroid (mean input edge 2.25 times the factor) and remeshed into the same interval [1.2, 1.8] by
carbonmesh (the protocol) and by CGAL's isotropic_remeshing (target 1.5, 10 iterations), measured against the scaled
input as in the main table. A user who wants a larger nanostructure of the same shape gets this case: the input is
coarse against the bonds, its faces and creases span many remeshed edges, and there are more vertices per feature of
the input. Writes its section of docs/benchmarks.md.

Usage: tools/bench/remesh_scales.py [--build build] [--models DIR] [--only NAME ...] [--scales 2 3] [--repeat 3]
"""
import argparse
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, ".."))
from bench_common import machine_line, replace_section  # noqa: E402
from remesh import programs, protocol_and_peer, ratio_line, stats, turn_ratios  # noqa: E402
from unusual_input_table import read_off, write_off  # noqa: E402

ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
# armadillo and stanford-bunny at 3x have 0.8 and 0.6 million vertices (minutes a run): left out unless named.
DEFAULT_MODELS = ("bunny", "camelhead", "elephant", "fertility", "sphere")


def scaled(vertices, factor):
    """The vertices scaled by `factor` about their centroid."""
    n = max(1, len(vertices))
    c = [sum(v[k] for v in vertices) / n for k in range(3)]
    return [tuple(c[k] + factor * (v[k] - c[k]) for k in range(3)) for v in vertices]


def table(cli, peer, args, models, work):
    """The section's lines; the scaled inputs and the remeshes are written to `work`."""
    lines = ["## Remeshing: the same protocol on the models made larger", "",
             f"Machine: {machine_line()}. Each seed-protocol model scaled about its centroid by the factor given (its "
             "mean edge 2.25 times the factor), then remeshed into the same interval [1.2, 1.8] by the protocol and "
             "the CGAL peer of the first table and measured against the scaled input the same way (seconds: the "
             f"fastest of {args.repeat} runs, the two methods taking turns). This is the input of a larger "
             "nanostructure of the same shape: coarse against the bonds, each input face and crease spanning several "
             "remeshed edges. Written by tools/bench/remesh_scales.py.", "",
             "| model | scale | method | seconds | V | long + short | % regular | % Eval > 1 | Hausdorff max | "
             "Hausdorff RMS |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    ratios, turns = [], {}
    for model in models:
        vertices, faces = read_off(os.path.join(args.models, model + ".off"))
        for factor in args.scales:
            name = f"{model} {factor:g}x"
            src = os.path.join(work, f"{model}-{factor:g}.off")
            write_off(src, scaled(vertices, factor), faces, digits=17)
            ours = os.path.join(work, f"{model}-{factor:g}-ours.off")
            theirs = os.path.join(work, f"{model}-{factor:g}-cgal.off")
            (result, _), (peer_result, _) = protocol_and_peer(cli, peer, src, ours, theirs, args.repeat)
            for method, seconds, s in (("carbonmesh", result["seconds"], stats(cli, ours, src)),
                                       ("CGAL", peer_result["seconds"], stats(cli, theirs, src, repair=True))):
                e, v, h, t = s["edges"], s["valence"], s["hausdorff"], s["topology"]
                lines.append(f"| {model} | {factor:g} | {method} | {seconds:.2f} | {t['vertices']} | "
                             f"{e['long'] + e['short']} | {v['percent_regular']:.2f} | {v['percent_eval_gt1']:.2f} | "
                             f"{h['max']:.4f} | {h['rms']:.4f} |")
                print(lines[-1], flush=True)
            ratios.append((name, result["seconds"] / max(peer_result["seconds"], 1e-9)))
            turns[name] = turn_ratios(result, peer_result)
    lines += ["", ratio_line(ratios, turns), ""]
    return lines


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--models", default=os.path.join(ROOT, "..", "shared", "models", "seed-protocol"))
    ap.add_argument("--only", nargs="*", help=f"model names (default: {' '.join(DEFAULT_MODELS)})")
    ap.add_argument("--scales", nargs="*", type=float, default=[2.0, 3.0], help="scale factors")
    ap.add_argument("--repeat", type=int, default=3, help="runs of each method; the table shows the fastest")
    args = ap.parse_args()
    if not os.path.isdir(args.models):
        print(f"remesh scales benchmark skipped: {args.models} is missing (the shared models are needed)")
        return 0
    if any(f <= 0 for f in args.scales):
        print("remesh scales benchmark: --scales must be positive", file=sys.stderr)
        return 2
    cli, peer = programs(args.build)
    available = sorted(f[:-4] for f in os.listdir(args.models) if f.endswith(".off"))
    wanted = args.only if args.only else DEFAULT_MODELS
    models = [m for m in available if m in wanted]
    with tempfile.TemporaryDirectory(prefix="carbonmesh-scales-") as work:
        lines = table(cli, peer, args, models, work)
    replace_section(os.path.join(ROOT, "docs", "benchmarks.md"), "remesh-scales", "\n".join(lines))
    print("wrote docs/benchmarks.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
