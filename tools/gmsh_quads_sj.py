#!/usr/bin/env python3
"""gmsh's Blossom recombination beside fepre's all-quad mesher (mesh2d::quads) on the same
regions: for every region JSON written by the ignored test
`mesh2d::quads::tests::dump_regions_for_gmsh` (its boundary loops as fepre got them, its size
field as a gmsh expression, fepre's figures), write a .geo with the same boundary points
(Mesh.Algorithm = 8, or 6 where 8 crashes, as gmsh 4.8.4 here does on every input; Mesh.RecombineAll = 1, the size as a MathEval background field), run
`gmsh -2`, read the quads (MSH 2.2) and print min / median scaled Jacobian of both, the same
definition as fepre's measure: per corner cross(e_next, e_prev) / (|e_next| |e_prev|), the
smallest over the corners, the median taken as v[round((n - 1) / 2)] of the sorted values.

Usage: QUADS_DUMP=/tmp/quads cargo test --release --lib mesh2d::quads::tests::dump -- --ignored
       python3 tools/gmsh_quads_sj.py /tmp/quads
Plain python3, no numpy.
"""
import json, math, os, subprocess, sys


def geo(region, algorithm):
    lines, out, loops = [], [], []
    p = l = 0
    for loop in region["loops"]:
        first = p + 1
        for x, y in loop:
            p += 1
            out.append(f"Point({p}) = {{{x!r}, {y!r}, 0, 1.0}};")
        ids = []
        for k in range(len(loop)):
            l += 1
            a, b = first + k, first + (k + 1) % len(loop)
            out.append(f"Line({l}) = {{{a}, {b}}};")
            ids.append(l)
        loops.append(ids)
    for k, ids in enumerate(loops):
        out.append(f"Curve Loop({k + 1}) = {{{', '.join(map(str, ids))}}};")
    out.append(f"Plane Surface(1) = {{{', '.join(str(k + 1) for k in range(len(loops)))}}};")
    out += [
        "Field[1] = MathEval;",
        f'Field[1].F = "{region["size"]}";',
        "Background Field = 1;",
        "Mesh.MeshSizeExtendFromBoundary = 0;",
        "Mesh.MeshSizeFromPoints = 0;",
        "Mesh.MeshSizeFromCurvature = 0;",
        f"Mesh.Algorithm = {algorithm};",
        "Mesh.RecombineAll = 1;",
    ]
    return "\n".join(out) + "\n"


def read_msh22(path):
    nodes, quads, tris = {}, [], 0
    with open(path) as f:
        lines = f.read().split("\n")
    i = 0
    while i < len(lines):
        if lines[i] == "$Nodes":
            n = int(lines[i + 1])
            for k in range(n):
                t = lines[i + 2 + k].split()
                nodes[int(t[0])] = (float(t[1]), float(t[2]))
            i += n + 2
        elif lines[i] == "$Elements":
            n = int(lines[i + 1])
            for k in range(n):
                t = list(map(int, lines[i + 2 + k].split()))
                ntags = t[2]
                v = t[3 + ntags:]
                if t[1] == 3:
                    quads.append(v)
                elif t[1] == 2:
                    tris += 1
            i += n + 2
        else:
            i += 1
    return nodes, quads, tris


def sj(pts):
    n, best = len(pts), math.inf
    for i in range(n):
        a = (pts[(i + 1) % n][0] - pts[i][0], pts[(i + 1) % n][1] - pts[i][1])
        b = (pts[(i - 1) % n][0] - pts[i][0], pts[(i - 1) % n][1] - pts[i][1])
        best = min(best, (a[0] * b[1] - a[1] * b[0]) / (math.hypot(*a) * math.hypot(*b)))
    return best


def main(folder):
    print(f"{'region':10} {'fepre quads':>11} {'min SJ':>7} {'median':>7} | {'gmsh quads':>10} {'tris':>4} {'min SJ':>7} {'median':>7}")
    for name in sorted(os.listdir(folder)):
        if not name.endswith(".json"):
            continue
        region = json.load(open(os.path.join(folder, name)))
        base = os.path.join(folder, region["name"])
        for algorithm in (8, 6):
            with open(base + ".geo", "w") as f:
                f.write(geo(region, algorithm))
            r = subprocess.run(["gmsh", "-2", base + ".geo", "-format", "msh22", "-o", base + ".msh"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            if r.returncode == 0:
                break
            print(f"  gmsh -2 with Mesh.Algorithm = {algorithm} failed (exit {r.returncode}); trying the next", file=sys.stderr)
        nodes, quads, tris = read_msh22(base + ".msh")
        v = []
        for q in quads:
            pts = [nodes[i] for i in q]
            area = sum(pts[k][0] * pts[(k + 1) % 4][1] - pts[(k + 1) % 4][0] * pts[k][1] for k in range(4))
            if area < 0:
                pts.reverse()
            v.append(sj(pts))
        v.sort()
        fe = region["fepre"]
        print(f"{region['name']:10} A{algorithm} {fe['quads']:>8} {fe['sj_after'][0]:7.3f} {fe['sj_after'][1]:7.3f} | {len(quads):>10} {tris:>4} {v[0]:7.3f} {v[round((len(v) - 1) * 0.5)]:7.3f}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "/tmp/quads")
