#!/usr/bin/python3
"""Plots and report.html for `carbonmesh analyze` (run by it as: /usr/bin/python3 analysis_report.py DIR).

Reads DIR/report.json and DIR/view.json (written by carbonmesh), writes DIR/ring_sizes.png,
DIR/pentagon_distances.png, DIR/heptagon_distances.png, DIR/sides.png (with --plane) and DIR/report.html:
one self-contained page (PNGs as base64, three.js from Debian's libjs-three inlined, an interactive 3D view).
Every file is written to a temporary name and renamed into place.
"""
import base64
import html
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

THREE_DIRS = ["/usr/share/javascript/three"]
THREE_FILES = ["three.min.js", "examples/js/controls/OrbitControls.js"]

# Same colours as defect_ring_colour() in simulations/src/report_files.cpp.
COLOURS = {3: "#ffd700", 4: "#ff7f0e", 5: "#d62728", 6: "#c8c8c8", 7: "#1f77b4", 8: "#2ca02c"}
OTHER = "#9467bd"


def colour(size):
    return COLOURS.get(size, OTHER)


def atomic_write(path, data, mode="wb"):
    tmp = os.path.join(os.path.dirname(path), "." + os.path.basename(path) + ".partial-%d" % os.getpid())
    try:
        with open(tmp, mode) as f:
            f.write(data)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def save_figure(fig, path):
    tmp = os.path.join(os.path.dirname(path), "." + os.path.basename(path) + ".partial-%d.png" % os.getpid())
    try:
        fig.savefig(tmp, dpi=110)
        os.replace(tmp, path)
    finally:
        plt.close(fig)
        if os.path.exists(tmp):
            os.remove(tmp)


def title_of(report):
    return os.path.basename(os.path.normpath(report["input"])) or report["input"]


def plot_ring_sizes(report, path):
    by = {int(k): v for k, v in report["rings"]["by_size"].items()}
    sizes = sorted(by)
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    if sizes:
        bars = ax.bar([str(s) for s in sizes], [by[s] for s in sizes], color=[colour(s) for s in sizes],
                      edgecolor="black", linewidth=0.6)
        for b, s in zip(bars, sizes):
            ax.annotate(str(by[s]), (b.get_x() + b.get_width() / 2, b.get_height()), ha="center", va="bottom",
                        fontsize=9)
        if max(by.values()) > 50 * max(1, min(by.values())):
            ax.set_yscale("log")
            ax.set_ylim(0.7, 2.5 * max(by.values()))
    ax.set_xlabel("ring size (atoms)")
    ax.set_ylabel("rings")
    open_total = report["rings"]["open"]
    ax.set_title("Ring sizes, %s (%d rings%s)" % (title_of(report), report["rings"]["closed"],
                                                   ", %d open border rings not shown" % open_total if open_total else ""),
                 fontsize=10)
    fig.tight_layout()
    save_figure(fig, path)


def plot_distances(report, key, name, size, path):
    d = report[key]
    hist = {int(k): v for k, v in d["histogram"].items()}
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    if hist:
        lo, hi = min(hist), max(hist)
        xs = list(range(lo, hi + 1))
        ax.bar(xs, [hist.get(x, 0) for x in xs], color=colour(size), edgecolor="black", linewidth=0.6, width=0.9)
        if len(xs) <= 30:
            ax.set_xticks(xs)
        ax.set_xlabel("distance to the nearest other %s (ring-to-ring steps)" % name)
        ax.set_ylabel("%ss" % name)
        ax.set_title("Nearest %s to each %s, %s (%d %ss, mean %.2f)" % (name, name, title_of(report), d["count"], name,
                                                                      d["mean"]), fontsize=10)
    else:
        ax.text(0.5, 0.5, "%d %ss: no distances" % (d["count"], name), ha="center", va="center",
                transform=ax.transAxes)
        ax.set_axis_off()
        ax.set_title("Nearest %s to each %s, %s" % (name, name, title_of(report)), fontsize=10)
    fig.tight_layout()
    save_figure(fig, path)


def plot_sides(report, path):
    s = report["symmetry"]["sides"]
    sizes = sorted({int(k) for part in ("positive", "negative", "on_plane") for k in s[part]})
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    w = 0.38
    pos = [s["positive"].get(str(k), 0) for k in sizes]
    neg = [s["negative"].get(str(k), 0) for k in sizes]
    xs = list(range(len(sizes)))
    b1 = ax.bar([x - w / 2 for x in xs], pos, w, label="+ side (%d)" % s["positive_total"], color="#4c72b0",
                edgecolor="black", linewidth=0.6)
    b2 = ax.bar([x + w / 2 for x in xs], neg, w, label="- side (%d)" % s["negative_total"], color="#dd8452",
                edgecolor="black", linewidth=0.6)
    for bars in (b1, b2):
        for b in bars:
            ax.annotate(str(int(b.get_height())), (b.get_x() + b.get_width() / 2, b.get_height()), ha="center",
                        va="bottom", fontsize=9)
    ax.set_xticks(xs)
    ax.set_xticklabels([str(k) for k in sizes])
    ax.set_xlabel("ring size")
    ax.set_ylabel("irregular rings")
    sym = report["symmetry"]
    ax.set_title("Irregular rings by side of the %s plane, %s\n(mirror residual %.3g = %.2f%% of the diagonal)" % (
        sym["requested"], title_of(report), sym["residual"]["max"], 100 * sym["relative_residual"]), fontsize=10)
    ax.set_ylim(0, 1.3 * max(pos + neg + [1]))
    ax.legend(loc="upper center", ncol=2)
    fig.tight_layout()
    save_figure(fig, path)


def read_three():
    parts = []
    for d in THREE_DIRS:
        if all(os.path.exists(os.path.join(d, f)) for f in THREE_FILES):
            for f in THREE_FILES:
                with open(os.path.join(d, f), encoding="utf-8") as fh:
                    parts.append(fh.read().replace("</script", "<\\/script"))
            return "\n".join(parts)
    return None


VIEW_JS = r"""
(function () {
  const data = JSON.parse(document.getElementById('view-data').textContent);
  const box = document.getElementById('view');
  const note = document.getElementById('view-note');
  if (typeof THREE === 'undefined') { note.textContent = 'three.js missing: install libjs-three and rerun carbonmesh analyze.'; return; }
  let renderer;
  try {
    renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
  } catch (e) { note.textContent = 'WebGL is not available in this browser: ' + e; return; }
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(box.clientWidth, box.clientHeight);
  renderer.setClearColor(0xffffff, 1);
  box.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  const a = data.atoms;
  const n = a.length / 3;
  let lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < n; ++i) for (let k = 0; k < 3; ++k) { lo[k] = Math.min(lo[k], a[3*i+k]); hi[k] = Math.max(hi[k], a[3*i+k]); }
  const c = [0, 1, 2].map(k => 0.5 * (lo[k] + hi[k]));
  const radius = Math.max(1e-3, 0.5 * Math.hypot(hi[0]-lo[0], hi[1]-lo[1], hi[2]-lo[2]));
  const group = new THREE.Group();
  group.position.set(-c[0], -c[1], -c[2]);
  scene.add(group);
  // Bonds.
  const b = data.bonds;
  const bp = new Float32Array(b.length * 3);
  for (let e = 0; e < b.length; ++e) for (let k = 0; k < 3; ++k) bp[3*e+k] = a[3*b[e]+k];
  const bg = new THREE.BufferGeometry();
  bg.setAttribute('position', new THREE.BufferAttribute(bp, 3));
  const bonds = new THREE.LineSegments(bg, new THREE.LineBasicMaterial({color: 0x555555, transparent: true, opacity: 0.55}));
  group.add(bonds);
  // Atoms.
  const ag = new THREE.BufferGeometry();
  ag.setAttribute('position', new THREE.BufferAttribute(new Float32Array(a), 3));
  // Atom dots a quarter of the mean bond long (whatever the length unit of the input).
  let bl = 0, bn = 0;
  for (let e = 0; e < b.length && bn < 2000; e += 2, ++bn)
    bl += Math.hypot(a[3*b[e]] - a[3*b[e+1]], a[3*b[e]+1] - a[3*b[e+1]+1], a[3*b[e]+2] - a[3*b[e+1]+2]);
  const dot = bn ? 0.25 * bl / bn : 0.01 * radius;
  const atoms = new THREE.Points(ag, new THREE.PointsMaterial({color: 0x222222, size: dot, sizeAttenuation: true}));
  group.add(atoms);
  // Defect rings: filled polygons (fan from the centroid) coloured by size.
  const colours = {3: 0xffd700, 4: 0xff7f0e, 5: 0xd62728, 7: 0x1f77b4, 8: 0x2ca02c};
  const fp = [], fc = [], lp = [], lc = [];
  for (const ring of data.defects) {
    const col = new THREE.Color(colours[ring.size] !== undefined ? colours[ring.size] : 0x9467bd);
    const m = ring.atoms.length;
    const cc = [0, 0, 0];
    for (const v of ring.atoms) for (let k = 0; k < 3; ++k) cc[k] += a[3*v+k] / m;
    for (let j = 0; j < m; ++j) {
      const u = ring.atoms[j], w = ring.atoms[(j + 1) % m];
      fp.push(cc[0], cc[1], cc[2], a[3*u], a[3*u+1], a[3*u+2], a[3*w], a[3*w+1], a[3*w+2]);
      lp.push(a[3*u], a[3*u+1], a[3*u+2], a[3*w], a[3*w+1], a[3*w+2]);
      for (let t = 0; t < 3; ++t) fc.push(col.r, col.g, col.b);
      for (let t = 0; t < 2; ++t) lc.push(col.r, col.g, col.b);
    }
  }
  if (fp.length) {
    const fg = new THREE.BufferGeometry();
    fg.setAttribute('position', new THREE.BufferAttribute(new Float32Array(fp), 3));
    fg.setAttribute('color', new THREE.BufferAttribute(new Float32Array(fc), 3));
    group.add(new THREE.Mesh(fg, new THREE.MeshBasicMaterial({vertexColors: THREE.VertexColors, side: THREE.DoubleSide,
      polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1})));
    const lg = new THREE.BufferGeometry();
    lg.setAttribute('position', new THREE.BufferAttribute(new Float32Array(lp), 3));
    lg.setAttribute('color', new THREE.BufferAttribute(new Float32Array(lc), 3));
    group.add(new THREE.LineSegments(lg, new THREE.LineBasicMaterial({vertexColors: THREE.VertexColors})));
  }
  // Hexagons: an opaque near-white surface so that the far side is hidden.
  const sp = [];
  for (const ring of (data.rings || [])) {
    const m = ring.length;
    const cc = [0, 0, 0];
    for (const v of ring) for (let k = 0; k < 3; ++k) cc[k] += a[3*v+k] / m;
    for (let j = 0; j < m; ++j) {
      const u = ring[j], w = ring[(j + 1) % m];
      sp.push(cc[0], cc[1], cc[2], a[3*u], a[3*u+1], a[3*u+2], a[3*w], a[3*w+1], a[3*w+2]);
    }
  }
  if (sp.length) {
    const sg = new THREE.BufferGeometry();
    sg.setAttribute('position', new THREE.BufferAttribute(new Float32Array(sp), 3));
    group.add(new THREE.Mesh(sg, new THREE.MeshBasicMaterial({color: 0xf2f2f2, side: THREE.DoubleSide,
      polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1})));
  }
  // The mirror plane, if any: a translucent square through the shape.
  if (data.plane) {
    const nrm = new THREE.Vector3().fromArray(data.plane.normal).normalize();
    const ctr = new THREE.Vector3(c[0], c[1], c[2]);
    const foot = ctr.clone().addScaledVector(nrm, data.plane.offset - nrm.dot(ctr));
    const pg = new THREE.PlaneGeometry(2.4 * radius, 2.4 * radius);
    const pm = new THREE.Mesh(pg, new THREE.MeshBasicMaterial({color: 0x2ca02c, transparent: true, opacity: 0.18,
      side: THREE.DoubleSide, depthWrite: false}));
    pm.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), nrm);
    pm.position.copy(foot);
    group.add(pm);
  }
  const camera = new THREE.PerspectiveCamera(40, box.clientWidth / box.clientHeight, radius * 0.01, radius * 100);
  camera.position.set(0.8 * radius, 0.5 * radius, 2.3 * radius);
  camera.lookAt(0, 0, 0);
  let controls = null;
  if (THREE.OrbitControls) {
    controls = new THREE.OrbitControls(camera, renderer.domElement);
    controls.enableDamping = false;
    controls.addEventListener('change', draw);
  } else {  // rotate with the mouse, zoom with the wheel
    let drag = null;
    renderer.domElement.addEventListener('mousedown', e => { drag = [e.clientX, e.clientY]; });
    window.addEventListener('mouseup', () => { drag = null; });
    window.addEventListener('mousemove', e => {
      if (!drag) return;
      scene.rotation.y += 0.01 * (e.clientX - drag[0]);
      scene.rotation.x += 0.01 * (e.clientY - drag[1]);
      drag = [e.clientX, e.clientY];
      draw();
    });
    renderer.domElement.addEventListener('wheel', e => { e.preventDefault(); camera.position.multiplyScalar(e.deltaY > 0 ? 1.1 : 1 / 1.1); draw(); });
  }
  function draw() { renderer.render(scene, camera); }
  document.getElementById('show-bonds').addEventListener('change', e => { bonds.visible = e.target.checked; draw(); });
  document.getElementById('show-atoms').addEventListener('change', e => { atoms.visible = e.target.checked; draw(); });
  window.addEventListener('resize', () => {
    renderer.setSize(box.clientWidth, box.clientHeight);
    camera.aspect = box.clientWidth / box.clientHeight;
    camera.updateProjectionMatrix();
    draw();
  });
  draw();
  note.textContent = n + ' atoms, ' + b.length / 2 + ' bonds, ' + data.defects.length + ' defect rings' +
    (data.complete ? '' : ' (large structure: only the defect rings are shown)') + '. Drag to rotate, wheel to zoom' +
    (controls ? ', right-drag to pan.' : '.');
})();
"""


def summary_rows(r):
    rows = [("input", r["input"]), ("read as", "%s (%s)" % (r["resolved"]["kind"], r["resolved"]["file"])),
            ("atoms / bonds", "%d / %d" % (r["atoms"], r["bonds"])),
            ("rings", "%d closed%s (%s)" % (r["rings"]["closed"],
                                           ", %d open (border)" % r["rings"]["open"] if r["rings"]["open"] else "",
                                           r["rings_from"])),
            ("ring sizes", ", ".join("%s: %d" % (k, v) for k, v in sorted(r["rings"]["by_size"].items(),
                                                                          key=lambda kv: int(kv[0]))))]
    for key, name in (("pentagon_distances", "pentagon"), ("heptagon_distances", "heptagon")):
        d = r[key]
        if d["count"]:
            rows.append(("nearest %s distance" % name, "%d %ss: min %s, mean %.2f, max %s steps" % (
                d["count"], name, d["min"], d["mean"] or 0, d["max"])))
    p = r["pentagon_heptagon"]
    rows.append(("5-7 pairs", "%d matched dislocation pairs (%d adjacent pentagon-heptagon contacts)" % (
        p["matched_pairs"], p["adjacent_pairs"])))
    t = r["topology"]
    if t["six_chi"] is not None:
        rows.append(("topological floor", "sum(6 - size) = %d, 6χ = %d (χ = %d): at least %d non-hexagons; "
                     "observed %d" % (t["sum_six_minus_size"], t["six_chi"], t["euler"], t["floor_non_hexagons"],
                                      t["observed_non_hexagons"])))
    else:
        rows.append(("topological floor", "open surface: sum(6 - size) over closed rings = %d; observed %d "
                     "non-hexagons" % (t["sum_six_minus_size"], t["observed_non_hexagons"])))
    if "symmetry" in r:
        s = r["symmetry"]
        n = s["plane"]["normal"]
        rows.append(("mirror plane (%s)" % s["requested"],
                     "n = (%.4f, %.4f, %.4f), d = %.4f; residual (Hausdorff to the mirror image) max %.4g, rms %.4g "
                     "= %.2f%% of the diagonal" % (n[0], n[1], n[2], s["plane"]["offset"], s["residual"]["max"],
                                                   s["residual"]["rms"], 100 * s["relative_residual"])))
        rows.append(("irregular rings by side", "+ %d, - %d, on the plane %d" % (
            s["sides"]["positive_total"], s["sides"]["negative_total"], s["sides"]["on_plane_total"])))
    return rows


def write_html(out, report, images, three, view_json):
    rows = "\n".join("<tr><th>%s</th><td>%s</td></tr>" % (html.escape(k), html.escape(v)) for k, v in summary_rows(report))
    figs = "\n".join('<figure><img alt="%s" src="data:image/png;base64,%s"><figcaption>%s</figcaption></figure>' % (
        html.escape(cap), base64.b64encode(open(os.path.join(out, name), "rb").read()).decode("ascii"), html.escape(cap))
        for name, cap in images)
    page = """<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>carbonmesh analyze: %(title)s</title>
<style>
body { font-family: sans-serif; margin: 16px 24px; color: #222; }
table { border-collapse: collapse; margin-bottom: 12px; }
th, td { text-align: left; padding: 3px 10px; border-bottom: 1px solid #ddd; vertical-align: top; font-size: 14px; }
th { white-space: nowrap; }
.plots { display: flex; flex-wrap: wrap; gap: 8px; }
figure { margin: 0; }
figure img { width: 440px; border: 1px solid #ccc; }
figcaption { font-size: 12px; color: #555; }
#view { width: 100%%; height: 560px; border: 1px solid #aaa; position: relative; }
.legend span { display: inline-block; width: 12px; height: 12px; margin: 0 4px 0 12px; vertical-align: middle; }
</style></head><body>
<h1>Defect analysis: %(title)s</h1>
<table>%(rows)s</table>
<h2>3D view</h2>
<div class="legend">rings:<span style="background:#d62728"></span>pentagon<span style="background:#1f77b4"></span>heptagon
<span style="background:#ff7f0e"></span>square<span style="background:#2ca02c"></span>octagon<span style="background:#9467bd"></span>other;
hexagons light grey; mirror plane translucent green &nbsp; <label><input type="checkbox" id="show-bonds" checked> bonds</label>
<label><input type="checkbox" id="show-atoms" checked> atoms</label></div>
<div id="view"></div><p id="view-note"></p>
<h2>Plots</h2>
<div class="plots">%(figs)s</div>
<script id="view-data" type="application/json">%(view)s</script>
<script>%(three)s</script>
<script>%(js)s</script>
</body></html>
""" % {"title": html.escape(title_of(report)), "rows": rows, "figs": figs,
       "view": view_json.replace("</", "<\\/"), "three": three or "", "js": VIEW_JS}
    atomic_write(os.path.join(out, "report.html"), page.encode("utf-8"))


def main():
    if len(sys.argv) != 2:
        print("usage: analysis_report.py DIR (a carbonmesh analyze output folder)", file=sys.stderr)
        return 2
    out = sys.argv[1]
    with open(os.path.join(out, "report.json"), encoding="utf-8") as f:
        report = json.load(f)
    with open(os.path.join(out, "view.json"), encoding="utf-8") as f:
        view_json = f.read().strip()
    images = [("ring_sizes.png", "Ring sizes (closed rings)")]
    plot_ring_sizes(report, os.path.join(out, "ring_sizes.png"))
    plot_distances(report, "pentagon_distances", "pentagon", 5, os.path.join(out, "pentagon_distances.png"))
    images.append(("pentagon_distances.png", "Distance from each pentagon to its nearest pentagon (cf. Fig. 6.3)"))
    plot_distances(report, "heptagon_distances", "heptagon", 7, os.path.join(out, "heptagon_distances.png"))
    images.append(("heptagon_distances.png", "Distance from each heptagon to its nearest heptagon (cf. Fig. 6.4)"))
    if "symmetry" in report:
        plot_sides(report, os.path.join(out, "sides.png"))
        images.append(("sides.png", "Irregular rings on each side of the mirror plane"))
    three = read_three()
    if three is None:
        print("analysis_report.py: three.js not found in %s (apt-get install libjs-three); report.html has no 3D view"
              % THREE_DIRS[0], file=sys.stderr)
    write_html(out, report, images, three, view_json)
    return 0


if __name__ == "__main__":
    sys.exit(main())
