#!/usr/bin/env python3
"""Writes the 2D test regions of issue 66 as Triangle .poly files (plain python3, no packages).

Usage: tools/gen_regions.py [OUT_DIR]   (default: cad_fixtures/regions beside this script's repo)

Regions (each loop its own segment marker: outer 1, holes 2, 3, ...; 1-based numbering;
hole seeds at the holes' centres; no regional attributes, so every region gets tag 1):
  convex        a regular 24-gon of radius 1
  l_shape       an L, 2 x 2 with the 1 x 1 upper-right square cut out
  comb          a comb: a 3.5 x 1 back with four 0.5 x 2 teeth
  two_holes     a 4 x 2 rectangle with a 24-gon hole (radius 0.5) and a square hole (0.8)
  strip         a thin strip, 10 x 0.2
  small_angle   a region with a 10 degree input angle at the origin
  large         a 10 x 10 rectangle with two 24-gon holes and a square hole, for speed runs
                (meshed to about a million triangles with a max area, not a big file)
The coordinates are printed with repr (shortest round-trip decimals), so the files are the
same bytes on every machine.
"""
import math
import os
import sys


def ngon(cx, cy, r, n, phase=0.0):
    return [(cx + r * math.cos(phase + 2 * math.pi * k / n), cy + r * math.sin(phase + 2 * math.pi * k / n)) for k in range(n)]


def rect(x0, y0, x1, y1):
    return [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]


def poly_text(name, loops, holes, comment):
    """loops: lists of points (closed); holes: seed points."""
    pts = [p for l in loops for p in l]
    out = [f"# {name}: {comment}", "# written by tools/gen_regions.py", f"{len(pts)} 2 0 0"]
    for k, (x, y) in enumerate(pts):
        out.append(f"{k + 1} {x!r} {y!r}")
    nseg = sum(len(l) for l in loops)
    out.append(f"{nseg} 1")
    base = 0
    s = 0
    for li, l in enumerate(loops):
        n = len(l)
        for k in range(n):
            s += 1
            out.append(f"{s} {base + k + 1} {base + (k + 1) % n + 1} {li + 1}")
        base += n
    out.append(f"{len(holes)}")
    for k, (x, y) in enumerate(holes):
        out.append(f"{k + 1} {x!r} {y!r}")
    out.append("0")
    return "\n".join(out) + "\n"


def regions():
    yield "convex", [ngon(0.0, 0.0, 1.0, 24)], [], "a regular 24-gon of radius 1"
    yield "l_shape", [[(0.0, 0.0), (2.0, 0.0), (2.0, 1.0), (1.0, 1.0), (1.0, 2.0), (0.0, 2.0)]], [], "an L, 2 x 2 less its upper-right unit square"
    comb = [(0.0, 0.0), (3.5, 0.0)]
    for x in (3.0, 2.0, 1.0, 0.0):  # teeth [x, x + 0.5] x [1, 3], right to left
        comb += [(x + 0.5, 3.0), (x, 3.0)] + ([(x, 1.0), (x - 0.5, 1.0)] if x > 0.0 else [])
    yield "comb", [comb], [], "a comb: a 3.5 x 1 back with four 0.5 x 2 teeth"
    circle = ngon(1.0, 1.0, 0.5, 24)
    square = rect(2.6, 0.6, 3.4, 1.4)
    yield "two_holes", [rect(0.0, 0.0, 4.0, 2.0), circle, square], [(1.0, 1.0), (3.0, 1.0)], "a 4 x 2 rectangle with a 24-gon hole and a square hole"
    yield "strip", [rect(0.0, 0.0, 10.0, 0.2)], [], "a thin strip, 10 x 0.2"
    t10 = 2.0 * math.tan(math.radians(10.0))
    yield "small_angle", [[(0.0, 0.0), (3.0, 0.0), (3.0, 1.0), (2.0, 1.0), (2.0, t10)]], [], "a 10 degree input angle at the origin"
    yield "large", [rect(0.0, 0.0, 10.0, 10.0), ngon(3.0, 3.0, 1.0, 24), ngon(6.5, 7.0, 1.5, 24), rect(6.0, 1.5, 8.0, 3.5)], [(3.0, 3.0), (6.5, 7.0), (7.0, 2.5)], "a 10 x 10 rectangle with three holes, for speed runs"


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "cad_fixtures", "regions")
    os.makedirs(out, exist_ok=True)
    for name, loops, holes, comment in regions():
        path = os.path.join(out, name + ".poly")
        with open(path, "w") as f:
            f.write(poly_text(name, loops, holes, comment))
        print(path)


if __name__ == "__main__":
    main()
