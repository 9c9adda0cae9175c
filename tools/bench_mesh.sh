#!/usr/bin/env bash
# Quality tetrahedral meshing of the generated PLCs, whole process, in one run: fepre mesh
# (keep-surface, sized to a tet count near TetGen's) against TetGen -pq1.414a... and CGAL
# Mesh_3 (shared/tools/cgal_ref/mesh3), each mesh judged by shared/tools/cgal_ref/tetquality.
# Prints median wall seconds, peak MiB, tets, the judge's min/max dihedral and max radius-edge,
# and the ratios fepre/TetGen and fepre/CGAL.
#
# With --octree, fepre meshes by isosurface stuffing (--method octree, uniform cell sized to a
# tet count near TetGen's) and the line also gives tets per second and fepre's rate over
# TetGen's (issue 15: at least 5).
#
# Usage: tools/bench_mesh.sh [-n RUNS] [--no-cgal] [--octree] [INPUT ...]   INPUT: plc, plc_fine (default both)
# Needs: cargo build --release; shared/tools/install.sh and gen/make_all.sh run.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
shared="${FEPRE_SHARED:-$root/../shared}"
data="$shared/tools/data"
runs=5
cgal_on=1
octree=0
inputs=()
while [ $# -gt 0 ]; do
  case "$1" in
    -n) runs="$2"; shift 2 ;;
    --no-cgal) cgal_on=0; shift ;;
    --octree) octree=1; shift ;;
    *) inputs+=("$1"); shift ;;
  esac
done
[ ${#inputs[@]} -eq 0 ] && inputs=(plc plc_fine)
fepre="${CARGO_TARGET_DIR:-$root/target}/release/fepre"
judge="$shared/tools/cgal_ref/tetquality"
cgal="$shared/tools/cgal_ref/mesh3"
timeit="$shared/tools/bench/timeit.py"
[ -x "$fepre" ] || { echo "build first: cargo build --release"; exit 1; }
[ -x "$judge" ] || { echo "missing $judge: run shared/tools/install.sh"; exit 1; }
command -v tetgen > /dev/null || { echo "tetgen is not installed"; exit 1; }
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
field() { python3 -c 'import json,sys; print(json.loads(open(sys.argv[1]).read().splitlines()[-1])[sys.argv[2]])' "$1" "$2"; }
q() { "$judge" "$1" | awk -v k="$2" '$1 == k { print $2 }'; }
printf '%-9s %-7s %9s %9s %8s %8s %8s %8s %9s %9s\n' input tool wall_s peak_MiB tets min_dih max_dih max_re vs_TetGen vs_CGAL
for name in "${inputs[@]}"; do
  case "$name" in
    plc) size=0.13; area=0.0005; csize=0.1; osize=0.134 ;;
    plc_fine) size=0.07; area=0.000065; csize=0.05; osize=0.0714 ;;
    *) echo "unknown input $name"; exit 1 ;;
  esac
  [ -f "$data/$name.poly" ] || { echo "missing $data/$name.poly: run shared/tools/gen/make_all.sh"; exit 1; }
  cp "$data/$name.poly" "$data/$name.off" "$tmp/"
  if [ "$octree" = 1 ]; then
    python3 "$timeit" -n "$runs" --json "$tmp/f.json" -- "$fepre" mesh "$tmp/$name.poly" -o "$tmp/fepre.mesh" --size "$osize" --method octree > /dev/null
  else
    python3 "$timeit" -n "$runs" --json "$tmp/f.json" -- "$fepre" mesh "$tmp/$name.poly" -o "$tmp/fepre.mesh" --size "$size" --keep-surface > /dev/null
  fi
  python3 "$timeit" -n "$runs" --cwd "$tmp" --json "$tmp/t.json" -- tetgen "-pq1.414a${area}Q" "$name.poly" > /dev/null
  fw=$(field "$tmp/f.json" wall); tw=$(field "$tmp/t.json" wall)
  fm=$(field "$tmp/f.json" maxrss_mib); tm=$(field "$tmp/t.json" maxrss_mib)
  cw=""
  if [ "$cgal_on" = 1 ] && [ -x "$cgal" ]; then
    python3 "$timeit" -n "$runs" --json "$tmp/c.json" -- "$cgal" "$tmp/$name.off" "$tmp/cgal.mesh" --size "$csize" --seed 0 > /dev/null
    cw=$(field "$tmp/c.json" wall); cm=$(field "$tmp/c.json" maxrss_mib)
  fi
  r() { python3 -c "print(f'{$1/$2:.3f}')"; }
  line() { printf '%-9s %-7s %9.3f %9.1f %8s %8s %8s %8s %9s %9s\n' "$name" "$1" "$2" "$3" "$(q "$4" tets)" "$(q "$4" min_dihedral_deg)" "$(q "$4" max_dihedral_deg)" "$(q "$4" max_radius_edge_ratio)" "${5:-}" "${6:-}"; }
  line fepre "$fw" "$fm" "$tmp/fepre.mesh" "$(r "$fw" "$tw")" "${cw:+$(r "$fw" "$cw")}"
  line TetGen "$tw" "$tm" "$tmp/$name.1"
  [ -n "$cw" ] && line CGAL "$cw" "$cm" "$tmp/cgal.mesh"
  if [ "$octree" = 1 ]; then
    ft=$(q "$tmp/fepre.mesh" tets); tt=$(q "$tmp/$name.1" tets)
    python3 -c "f=$ft/$fw; t=$tt/$tw; print(f'$name octree: {f:,.0f} tets/s, TetGen {t:,.0f} tets/s: {f/t:.2f}x')"
  fi
  echo "$name fepre: radius-edge over 2: $(q "$tmp/fepre.mesh" tets_radius_edge_over_2) tets; TetGen: $(q "$tmp/$name.1" tets_radius_edge_over_2)"
done
