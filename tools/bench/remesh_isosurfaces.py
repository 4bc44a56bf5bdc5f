#!/usr/bin/python3
"""The remeshing benchmark's protocol on isosurfaces: implicit surfaces (tori joined into genus 2 and 3, a bumpy
blob, a rounded cube, a gyroid and a Schwarz P surface clipped by a box) triangulated by marching tetrahedra, the
way a CT scan or an implicit model reaches a user: slivers with angles down to hundredths of a degree, vertices on
the grid's edges, creases where tori meet, borders where the box cuts. Each is scaled so that its mean edge is 2.25
like ../shared/models/seed-protocol; then carbonmesh (the protocol of tools/bench/remesh.py) and CGAL's
isotropic_remeshing (target 1.5, 10 iterations, borders protected) run on the same inputs. Writes its section of
docs/benchmarks.md. Needs numpy (python3-numpy, in scripts/bootstrap).

Usage: tools/bench/remesh_isosurfaces.py [--build build] [--only NAME ...] [--repeat 2]
"""
import argparse
import os
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, ".."))
from bench_common import machine_line, replace_section  # noqa: E402
from remesh import header, programs, protocol_and_peer, ratio_line, row, stats  # noqa: E402
from unusual_input_table import read_off, write_off  # noqa: E402

ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
MEAN_EDGE = 2.25  # the seed protocol's
CORNERS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
TETRAHEDRA = [(0, 1, 2, 6), (0, 2, 3, 6), (0, 3, 7, 6), (0, 7, 4, 6), (0, 4, 5, 6), (0, 5, 1, 6)]  # around 0-6


def marching_tetrahedra(f, lo, hi, n):
    """The surface f = 0 over the grid of n^3 points on [lo, hi]^3 (shifted by 0.0123 so that no grid point is on
    it), each cube cut into 6 tetrahedra around its diagonal; vertices where f changes sign along a tetrahedron's
    edge, shared by the tetrahedra around that edge. Faces oriented with f rising outwards."""
    xs = np.linspace(lo, hi, n) + 0.0123
    x, y, z = np.meshgrid(xs, xs, xs, indexing="ij")
    values = f(x, y, z).ravel()
    points = np.stack([x, y, z], -1).reshape(-1, 3)
    inside = (values < 0).reshape(n, n, n)
    any_inside = np.zeros((n - 1,) * 3, bool)
    all_inside = np.ones((n - 1,) * 3, bool)
    for c in CORNERS:
        s = inside[c[0]:n - 1 + c[0], c[1]:n - 1 + c[1], c[2]:n - 1 + c[2]]
        any_inside |= s
        all_inside &= s
    index, vertices, faces = {}, [], []

    def vertex(a, b):
        key = (a, b) if a < b else (b, a)
        if key not in index:
            t = min(max(values[a] / (values[a] - values[b]), 1e-6), 1 - 1e-6)  # never on a grid point
            index[key] = len(vertices)
            vertices.append(points[a] + t * (points[b] - points[a]))
        return index[key]

    for i, j, k in zip(*np.nonzero(any_inside & ~all_inside)):
        cube = [((i + c[0]) * n + j + c[1]) * n + k + c[2] for c in CORNERS]
        for tet in TETRAHEDRA:
            ids = [cube[a] for a in tet]
            neg = [v for v in ids if values[v] < 0]
            pos = [v for v in ids if values[v] >= 0]
            if not neg or not pos:
                continue
            if len(neg) == 1 or len(pos) == 1:
                one, rest = (neg[0], pos) if len(neg) == 1 else (pos[0], neg)
                triangles = [[vertex(one, r) for r in rest]]
            else:
                q = [vertex(neg[0], pos[0]), vertex(neg[0], pos[1]), vertex(neg[1], pos[1]), vertex(neg[1], pos[0])]
                triangles = [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]
            outwards = points[pos].mean(0) - points[neg].mean(0)
            for t in triangles:
                p0, p1, p2 = (vertices[v] for v in t)
                if np.dot(np.cross(p1 - p0, p2 - p0), outwards) < 0:
                    t = [t[0], t[2], t[1]]
                faces.append(tuple(t))
    return np.array(vertices), faces


def torus(x, y, z, cx, cy, major, minor):
    return np.sqrt((np.sqrt((x - cx) ** 2 + (y - cy) ** 2) - major) ** 2 + z ** 2) - minor


# (name, f, lo, hi, grid points a side)
SHAPES = [
    ("two tori joined (genus 2)",
     lambda x, y, z: np.minimum(torus(x, y, z, -3, 0, 3, 1.1), torus(x, y, z, 3, 0, 3, 1.1)), -8, 8, 60),
    ("three tori joined (genus 3)",
     lambda x, y, z: np.minimum(np.minimum(torus(x, y, z, -3, 0, 2.6, 1), torus(x, y, z, 3, 0, 2.6, 1)),
                                torus(x, y, z, 0, 5.2, 2.6, 1)), -8, 9.5, 64),
    ("bumpy blob", lambda x, y, z: np.sqrt(x ** 2 + y ** 2 + z ** 2) - 5 - 0.8 * np.sin(2 * x) * np.sin(2 * y) *
     np.sin(1.5 * z), -8, 8, 56),
    ("rounded cube", lambda x, y, z: (x ** 8 + y ** 8 + z ** 8) ** 0.125 - 5, -7, 7, 48),
    ("gyroid, one period box (borders)",
     lambda x, y, z: np.sin(x) * np.cos(y) + np.sin(y) * np.cos(z) + np.sin(z) * np.cos(x), 0, 2 * np.pi, 50),
    ("Schwarz P, 2 x 2 x 2 cells (24 borders)", lambda x, y, z: np.cos(x) + np.cos(y) + np.cos(z),
     -np.pi, 3 * np.pi, 60),
]


def shape_files(work, only):
    """(name, path) of every shape, written to `work` as OFF scaled to the mean edge MEAN_EDGE."""
    for k, (name, f, lo, hi, n) in enumerate(SHAPES):
        if only and name not in only:
            continue
        vertices, faces = marching_tetrahedra(f, lo, hi, n)
        edges = {(min(a, b), max(a, b)) for t in faces for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0]))}
        a, b = np.array(list(edges)).T
        scale = MEAN_EDGE / np.linalg.norm(vertices[a] - vertices[b], axis=1).mean()
        path = os.path.join(work, f"isosurface{k}.off")
        write_off(path, [tuple(scale * p) for p in vertices], faces, digits=17)
        yield name, path


def without_small_components(src, dst, min_area):
    """Writes `src` to `dst` without the components (by shared vertices) of less area than `min_area`, but the
    largest: the surface `remesh` keeps of it (tools/carbonmesh/cmd_remesh.cpp)."""
    vertices, faces = (np.array(x) for x in read_off(src))
    parent = np.arange(len(vertices))

    def find(v):
        while parent[v] != v:
            parent[v] = parent[parent[v]]
            v = parent[v]
        return v

    for a, b, c in faces:
        parent[find(a)] = find(b)
        parent[find(b)] = find(c)
    roots = np.array([find(t[0]) for t in faces])
    p = vertices[faces]
    areas = np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1) / 2
    total = {r: areas[roots == r].sum() for r in set(roots.tolist())}
    largest = max(total, key=total.get)
    keep = [t for t, r in zip(faces, roots) if r == largest or total[r] >= min_area]
    used = sorted({int(v) for t in keep for v in t})
    new = {v: k for k, v in enumerate(used)}
    write_off(dst, [tuple(vertices[v]) for v in used], [tuple(new[int(v)] for v in t) for t in keep], digits=17)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--only", nargs="*", help="shape names (the table's first column) to run")
    ap.add_argument("--repeat", type=int, default=2, help="runs of each method per shape; the table shows the fastest")
    args = ap.parse_args()
    cli, peer = programs(args.build)
    lines = ["## Remeshing: the same protocol on isosurfaces (marching tetrahedra)", "",
             f"Machine: {machine_line()}. Implicit surfaces triangulated by marching tetrahedra as an isosurface of a "
             "scan or an implicit model is (slivers, vertices on the grid's edges), generated by "
             "tools/bench/remesh_isosurfaces.py and scaled so that their mean edge is 2.25; then the protocol and the "
             f"CGAL peer of the first table, measured the same way (seconds: the fastest of {args.repeat} runs, the "
             "two methods taking turns). Where `remesh` removed a component with less area than four triangles of "
             "the interval (it warns; the gyroid's box cuts a small piece off at a corner), its Hausdorff figures are "
             "against the input without that component, CGAL's (which keeps it) against the whole input.", ""] + header("shape")
    ratios = []
    with tempfile.TemporaryDirectory(prefix="carbonmesh-isosurfaces-") as work:
        for name, src in shape_files(work, args.only):
            ours = src[:-4] + "-out.off"
            theirs = src[:-4] + "-cgal.off"
            (result, rss), (peer_result, peer_rss) = protocol_and_peer(cli, peer, src, ours, theirs, args.repeat)
            removed = result["removed_components"]
            label, reference = name, src
            if removed["removed"]:
                label += f" ({removed['removed']} piece of area {removed['area']:.2f} removed)"
                reference = src[:-4] + "-kept.off"
                without_small_components(src, reference, 3 ** 0.5 * result["emin"] ** 2)
            lines.append(row(label, "carbonmesh", result["seconds"], rss, stats(cli, ours, reference),
                             result["iterations"]))
            lines.append(row(label, "CGAL", peer_result["seconds"], peer_rss, stats(cli, theirs, src, repair=True),
                             10))
            ratios.append((name, result["seconds"] / peer_result["seconds"]))
            print(lines[-2] + "\n" + lines[-1], flush=True)
    lines += ["", ratio_line(ratios)]
    replace_section(os.path.join(ROOT, "docs", "benchmarks.md"), "remesh-isosurfaces", "\n".join(lines))
    print("wrote docs/benchmarks.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
