#!/bin/bash
# Usage: tools/bench_faceted.sh [DIR] (after cargo build --release; needs python3 with trimesh, tetgen
# and shared/tools/cgal_ref/tetquality). Writes the faceted surfaces of tools/gen_faceted.py into DIR
# (default /tmp/faceted) and meshes each with fepre's defaults (written whatever its angles) and
# with tetgen -pq1.414/18 in the same run; prints tets, min dihedral by tetquality, seconds, ratio.
root="$(cd "$(dirname "$0")/.." && pwd)"; shared="${FEPRE_SHARED:-$root/../shared}"
F=$root/target/release/fepre; J=$shared/tools/cgal_ref/tetquality; D=${1:-/tmp/faceted}
${FEPRE_PYTHON:-python3} "$root/tools/gen_faceted.py" "$D" || exit 1
q() { $J "$1" 2>/dev/null | awk '/^tets /{t=$2}/^min_dihedral_deg/{d=$2}END{printf "%d tets %.2f deg", t, d}'; }
for f in "$D"/*.stl; do b=${f%.stl}; n=$(basename $b)
  s=$(date +%s.%N); timeout 300 $F mesh $f -o $b.mesh --require-min-dihedral 0 > /dev/null 2>&1; e=$(date +%s.%N); tf=$(echo "$e - $s" | bc)
  s=$(date +%s.%N); timeout 300 tetgen -pq1.414/18Q $b.off > /dev/null 2>&1; e=$(date +%s.%N); tt=$(echo "$e - $s" | bc)
  echo "$n: fepre $(q $b.mesh) ${tf} s | tetgen $(q $b.1.ele) ${tt} s | time ratio $(echo "scale=2; $tf / $tt" | bc)"
done
