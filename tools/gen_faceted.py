#!/usr/bin/env python3
"""Faceted closed surfaces as CAD systems export them (binary STL), for tools/bench_faceted.sh:
a 105-gon cylinder with caps fanned from one rim vertex (416 triangles), 15- and 64-gon tubes
(the 64-gon one thin), and trimesh's torus, capsule, cone, UV sphere and a long cylinder (each
also written as .off, which TetGen reads). Usage: gen_faceted.py DIR (needs numpy and trimesh)."""
import math, os, struct, sys
import trimesh


def write_stl(path, tris):
    with open(path, 'wb') as f:
        f.write(b'\0' * 80)
        f.write(struct.pack('<I', len(tris)))
        for a, b, c in tris:
            u = [b[i] - a[i] for i in range(3)]
            v = [c[i] - a[i] for i in range(3)]
            n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
            l = math.sqrt(sum(x * x for x in n)) or 1.0
            f.write(struct.pack('<12fH', *(x / l for x in n), *a, *b, *c, 0))


def ring(r, z, n):
    return [(r * math.cos(2 * math.pi * i / n), r * math.sin(2 * math.pi * i / n), z) for i in range(n)]


def cylinder(n, r=10.0, h=30.0):
    lo, hi, t = ring(r, 0, n), ring(r, h, n), []
    for i in range(n):
        j = (i + 1) % n
        t += [(lo[i], lo[j], hi[j]), (lo[i], hi[j], hi[i])]
    for k in range(1, n - 1):
        t += [(lo[0], lo[k + 1], lo[k]), (hi[0], hi[k], hi[k + 1])]
    return t


def tube(n, r0, r1, h):
    o0, o1, i0, i1, t = ring(r1, 0, n), ring(r1, h, n), ring(r0, 0, n), ring(r0, h, n), []
    for i in range(n):
        j = (i + 1) % n
        t += [(o0[i], o0[j], o1[j]), (o0[i], o1[j], o1[i]), (i0[i], i1[j], i0[j]), (i0[i], i1[i], i1[j])]
        t += [(o0[i], i0[i], i0[j]), (o0[i], i0[j], o0[j]), (o1[i], o1[j], i1[j]), (o1[i], i1[j], i1[i])]
    return t


def main(out):
    os.makedirs(out, exist_ok=True)
    shapes = {'cyl105': cylinder(105), 'tube15': tube(15, 5, 10, 40), 'tube64': tube(64, 9.5, 10, 40)}
    for name, tris in shapes.items():
        write_stl(f'{out}/{name}.stl', tris)
    c = trimesh.creation
    more = {
        'tm_torus': c.torus(major_radius=20, minor_radius=2, major_sections=96, minor_sections=24),
        'tm_capsule': c.capsule(height=30, radius=4, count=[64, 32]),
        'tm_cone': c.cone(radius=10, height=3, sections=128),
        'tm_uvsphere': c.uv_sphere(radius=10, count=[48, 48]),
        'tm_cyl200': c.cylinder(radius=5, height=80, sections=200),
    }
    for name, m in more.items():
        m.export(f'{out}/{name}.stl')
    for name in list(shapes) + list(more):
        trimesh.load(f'{out}/{name}.stl').export(f'{out}/{name}.off')


if __name__ == '__main__':
    main(sys.argv[1] if len(sys.argv) > 1 else '/tmp/faceted')
