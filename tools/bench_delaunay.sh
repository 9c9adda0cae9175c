#!/usr/bin/env bash
# Delaunay tetrahedralization, whole process, in one run: fepre against `tetgen -NEF` and CGAL's
# Delaunay_triangulation_3 (shared/tools/cgal_ref/delaunay3) on the same inputs. Prints median
# wall seconds, peak MiB and the ratios fepre/CGAL and fepre/TetGen.
#
# Usage: tools/bench_delaunay.sh [-n RUNS] [--threads N] [INPUT ...]
#   INPUT: names in shared/tools/data (default: rand_1e5 rand_1e6 grid_50); fepre and TetGen read
#   INPUT.node, CGAL reads INPUT.xyz (the same points).
# Needs: cargo build --release; shared/tools/install.sh and gen/make_all.sh run.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
shared="${FEPRE_SHARED:-$root/../shared}"
data="$shared/tools/data"
runs=5
threads=1
inputs=()
while [ $# -gt 0 ]; do
  case "$1" in
    -n) runs="$2"; shift 2 ;;
    --threads) threads="$2"; shift 2 ;;
    *) inputs+=("$1"); shift ;;
  esac
done
[ ${#inputs[@]} -eq 0 ] && inputs=(rand_1e5 rand_1e6 grid_50)
fepre="$root/target/release/fepre"
cgal="$shared/tools/cgal_ref/delaunay3"
timeit="$shared/tools/bench/timeit.py"
[ -x "$fepre" ] || { echo "build first: cargo build --release"; exit 1; }
[ -x "$cgal" ] || { echo "missing $cgal: run shared/tools/install.sh"; exit 1; }
command -v tetgen > /dev/null || { echo "tetgen is not installed"; exit 1; }
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
field() { python3 -c 'import json,sys; print(json.loads(open(sys.argv[1]).read().splitlines()[-1])[sys.argv[2]])' "$1" "$2"; }
printf '%-10s %-8s %10s %10s %10s %10s\n' input tool wall_s peak_MiB vs_CGAL vs_TetGen
for name in "${inputs[@]}"; do
  node="$data/$name.node"; xyz="$data/$name.xyz"
  [ -f "$node" ] && [ -f "$xyz" ] || { echo "missing $node or $xyz: run shared/tools/gen/make_all.sh"; exit 1; }
  # each tool: one warm-up, then RUNS counted runs, median quoted (timeit.py)
  python3 "$timeit" -n "$runs" --json "$tmp/f.json" -- "$fepre" delaunay "$node" --threads "$threads" > /dev/null
  python3 "$timeit" -n "$runs" --json "$tmp/t.json" -- tetgen -NEFQ "$node" > /dev/null
  python3 "$timeit" -n "$runs" --json "$tmp/c.json" -- "$cgal" "$xyz" > /dev/null
  fw=$(field "$tmp/f.json" wall); tw=$(field "$tmp/t.json" wall); cw=$(field "$tmp/c.json" wall)
  fm=$(field "$tmp/f.json" maxrss_mib); tm=$(field "$tmp/t.json" maxrss_mib); cm=$(field "$tmp/c.json" maxrss_mib)
  r() { python3 -c "print(f'{$1/$2:.3f}')"; }
  printf '%-10s %-8s %10.3f %10.1f %10s %10s\n' "$name" fepre "$fw" "$fm" "$(r "$fw" "$cw")" "$(r "$fw" "$tw")"
  printf '%-10s %-8s %10.3f %10.1f\n' "$name" TetGen "$tw" "$tm"
  printf '%-10s %-8s %10.3f %10.1f\n' "$name" CGAL "$cw" "$cm"
  printf '%-10s memory fepre/CGAL %.3f\n' "$name" "$(python3 -c "print($fm/$cm)")"
done
