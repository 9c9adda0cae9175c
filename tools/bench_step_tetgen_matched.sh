#!/bin/bash
# Usage: tools/bench_step_tetgen_matched.sh [FILE ...]   (after cargo build --release; needs tetgen)
# Speed at a matched tet count: TetGen `-pq1.414/18` meshes the surface fepre makes of each
# corpus STEP part at its default size (diagonal / 25), then `fepre mesh` meshes the part again
# at the size that gives TetGen's tet count (size scaled by the cube root of the count ratio,
# corrected until within 20 %, six tries at most: the count is not monotonic in the size where
# thin walls and narrow faces ask for a share of it). One line a file: TetGen's tets and
# seconds (surface to tets), fepre's size, tets and seconds (STEP file to tets, reading and
# tessellating included), and fepre's time over TetGen's. Runs under a second are timed
# three times and the median kept (a 0.04 s run varies by 10 ms).
root="$(cd "$(dirname "$0")/.." && pwd)"; shared="${FEPRE_SHARED:-$root/../shared}"
F=$root/target/release/fepre; C=${FEPRE_CORPUS:-$shared/cad_corpus}
files=("$@"); [ ${#files[@]} -eq 0 ] && files=($C/*.step $C/*.stp $C/*.STEP)
w=$(mktemp -d); trap 'rm -rf "$w"' EXIT
now() { date +%s.%N; }
# median seconds of a command: once, or three times when under a second
timed() { local s e t1 t2 t3; s=$(now); "$@" > /dev/null 2>&1 || return 1; e=$(now); t1=$(echo "$e - $s" | bc)
  if [ "$(echo "$t1 < 1" | bc)" = 1 ]; then
    s=$(now); "$@" > /dev/null 2>&1; e=$(now); t2=$(echo "$e - $s" | bc)
    s=$(now); "$@" > /dev/null 2>&1; e=$(now); t3=$(echo "$e - $s" | bc)
    printf "%s\n%s\n%s\n" $t1 $t2 $t3 | sort -n | sed -n 2p
  else echo $t1; fi; }
field() { python3 -c "import json,sys; print(json.load(open('$1'))['$2'])" 2>/dev/null; }
printf "%-28s | %-18s | %-30s | %s\n" file "tetgen: tets s" "fepre: size tets s" "fepre/tetgen"
for f in "${files[@]}"; do
  [ -f "$f" ] || continue
  n=$(basename "$f"); rm -f $w/*
  printf '[input]\nfile = "%s"\n[require]\nmin_dihedral = 0\n[[output]]\nfile = "s.obj"\n' "$f" > $w/job.toml
  (cd $w && timeout 300 $F run job.toml > /dev/null 2>&1) || { printf "%-28s | fepre exit\n" "$n"; continue; }
  timeout 300 $F mesh "$f" -o $w/d.mesh --json --require-min-dihedral 0 > $w/d.json 2>/dev/null || { printf "%-28s | fepre mesh exit\n" "$n"; continue; }
  $F convert $w/s.obj $w/s.poly > /dev/null 2>&1
  tt=$(timed timeout 300 tetgen -pq1.414/18Q $w/s.poly); rc=$?
  if [ $rc -ne 0 ] || [ ! -f $w/s.1.ele ]; then printf "%-28s | tetgen fails\n" "$n"; continue; fi
  nt=$(head -1 $w/s.1.ele | awk '{print $1}')
  size=$(field $w/d.json global_size); nf=$(field $w/d.json tets)
  for k in 1 2 3 4 5 6; do
    size=$(python3 -c "print($size * ($nf / $nt) ** (1 / 3))")
    timeout 300 $F mesh "$f" -o $w/m.mesh --size $size --json > $w/m.json 2>/dev/null
    nf=$(field $w/m.json tets)
    [ -z "$nf" ] && break
    python3 -c "import sys; sys.exit(0 if abs($nf / $nt - 1) <= 0.2 else 1)" && break
  done
  [ -z "$nf" ] && { printf "%-28s | fepre exit at size %s\n" "$n" "$size"; continue; }
  tf=$(timed timeout 300 $F mesh "$f" -o $w/m.mesh --size $size)
  printf "%-28s | %8d %8.2f | %8.4f %9d %8.2f | %.2f\n" "$n" "$nt" "$tt" "$size" "$nf" "$tf" "$(echo "$tf / $tt" | bc -l)"
done
