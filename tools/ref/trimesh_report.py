#!/usr/bin/env python3
"""Independent surface report with trimesh, for comparison with `fepre inspect --json`.

Usage: trimesh_report.py FILE...   -> one JSON object per line:
  file, file_vertices, triangles, welded_vertices, open_edges, nonmanifold_edges,
  components (bodies: face-connected through shared edges), closed, volume (if closed), bbox

The scene is flattened with node transforms applied (glTF instances repeated); vertices are
merged as trimesh does on load (process=True, merge_tex and merge_norm so that only positions
count), the same welding the corpus README's table was measured with.
"""
import json
import sys

import numpy as np
import trimesh


def report(path):
    loaded = trimesh.load(path, force=None, process=False)
    if isinstance(loaded, trimesh.Scene):
        mesh = loaded.dump(concatenate=True)
    else:
        mesh = loaded
    file_vertices = len(mesh.vertices)
    mesh = trimesh.Trimesh(vertices=np.asarray(mesh.vertices), faces=np.asarray(mesh.faces), process=False)
    mesh.merge_vertices(merge_tex=True, merge_norm=True)
    edges = mesh.edges_sorted
    uniq, counts = np.unique(edges, axis=0, return_counts=True)
    bodies = mesh.split(only_watertight=False)
    closed = bool((counts == 2).all())
    out = {
        "file": path,
        "file_vertices": file_vertices,
        "triangles": int(len(mesh.faces)),
        "welded_vertices": int(len(mesh.vertices)),
        "open_edges": int((counts == 1).sum()),
        "nonmanifold_edges": int((counts > 2).sum()),
        "components": int(len(bodies)),
        "closed": closed,
        "volume": float(mesh.volume) if closed else None,
        "bbox": mesh.bounds.tolist(),
    }
    return out


if __name__ == "__main__":
    for p in sys.argv[1:]:
        print(json.dumps(report(p)))
