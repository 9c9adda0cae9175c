#!/usr/bin/env bash
# Issue 14's speed line: fepre's read + tessellate + certify against OpenCASCADE's read +
# BRepMesh at the same linear deflection, every STEP file of the corpus, in one run. Per file:
# fepre's phases (from `fepre tessellate --json`) and process wall time, OCC's read and mesh
# seconds (timed inside one Python process, start-up not counted), the ratio, both triangle
# counts; then totals and the overall ratio fepre / OCC. See tools/ref/occ_tessellate_time.py.
#
# Usage: tools/bench_tessellate_occ.sh [--angle RAD] [--parallel] [--repeat N] [--warm-up] [--timeout S]
#                                      [--json FILE] [CORPUS_DIR]
#   default corpus: $FEPRE_CORPUS, else ../shared/cad_corpus beside the checkout
#   Python with cadquery-ocp: $OCP_PYTHON, else .venv/bin/python in the checkout, else python3
#   cargo's target folder: $CARGO_TARGET_DIR, else target/ in the checkout
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
corpus="${FEPRE_CORPUS:-$root/../shared/cad_corpus}"
args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --angle|--timeout|--json|--repeat) args+=("$1" "$2"); shift 2 ;;
    --parallel|--warm-up) args+=("$1"); shift ;;
    *) corpus="$1"; shift ;;
  esac
done
[ -d "$corpus" ] || { echo "no corpus at $corpus (set FEPRE_CORPUS or pass the folder)"; exit 1; }
py="${OCP_PYTHON:-}"
if [ -z "$py" ]; then
  if [ -x "$root/.venv/bin/python" ]; then py="$root/.venv/bin/python"; else py=python3; fi
fi
"$py" -c 'import OCP' 2>/dev/null || { echo "$py cannot import OCP (pip install cadquery-ocp; or set OCP_PYTHON)"; exit 1; }
target="${CARGO_TARGET_DIR:-$root/target}"
cargo build --release --quiet --manifest-path "$root/Cargo.toml" --bin fepre
exec "$py" "$root/tools/ref/occ_tessellate_time.py" "$target/release/fepre" "$corpus" "${args[@]}"
