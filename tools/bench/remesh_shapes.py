#!/usr/bin/python3
"""The remeshing benchmark's protocol on shapes that are not among the shared models: spheres (plain, noisy,
bumpy, squashed), tori, a helix, a trefoil knot, a capsule, a cube, a star prism and three bordered sheets,
generated here (`carbonmesh shape` or a few lines of Python), each scaled so that its mean edge is 2.25 like
../shared/models/seed-protocol. carbonmesh (the protocol of tools/bench/remesh.py) and CGAL's isotropic_remeshing
(target 1.5, 10 iterations, borders protected) run on the same inputs. Writes its section of docs/benchmarks.md.

Usage: tools/bench/remesh_shapes.py [--build build] [--only NAME ...] [--repeat 3]
"""
import argparse
import math
import os
import random
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, ".."))
from bench_common import machine_line, replace_section  # noqa: E402
from remesh import header, programs, protocol_and_peer, ratio_line, row, stats  # noqa: E402
from unusual_input_table import grid, read_off, star_prism, write_off  # noqa: E402

ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
MEAN_EDGE = 2.25  # the seed protocol's


def mean_edge(vertices, faces):
    total = sum(math.dist(vertices[a], vertices[b])
                for t in faces for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])))
    return total / (3 * len(faces))


def grid_cube(n):
    """A unit cube with an n x n grid of squares (two triangles each) on every face: 90-degree edges."""
    index, vertices, faces = {}, [], []

    def vertex(p):
        key = tuple(round(c * n) for c in p)
        if key not in index:
            index[key] = len(vertices)
            vertices.append(p)
        return index[key]

    sides = [((0, 0, 0), (1, 0, 0), (0, 1, 0)), ((0, 0, 1), (0, 1, 0), (1, 0, 0)), ((0, 0, 0), (0, 1, 0), (0, 0, 1)),
             ((1, 0, 0), (0, 0, 1), (0, 1, 0)), ((0, 0, 0), (0, 0, 1), (1, 0, 0)), ((0, 1, 0), (1, 0, 0), (0, 0, 1))]
    for o, a, b in sides:  # a x b points outwards
        at = lambda i, j: vertex(tuple(o[k] + a[k] * i / n + b[k] * j / n for k in range(3)))  # noqa: E731
        for i in range(n):
            for j in range(n):
                q = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]
                faces += [(q[0], q[1], q[2]), (q[0], q[2], q[3])]
    return vertices, faces


def trefoil(nu=200, nv=16):
    """A tube around the trefoil knot (sin t + 2 sin 2t, cos t - 2 cos 2t, -sin 3t), times 3, tube radius 0.48."""
    tau = 2 * math.pi

    def curve(t):
        return (math.sin(t) + 2 * math.sin(2 * t), math.cos(t) - 2 * math.cos(2 * t), -math.sin(3 * t))

    def point(s, t):
        u, h = tau * s, 1e-4
        p, q = curve(u), curve(u + h)
        d = [(q[i] - p[i]) / h for i in range(3)]
        length = math.sqrt(sum(x * x for x in d))
        d = [x / length for x in d]
        n1 = [-d[1], d[0], 0.0]  # (0, 0, 1) x d: the knot's tangent is never vertical
        length = math.sqrt(sum(x * x for x in n1))
        n1 = [x / length for x in n1]
        n2 = [d[1] * n1[2] - d[2] * n1[1], d[2] * n1[0] - d[0] * n1[2], d[0] * n1[1] - d[1] * n1[0]]
        w = tau * t
        return tuple(3 * p[i] + 0.48 * (math.cos(w) * n1[i] + math.sin(w) * n2[i]) for i in range(3))

    vertices, faces = grid(nu, nv, point, closed_u=True)
    # Close the tube: the column t = 1 is the column t = 0.
    last = {i * (nv + 1) + nv: i * (nv + 1) for i in range(nu)}
    faces = [tuple(last.get(x, x) for x in t) for t in faces]
    used = sorted({x for t in faces for x in t})
    new = {u: k for k, u in enumerate(used)}
    return [vertices[u] for u in used], [tuple(new[x] for x in t) for t in faces]


def make_shapes(cli, folder):
    def shape(*args):
        path = os.path.join(folder, "shape.off")
        subprocess.run([cli, "-q", "shape", *args, "-o", path], check=True, capture_output=True)
        return read_off(path)

    tau = 2 * math.pi
    ico4 = shape("sphere", "--subdivisions", "4")
    v, f = ico4
    rng = random.Random(3)
    return [
        ("icosphere, 1280 faces", shape("sphere", "--subdivisions", "3")),
        ("icosphere, 5120 faces", ico4),
        ("icosphere, 2% radial noise", ([tuple(x * (1 + 0.02 * g) for x in p) for p, g in
                                         ((p, rng.gauss(0, 1)) for p in v)], f)),
        ("bumpy sphere (15% waves)", ([tuple(x * (1 + 0.15 * math.sin(0.3 * math.pi * p[0]) *
                                                 math.cos(0.2 * math.pi * p[1])) for x in p) for p in v], f)),
        ("ellipsoid 10:1", ([(5 * x, 0.5 * y, 0.5 * z) for x, y, z in v], f)),
        ("flat disc 20:1", ([(x, y, 0.05 * z) for x, y, z in v], f)),
        ("torus 10 / 4", shape("torus", "--major", "10", "--minor", "4")),
        ("torus 10 / 1.5", shape("torus", "--major", "10", "--minor", "1.5")),
        ("helix, 3 turns", shape("helix", "--radius", "6", "--tube-radius", "2", "--pitch", "8", "--turns", "3")),
        ("trefoil knot tube", trefoil()),
        ("capsule", shape("capsule", "--radius", "4", "--length", "20")),
        ("cube (10 x 10 grid a side)", grid_cube(10)),
        ("five-pointed star prism", star_prism()),
        ("open tube (two borders)", grid(40, 60, lambda s, t: (5 * math.cos(tau * s), 5 * math.sin(tau * s), 30 * t),
                                         True)),
        ("annulus (two borders)", grid(60, 30, lambda s, t: (20 * (0.05 + 0.95 * t) * math.cos(tau * s),
                                                             20 * (0.05 + 0.95 * t) * math.sin(tau * s), 0.0), True)),
        ("saddle (one border)", grid(40, 40, lambda s, t: (30 * s - 15, 30 * t - 15,
                                                           ((30 * s - 15) ** 2 - (30 * t - 15) ** 2) / 40))),
    ]


def scaled_shape_files(cli, work):
    """(name, path) of every shape of make_shapes, written to `work` as OFF scaled to the mean edge MEAN_EDGE."""
    for k, (name, (vertices, faces)) in enumerate(make_shapes(cli, work)):
        scale = MEAN_EDGE / mean_edge(vertices, faces)
        path = os.path.join(work, f"shape{k}.off")
        write_off(path, [tuple(scale * x for x in p) for p in vertices], faces)
        yield name, path


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--only", nargs="*", help="shape names (the table's first column) to run")
    ap.add_argument("--repeat", type=int, default=3, help="runs of each method per shape; the table shows the fastest")
    args = ap.parse_args()
    cli, peer = programs(args.build)
    work = tempfile.mkdtemp(prefix="carbonmesh-shapes-")
    lines = ["## Remeshing: the same protocol on generated shapes", "",
             f"Machine: {machine_line()}. Shapes that are not among the shared models, generated by "
             "tools/bench/remesh_shapes.py and scaled so that their mean edge is 2.25; then the protocol and the "
             f"CGAL peer of the table above, measured the same way (seconds: the fastest of {args.repeat} runs, the "
             "two methods taking turns). The star prism at this scale is 5.6 x 5.9 x 1.9, its tips narrower than "
             "emin.", ""] + header("shape")
    ratios = []
    for name, src in scaled_shape_files(cli, work):
        if args.only and name not in args.only:
            continue
        ours = src[:-4] + "-out.off"
        theirs = src[:-4] + "-cgal.off"
        (result, rss), (peer_result, peer_rss) = protocol_and_peer(cli, peer, src, ours, theirs, args.repeat)
        lines.append(row(name, "carbonmesh", result["seconds"], rss, stats(cli, ours, src), result["iterations"]))
        lines.append(row(name, "CGAL", peer_result["seconds"], peer_rss, stats(cli, theirs, src, repair=True), 10))
        if peer_result["seconds"] >= 0.005:  # not to a time below the clock's resolution
            ratios.append((name, result["seconds"] / peer_result["seconds"]))
        print(lines[-2] + "\n" + lines[-1], flush=True)
    lines += ["", ratio_line(ratios)]
    replace_section(os.path.join(ROOT, "docs", "benchmarks.md"), "remesh-shapes", "\n".join(lines))
    print("wrote docs/benchmarks.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
