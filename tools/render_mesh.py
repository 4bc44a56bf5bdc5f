#!/usr/bin/python3
"""Render a carbonmesh mesh to a PNG with matplotlib (for the documentation in docs/img/).

    render_mesh.py MESH -o PICTURE.png [--color rings|valence|file] [--elev 20] [--azim -60]
                   [--title TEXT] [--size 5] [--dpi 110]
                   [--edges] [--zoom 1.3]

MESH is an ASCII OFF or PLY (what carbonmesh writes: remeshed.off, `shape` output, rings.ply,
analyze's defects.ply).  Faces are coloured

  * rings   -- by their number of corners (a ring of the dual: 5 red, 6 grey, 7 blue, other yellow,
               the colours of rings.ply), the default for a polygon mesh;
  * valence -- a triangle mesh: every triangle is cut into three corner quads coloured by the valence
               of their corner (5 red, 6 grey, 7 blue, other yellow), so the cell of a vertex has the
               colour of the ring it becomes in the dual; the default for a triangle mesh;
  * file    -- the red/green/blue face properties of a PLY.

Flat shading: the colour is scaled by the cosine between the face normal and a fixed light direction
(two-sided).  Only /usr/bin/python3 with python3-matplotlib and numpy is needed.
"""
import argparse
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

SIZE_COLOURS = {5: (220, 40, 40), 6: (170, 170, 170), 7: (40, 80, 220)}
OTHER = (240, 200, 30)


def tokens_of(path):
    with open(path, encoding="ascii", errors="replace") as f:
        return f.read().splitlines()


def read_off(path):
    lines = [l.split("#")[0].strip() for l in tokens_of(path)]
    lines = [l for l in lines if l]
    if not lines[0].startswith("OFF"):
        raise ValueError(f"{path}: not an ASCII OFF file")
    words = " ".join(lines[0][3:].split() + lines[1:]).split()
    nv, nf = int(words[0]), int(words[1])
    pos = 3
    verts = np.array([float(w) for w in words[pos:pos + 3 * nv]]).reshape(nv, 3)
    pos += 3 * nv
    faces = []
    for _ in range(nf):
        k = int(words[pos])
        faces.append([int(w) for w in words[pos + 1:pos + 1 + k]])
        pos += 1 + k
    return verts, faces, None


def read_ply(path):
    lines = tokens_of(path)
    if lines[0].strip() != "ply" or "ascii" not in lines[1]:
        raise ValueError(f"{path}: only ASCII PLY is read")
    nv = nf = 0
    face_props = []
    element = None
    i = 2
    while lines[i].strip() != "end_header":
        w = lines[i].split()
        if w[0] == "element":
            element = w[1]
            if element == "vertex":
                nv = int(w[2])
            elif element == "face":
                nf = int(w[2])
        elif w[0] == "property" and element == "face" and w[1] != "list":
            face_props.append(w[-1])
        i += 1
    body = lines[i + 1:]
    verts = np.array([[float(x) for x in body[k].split()[:3]] for k in range(nv)])
    faces, colours = [], []
    for line in body[nv:nv + nf]:
        w = line.split()
        k = int(w[0])
        faces.append([int(x) for x in w[1:1 + k]])
        extra = dict(zip(face_props, w[1 + k:]))
        if {"red", "green", "blue"} <= extra.keys():
            colours.append((int(extra["red"]), int(extra["green"]), int(extra["blue"])))
    return verts, faces, colours if len(colours) == len(faces) else None


def corner_polygons(verts, faces):
    """Each triangle cut into three quads (corner, edge midpoint, centroid, edge midpoint): the part of a
    triangle nearest to each corner, so the quads around a vertex form its cell (the ring it becomes)."""
    edges = {tuple(sorted((a, b))) for f in faces for a, b in zip(f, f[1:] + f[:1])}
    valence = np.zeros(len(verts), dtype=int)
    for a, b in edges:
        valence[a] += 1
        valence[b] += 1
    polys, colours = [], []
    for f in faces:
        g = verts[f].mean(axis=0)
        for i, v in enumerate(f):
            prev, nxt = f[i - 1], f[(i + 1) % len(f)]
            polys.append(np.array([verts[v], (verts[v] + verts[nxt]) / 2, g, (verts[v] + verts[prev]) / 2]))
            colours.append(SIZE_COLOURS.get(int(valence[v]), OTHER))
    return polys, np.array(colours, dtype=float) / 255


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("mesh")
    ap.add_argument("-o", "--output", required=True)
    ap.add_argument("--color", choices=["rings", "valence", "file"])
    ap.add_argument("--elev", type=float, default=20)
    ap.add_argument("--azim", type=float, default=-60)
    ap.add_argument("--title", default="")
    ap.add_argument("--size", type=float, default=5, help="figure size in inches")
    ap.add_argument("--dpi", type=int, default=110)
    ap.add_argument("--edges", action="store_true", help="draw the polygon edges (rings and file colours)")
    ap.add_argument("--zoom", type=float, default=1.3, help="zoom of the 3D box")
    a = ap.parse_args()

    verts, faces, file_colours = (read_ply if a.mesh.endswith(".ply") else read_off)(a.mesh)
    mode = a.color or ("valence" if all(len(f) == 3 for f in faces) else "rings")
    if mode == "valence":
        polys, base = corner_polygons(verts, faces)
    else:
        polys = [verts[f] for f in faces]
        if mode == "file":
            if file_colours is None:
                raise ValueError("the mesh has no face colours")
            base = np.array(file_colours, dtype=float) / 255
        else:
            base = np.array([SIZE_COLOURS.get(len(f), OTHER) for f in faces], dtype=float) / 255
    light = np.array([0.4, -0.5, 0.8])
    light /= np.linalg.norm(light)
    shade = np.empty(len(polys))
    for k, p in enumerate(polys):
        c = p.mean(axis=0)
        n = np.zeros(3)
        for i in range(len(p)):  # Newell normal, fine for non-planar rings
            n += np.cross(p[i] - c, p[(i + 1) % len(p)] - c)
        ln = np.linalg.norm(n)
        shade[k] = abs(n @ light) / ln if ln > 0 else 1.0
    colours = base * (0.35 + 0.65 * shade)[:, None]

    fig = plt.figure(figsize=(a.size, a.size))
    ax = fig.add_subplot(projection="3d")
    coll = Poly3DCollection(polys, facecolors=np.clip(colours, 0, 1), edgecolors="none", linewidths=0)
    if a.edges and mode != "valence":
        coll.set_edgecolor((0, 0, 0, 0.35))
        coll.set_linewidth(0.3)
    ax.add_collection3d(coll)
    lo, hi = verts.min(axis=0), verts.max(axis=0)
    centre, half = (lo + hi) / 2, (hi - lo).max() / 2
    for setter, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre):
        setter(c - half, c + half)
    ax.set_box_aspect((1, 1, 1), zoom=a.zoom)
    ax.view_init(elev=a.elev, azim=a.azim)
    ax.set_axis_off()
    if a.title:
        fig.suptitle(a.title, fontsize=10, y=0.97)
    fig.subplots_adjust(0, 0, 1, 1)
    fig.savefig(a.output, dpi=a.dpi)
    print(f"{a.output}: {len(verts)} vertices, {len(faces)} faces, coloured by {mode}")


if __name__ == "__main__":
    try:
        main()
    except (OSError, ValueError, IndexError) as e:
        sys.exit(f"render_mesh.py: {e}")
