#!/usr/bin/env bash
# Whole-process timing of `fepre inspect --json` against trimesh (tools/ref/trimesh_report.py:
# load, weld, edge counts, bodies, volume) on the same surfaces, in one run, with the ratio.
# fepre does more (exact self-intersections, vertex-manifoldness, nesting); pass
# --no-self-intersections in FEPRE_ARGS to compare like with like.
#
# Usage: tools/bench_inspect.sh [-n RUNS] [FILE ...]
#   default files: shared/tools/data/plc_fine.stl and the corpus meshes
# Needs: a release build (cargo build --release), python with trimesh (.venv or FEPRE_PYTHON).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
shared="${FEPRE_SHARED:-$root/../shared}"
runs=5
if [ "${1:-}" = "-n" ]; then runs="$2"; shift 2; fi
files=("$@")
if [ ${#files[@]} -eq 0 ]; then
  files=("$shared/tools/data/plc_fine.stl" "$shared/cad_corpus/bunny_binary.stl" "$shared/cad_corpus/fandisk.obj" "$shared/cad_corpus/Duck.glb")
fi
python="${FEPRE_PYTHON:-$root/.venv/bin/python}"
fepre="$root/target/release/fepre"
timeit="$shared/tools/bench/timeit.py"
[ -x "$fepre" ] || { echo "build first: cargo build --release"; exit 1; }
median() { python3 -c 'import json,sys; print(json.loads(open(sys.argv[1]).read().splitlines()[-1])["wall"])' "$1"; }
printf "%-28s %12s %12s %8s\n" "input" "fepre s" "trimesh s" "ratio"
for f in "${files[@]}"; do
  a=$(mktemp); b=$(mktemp)
  python3 "$timeit" -n "$runs" --json "$a" -- "$fepre" inspect --json ${FEPRE_ARGS:-} "$f" > /dev/null
  python3 "$timeit" -n "$runs" --json "$b" -- "$python" -W ignore "$root/tools/ref/trimesh_report.py" "$f" > /dev/null
  fa=$(median "$a"); fb=$(median "$b")
  printf '%-28s %12.4f %12.4f %8.3f\n' "$(basename "$f")" "$fa" "$fb" "$(python3 -c "print($fa/$fb)")"
  rm -f "$a" "$b"
done
