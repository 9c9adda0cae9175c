#!/usr/bin/env python3
"""The 2D side-by-side table of issue 66: fepre's mesh2d methods beside Shewchuk's Triangle,
CGAL Mesh_2 and gmsh on the same .poly regions; prints a markdown table.

Usage (Python with triangle, numpy and meshio: tools/install_refs_2d.sh VENV makes one):
  VENV/bin/python tools/bench_mesh2d_anchors.py [--fepre target/release/fepre]
      [--cgal tools/cgal_mesh2/cgal_mesh2] [--gmsh gmsh] [--regions cad_fixtures/regions]
      [--triangles 20000] [--only large,convex] [--methods delaunay,front] [--no-quads]
      [--million] [--json-out results.json]
  --million: the region 'large' at about a million triangles, fepre's delaunay only, no quads,
  no gmsh, no CGAL size row (the speed acceptance: fepre's whole run against Triangle's
  triangulate call).

For each region (every .poly in --regions, or --only), with the maximum area
A = 1.7 * region area / --triangles (Triangle's -q33 triangles average about 0.58 A, so
about --triangles of them; --million: the region 'large' at a million triangles):
  - Triangle: triangle.triangulate(poly, 'pq33a<A>Q'); only that call is timed (Python's
    start and the import excluded). Every ratio in the table is to this row.
  - fepre: `fepre mesh2d REGION.poly --method delaunay --json --max-area A --min-angle 33`,
    and `--method M --size h` (h as for gmsh below) for M in ear recursive removal front
    quadtree (they size by the size field only), and `--quads --size h` for each M; the whole
    process is timed (its start and the file read included), and its own `total_seconds` is
    shown beside.
  - CGAL Mesh_2 at 30 deg (its refinement is not sure to end at 33), timed inside
    (refine_Delaunay_mesh_2 alone; the CDT's time in brackets): `cgal_mesh2 REGION.poly
    --area A --min-angle 30` (the driver's area criteria, Triangle's -a: CGAL leaves some
    angles under 30 there) beside fepre's delaunay at --max-area A --min-angle 30, and
    `--size S` (CGAL's Delaunay_mesh_size_criteria_2(0.25, S), S the h below) beside
    fepre's delaunay at --size S --min-angle 30: the 15 % comparisons.
  - gmsh 2D: a .geo of the region with the point size h = sqrt(4 * 0.6 A / sqrt 3) (an
    equilateral triangle of area 0.6 A), Mesh.Algorithm 5 (Delaunay) and 6 (Frontal-
    Delaunay), and 8 with Mesh.RecombineAll = 1 (Blossom quads; where gmsh 4.8's algorithm
    8 crashes, as it does on some sizes, 6 with RecombineAll, so labelled); the time is
    gmsh's own "Done meshing 2D" wall time (the whole process in brackets).
Columns: elements, min and max angle, median scaled Jacobian of the quads, seconds, count and
time ratio to Triangle. A tool that is missing or fails gets a row saying so.
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time

import numpy as np

METHODS = ["delaunay", "ear", "recursive", "removal", "front", "quadtree"]
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def read_poly(path):
    """Points (n x 2), segments (0-based, m x 2) and hole seeds of a Triangle 2D .poly."""
    def lines(p):
        out = []
        with open(p) as f:
            for raw in f:
                fields = raw.split("#")[0].split()
                if fields:
                    out.append(fields)
        return out

    L = lines(path)
    i = 0

    def vertices(L, i):
        n = int(L[i][0])
        rows = L[i + 1:i + 1 + n]
        base = int(rows[0][0]) if rows else 0
        return np.array([[float(r[1]), float(r[2])] for r in rows]).reshape(-1, 2), base, i + 1 + n

    pts, base, i = vertices(L, i)
    if len(pts) == 0:
        pts, base, _ = vertices(lines(os.path.splitext(path)[0] + ".node"), 0)
    m = int(L[i][0])
    segs = np.array([[int(r[1]) - base, int(r[2]) - base] for r in L[i + 1:i + 1 + m]], dtype=np.int64).reshape(-1, 2)
    i += 1 + m
    holes = []
    if i < len(L):
        h = int(L[i][0])
        holes = [[float(r[1]), float(r[2])] for r in L[i + 1:i + 1 + h]]
    return pts, segs, np.array(holes).reshape(-1, 2)


def loops(pts, segs):
    """The closed loops of a graph whose vertices all have two segments (the fixtures)."""
    nxt = {}
    adj = {}
    for a, b in segs:
        adj.setdefault(a, []).append(b)
        adj.setdefault(b, []).append(a)
    seen = set()
    out = []
    for a, b in segs:
        if a in seen:
            continue
        loop = [a]
        seen.add(a)
        prev, cur = a, b
        while cur != a:
            loop.append(cur)
            seen.add(cur)
            n = [x for x in adj[cur] if x != prev]
            if len(adj[cur]) != 2 or not n:
                raise ValueError("the region is not a set of simple loops (gmsh's .geo needs them)")
            prev, cur = cur, n[0]
        out.append(loop)
    return out


def loop_area(pts, loop):
    p = pts[loop]
    q = np.roll(p, -1, axis=0)
    return 0.5 * float(np.sum(p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1]))


def region_area(pts, segs):
    ls = loops(pts, segs)
    areas = sorted((abs(loop_area(pts, l)) for l in ls), reverse=True)
    return areas[0] - sum(areas[1:])


def tri_angles(p, t):
    """Smallest and largest corner angle (degrees) of triangles t over points p."""
    a, b, c = p[t[:, 0]], p[t[:, 1]], p[t[:, 2]]
    angs = []
    for u, v, w in ((a, b, c), (b, c, a), (c, a, b)):
        e1, e2 = v - u, w - u
        cr = np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
        angs.append(np.degrees(np.arctan2(cr, np.sum(e1 * e2, axis=1))))
    angs = np.concatenate(angs)
    return float(angs.min()), float(angs.max())


def quad_quality(p, q):
    """Smallest and largest corner angle, median and smallest scaled Jacobian (Verdict: the
    smallest corner cross(e_next, e_prev) / (|e_next| |e_prev|)) of quads q, each taken
    counter-clockwise (a clockwise quad is read the other way round)."""
    P = p[q]  # (k, 4, 2)
    area = 0.5 * np.sum(P[:, :, 0] * np.roll(P[:, :, 1], -1, axis=1) - np.roll(P[:, :, 0], -1, axis=1) * P[:, :, 1], axis=1)
    P = np.where((area < 0)[:, None, None], P[:, ::-1], P)
    sj = np.full(len(q), np.inf)
    angs = []
    for k in range(4):
        u, v, w = P[:, k], P[:, (k + 1) % 4], P[:, (k + 3) % 4]
        e1, e2 = v - u, w - u
        cr = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
        sj = np.minimum(sj, cr / (np.linalg.norm(e1, axis=1) * np.linalg.norm(e2, axis=1)))
        angs.append(np.degrees(np.arctan2(np.abs(cr), np.sum(e1 * e2, axis=1))))
    angs = np.concatenate(angs)
    return float(angs.min()), float(angs.max()), float(np.median(sj)), float(sj.min())


def fixed(x):
    """x in fixed-point decimals (no exponent), as Triangle's switches need."""
    return f"{x:.15f}".rstrip("0").rstrip(".")


def run_triangle(poly_path, A, angle=33):
    import triangle
    pts, segs, holes = read_poly(poly_path)
    d = {"vertices": pts, "segments": segs}
    if len(holes):
        d["holes"] = holes
    # fixed-point: Triangle reads the digits and '.' after 'a', and 'e' is its own switch
    opts = f"pq{angle}a{fixed(A)}Q"
    t0 = time.perf_counter()
    m = triangle.triangulate(d, opts)
    t = time.perf_counter() - t0
    lo, hi = tri_angles(m["vertices"], m["triangles"])
    return dict(elements=len(m["triangles"]), kind="tri", min=lo, max=hi, seconds=t, cmd=f"triangle.triangulate(poly, '{opts}')")


def run_fepre(fepre, poly_path, method, A, angle, quads, size=None):
    """delaunay's triangle runs take A and the angle; every other run (the methods that size by
    the size field only, and every --quads run) takes the size h, as gmsh."""
    cmd = [fepre, "mesh2d", poly_path, "--method", method, "--json"]
    if quads or method != "delaunay":
        cmd += ["--size", repr(size if size is not None else float(f"{math.sqrt(4 * 0.6 * A / math.sqrt(3)):.3g}"))] + (["--quads"] if quads else [])
    else:
        cmd += ["--max-area", repr(A)] if A is not None else ["--size", repr(size)]
        cmd += ["--min-angle", str(angle)]
    t0 = time.perf_counter()
    try:
        r = subprocess.run(cmd, capture_output=True, text=True)
    except OSError as e:
        return dict(error=str(e), cmd=" ".join(cmd[1:]))
    wall = time.perf_counter() - t0
    if r.returncode != 0:
        return dict(error=(r.stderr.strip() or r.stdout.strip())[:160], cmd=" ".join(cmd[1:]))
    try:
        j = json.loads(r.stdout)
    except ValueError:
        return dict(error="no JSON on stdout: " + r.stdout[:120], cmd=" ".join(cmd[1:]))
    q = j.get("quality", {})
    tris, nq = j.get("triangles", q.get("triangles", 0)), j.get("quads", q.get("quads", 0))
    own = j.get("total_seconds", j.get("seconds"))
    if isinstance(own, list):
        own = sum(own)
    ar = q.get("angle_range", [float("nan")] * 2)
    sj = q.get("quad_scaled_jacobian", [float("nan")] * 2) if nq else [float("nan")] * 2
    return dict(elements=tris + nq, kind="quad" if nq and not tris else ("mixed" if nq else "tri"), min=ar[0], max=ar[1], sj=sj[1], sj_min=sj[0],
                seconds=wall, own_seconds=own, cmd=" ".join(cmd[1:]))


def run_cgal(cgal, poly_path, bound, by="area"):
    cmd = [cgal, poly_path, "--" + by, repr(bound), "--min-angle", "30"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        return dict(error=r.stderr.strip()[:160], cmd=" ".join(cmd))
    j = json.loads(r.stdout)
    return dict(elements=j["triangles"], kind="tri", min=j["min_angle"], max=j["max_angle"], seconds=j["refine_seconds"], own_seconds=j["cdt_seconds"] + j["refine_seconds"], cmd="cgal_mesh2 " + " ".join(cmd[1:]))


def geo_text(poly_path, h, algorithm, recombine):
    pts, segs, _ = read_poly(poly_path)
    ls = loops(pts, segs)
    ls.sort(key=lambda l: -abs(loop_area(pts, l)))
    out = [f"Mesh.Algorithm = {algorithm};", f"Mesh.RecombineAll = {1 if recombine else 0};", f"Mesh.MeshSizeMax = {h!r};", "Mesh.MeshSizeFromCurvature = 0;"]
    for k, (x, y) in enumerate(pts):
        out.append(f"Point({k + 1}) = {{{float(x)!r}, {float(y)!r}, 0, {h!r}}};")
    line = 0
    loop_ids = []
    for li, l in enumerate(ls):
        ids = []
        for k in range(len(l)):
            line += 1
            out.append(f"Line({line}) = {{{int(l[k]) + 1}, {int(l[(k + 1) % len(l)]) + 1}}};")
            ids.append(line)
        out.append(f"Curve Loop({li + 1}) = {{{', '.join(map(str, ids))}}};")
        loop_ids.append(li + 1)
    out.append(f"Plane Surface(1) = {{{', '.join(map(str, loop_ids))}}};")
    return "\n".join(out) + "\n"


def run_gmsh(gmsh, poly_path, A, algorithm, recombine, tmp):
    import meshio
    h = math.sqrt(4 * 0.6 * A / math.sqrt(3))
    geo = os.path.join(tmp, f"r_{algorithm}_{int(recombine)}.geo")
    msh = geo[:-4] + ".msh"
    with open(geo, "w") as f:
        f.write(geo_text(poly_path, h, algorithm, recombine))
    cmd = [gmsh, geo, "-2", "-o", msh, "-format", "msh41"]
    t0 = time.perf_counter()
    r = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    name = f"gmsh -2 Mesh.Algorithm {algorithm}" + (" + RecombineAll" if recombine else "")
    if r.returncode != 0 or not os.path.exists(msh):
        return dict(error=f"exit {r.returncode}: " + (r.stderr.strip() or r.stdout.strip())[-120:], cmd=name)
    times = [float(x) for x in re.findall(r"Done meshing 2D \(Wall ([0-9.eE+-]+)s", r.stdout)]
    m = meshio.read(msh)
    p = m.points[:, :2]
    tris = np.concatenate([c.data for c in m.cells if c.type == "triangle"] or [np.zeros((0, 3), int)])
    quads = np.concatenate([c.data for c in m.cells if c.type == "quad"] or [np.zeros((0, 4), int)])
    res = dict(elements=len(tris) + len(quads), kind="quad" if len(quads) and not len(tris) else ("mixed" if len(quads) else "tri"), seconds=times[-1] if times else wall, own_seconds=wall, cmd=name + f" (h = {h:.4g})")
    lo, hi = tri_angles(p, tris) if len(tris) else (float("inf"), 0.0)
    if len(quads):
        qlo, qhi, sj, sjmin = quad_quality(p, quads)
        lo, hi = min(lo, qlo), max(hi, qhi)
        res.update(sj=sj, sj_min=sjmin)
    res.update(min=lo, max=hi)
    return res


def fmt(x, nd=2):
    if x is None or (isinstance(x, float) and (math.isnan(x) or math.isinf(x))):
        return "-"
    return f"{x:.{nd}f}"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--fepre", default=os.path.join(ROOT, "target/release/fepre"))
    ap.add_argument("--cgal", default=os.path.join(HERE, "cgal_mesh2/cgal_mesh2"))
    ap.add_argument("--gmsh", default="gmsh")
    ap.add_argument("--regions", default=os.path.join(ROOT, "cad_fixtures/regions"))
    ap.add_argument("--triangles", type=float, default=20000)
    ap.add_argument("--only", default="")
    ap.add_argument("--million", action="store_true", help="only the region 'large', at about a million triangles")
    ap.add_argument("--no-quads", action="store_true")
    ap.add_argument("--no-gmsh", action="store_true")
    ap.add_argument("--methods", default=",".join(METHODS), help="fepre's methods to run (default: all six)")
    ap.add_argument("--json-out")
    a = ap.parse_args()
    names = sorted(f[:-5] for f in os.listdir(a.regions) if f.endswith(".poly"))
    if a.million:
        names, a.triangles, a.no_quads, a.no_gmsh = ["large"], 1e6, True, True
        if a.methods == ",".join(METHODS):
            a.methods = "delaunay"
    methods = [m for m in a.methods.split(",") if m]
    if a.only:
        names = [n for n in names if n in a.only.split(",")]
    results = []
    print("| region | tool | elements | min angle | max angle | median quad SJ (min) | seconds | count / Triangle | time / Triangle |")
    print("|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for name in names:
            path = os.path.join(a.regions, name + ".poly")
            pts, segs, _ = read_poly(path)
            A = float(f"{1.7 * region_area(pts, segs) / a.triangles:.3g}")
            rows = [("Triangle -q33", run_triangle(path, A))]
            for m in methods:
                rows.append((f"fepre {m} -q33" if m == "delaunay" else f"fepre {m} (--size h)", run_fepre(a.fepre, path, m, A, 33, False)))
            built = os.path.exists(a.cgal)
            rows.append(("CGAL Mesh_2 30° area", run_cgal(a.cgal, path, A) if built else dict(error="not built (make -C tools/cgal_mesh2)")))
            rows.append(("fepre delaunay 30°", run_fepre(a.fepre, path, "delaunay", A, 30, False)))
            S = float(f"{math.sqrt(4 * 0.6 * A / math.sqrt(3)):.3g}")
            if not a.million:
                rows.append((f"CGAL Mesh_2 30° size {S:g}", run_cgal(a.cgal, path, S, "size") if built else dict(error="not built (make -C tools/cgal_mesh2)")))
                rows.append((f"fepre delaunay 30° --size {S:g}", run_fepre(a.fepre, path, "delaunay", None, 30, False, size=S)))
            for alg, rec in () if a.no_gmsh else ((5, False), (6, False), (8, True)):
                label = {5: "gmsh Delaunay (5)", 6: "gmsh Frontal-Delaunay (6)", 8: "gmsh Blossom quads (8)"}[alg]
                try:
                    r = run_gmsh(a.gmsh, path, A, alg, rec, tmp)
                    if "error" in r and alg == 8:
                        # gmsh 4.8's algorithm 8 crashes on some sizes: Blossom on 6 instead
                        r = run_gmsh(a.gmsh, path, A, 6, True, tmp)
                        label = "gmsh Blossom quads (6 + RecombineAll; 8 failed)"
                    rows.append((label, r))
                except (OSError, ValueError) as e:
                    rows.append((label, dict(error=str(e)[:160])))
            if not a.no_quads:
                for m in methods:
                    rows.append((f"fepre {m} --quads", run_fepre(a.fepre, path, m, A, 33, True)))
            ref = rows[0][1]
            for tool, r in rows:
                r.update(region=name, tool=tool, max_area=A)
                results.append(r)
                if "error" in r:
                    print(f"| {name} (A = {A:g}) | {tool} | failed: {r['error'].splitlines()[0] if r['error'] else '?'} | | | | | | |")
                    continue
                sj = f"{fmt(r.get('sj'), 3)} ({fmt(r.get('sj_min'), 3)})" if r.get("sj") is not None else "-"
                secs = fmt(r["seconds"], 4) + (f" ({fmt(r['own_seconds'], 4)})" if r.get("own_seconds") is not None else "")
                print(f"| {name} (A = {A:g}) | {tool} | {r['elements']} {r['kind']} | {fmt(r['min'])} | {fmt(r['max'])} | {sj} | {secs} | {r['elements'] / ref['elements']:.3f} | {r['seconds'] / ref['seconds']:.2f} |")
            sys.stdout.flush()
    if a.json_out:
        with open(a.json_out, "w") as f:
            json.dump(results, f, indent=1)


if __name__ == "__main__":
    main()
