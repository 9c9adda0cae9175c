#!/bin/bash
# Usage: tools/bench_real_parts.sh (after cargo build --release; needs tetgen and shared/tools/cgal_ref/tetquality). Prints the surface figures; writes the STEP sweep table, one line a file, to /tmp/rp/sweep.txt.
# real parts: fepre mesh (defaults, but written whatever its angles: --require-min-dihedral 0) vs tetgen -pq1.414/18 on the same surface, judged by tetquality
root="$(cd "$(dirname "$0")/.." && pwd)"; shared="${FEPRE_SHARED:-$root/../shared}"
F=$root/target/release/fepre; J=$shared/tools/cgal_ref/tetquality; C=${FEPRE_CORPUS:-$shared/cad_corpus}
mkdir -p /tmp/rp
cd /tmp/rp
for n in plate_holes.STL fandisk.obj featuretype.STL; do
  b=${n%.*}
  s=$(date +%s.%N); timeout 300 $F mesh $C/$n -o $b.mesh --require-min-dihedral 0 > $b.fepre.txt 2>&1; e=$(date +%s.%N)
  echo "== $n fepre $(echo "$e - $s" | bc) s"; $J $b.mesh | grep -E "^(tets|min_dihedral_deg|max_dihedral_deg|tets_min_dihedral_below_5|max_radius_edge_ratio) "
  $F convert $C/$n $b.poly > /dev/null 2>&1
  s=$(date +%s.%N); timeout 300 tetgen -pq1.414/18Q $b.poly > /dev/null 2>&1; e=$(date +%s.%N)
  echo "== $n tetgen $(echo "$e - $s" | bc) s"; $J $b.1.ele 2>/dev/null | grep -E "^(tets|min_dihedral_deg|max_dihedral_deg|tets_min_dihedral_below_5|max_radius_edge_ratio) "
done
# the step sweep: certify (tessellate) and mesh, by file
S=$shared/step_sweep
: > sweep.txt
for f in $S/*.stp $S/*.step; do [ -f "$f" ] || continue
  n=$(basename $f)
  t=$(timeout 60 $F tessellate $f -o /tmp/rp/s.stl --json 2>/dev/null | python3 -c 'import json,sys
try:
  r=json.load(sys.stdin); print("cert", r["certificate"]["passed"], r["solids"])
except Exception: print("cert fail -")')
  m=$(timeout 60 $F mesh $f -o /tmp/rp/s.mesh --json --require-min-dihedral 0 2>/dev/null | python3 -c 'import json,sys
try:
  r=json.load(sys.stdin); print("mesh %d %.2f %.2f %d %.2f" % (r["tets"], r["min_dihedral_deg"], r["max_dihedral_deg"], r["tets_under_1_deg"], r["seconds"]))
except Exception: print("mesh fail")')
  echo "$n $t $m" >> sweep.txt
done
echo done >> sweep.txt
