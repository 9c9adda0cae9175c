#!/usr/bin/env bash
# Dirty input at the speed of clean input (issue 70, item 5): whole-process times of
#   - `fepre inspect --json` on the mutated surfaces of shared/fuzz/ beside trimesh's report
#     on the same files (tools/bench_inspect.sh, the ratio);
#   - `fepre mesh --method octree` at its default cell on them and on three triangle soups of
#     100 random triangles in the unit cube (seeds 1-3, written here);
#   - tools/fuzz_mutate.py: 60 mutations each of featuretype.STL, plc.off and fandisk.obj,
#     inspect and octree, the slowest and how many passed 10 s.
#
# Usage: tools/bench_dirty.sh [-n RUNS] [--no-fuzz]
# Needs: a release build, python with trimesh (.venv or FEPRE_PYTHON), shared/tools/data.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
shared="${FEPRE_SHARED:-$root/../shared}"
runs=3
if [ "${1:-}" = "-n" ]; then runs="$2"; shift 2; fi
fepre="$root/target/release/fepre"
timeit="$shared/tools/bench/timeit.py"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
"$root/tools/bench_inspect.sh" -n "$runs" "$shared"/fuzz/*.stl "$shared"/fuzz/*.off
for s in 1 2 3; do
  python3 - "$tmp/soup$s.stl" "$s" <<'PY'
import random, sys
r = random.Random(int(sys.argv[2]))
with open(sys.argv[1], "w") as f:
    f.write("solid soup\n")
    for _ in range(100):
        f.write(" facet normal 0 0 0\n  outer loop\n")
        for _ in range(3):
            f.write("   vertex %f %f %f\n" % (r.random(), r.random(), r.random()))
        f.write("  endloop\n endfacet\n")
    f.write("endsolid soup\n")
PY
done
printf "%-28s %10s %10s  %s\n" "octree, default cell" "seconds" "tets" "cell chosen"
for f in "$shared"/fuzz/*.stl "$shared"/fuzz/*.off "$tmp"/soup*.stl; do
  python3 - "$fepre" "$f" "$tmp/o.vtu" <<'PY'
import json, os, subprocess, sys, time
t = time.monotonic()
out = subprocess.run([sys.argv[1], "mesh", sys.argv[2], "--method", "octree", "-o", sys.argv[3], "--json"], capture_output=True, text=True).stdout
wall = time.monotonic() - t
r = json.loads(out)
o = r.get("octree") or {}
print("%-28s %10.2f %10d  %d tries, kept %.4g" % (os.path.basename(sys.argv[2]), wall, r.get("tets", 0), len(o.get("cell_tries") or []), o.get("cell_size", 0)))
PY
done
if [ "${1:-}" != "--no-fuzz" ]; then
  python3 "$root/tools/fuzz_mutate.py" --fepre "$fepre" --count 60 --limit 10 "$shared/cad_corpus/featuretype.STL" "$shared/tools/data/plc.off" "$shared/cad_corpus/fandisk.obj" | tail -1
fi
