#!/bin/bash
# Usage: tools/bench_step_tetgen.sh [FILE ...]   (after cargo build --release; needs tetgen and
# shared/tools/cgal_ref/tetquality). Every corpus STEP file by default.
# For each STEP part: `fepre run` on a job that writes the tet mesh and the surface it meshed
# (defaults: size diagonal / 25), then `tetgen -pq1.414/18` on that same surface; both meshes
# judged by tetquality. One line a file: tets, min and max dihedral, tets under 5 and under 10
# degrees, seconds, for fepre and for TetGen; then how many of the files each meshed with every
# dihedral angle >= 10 degrees. Any STEP, STL or OBJ files: `tools/bench_step_tetgen.sh
# DIR/*` measures a directory of real parts.
root="$(cd "$(dirname "$0")/.." && pwd)"; shared="${FEPRE_SHARED:-$root/../shared}"
F=$root/target/release/fepre; J=$shared/tools/cgal_ref/tetquality; C=${FEPRE_CORPUS:-$shared/cad_corpus}
files=("$@"); [ ${#files[@]} -eq 0 ] && files=($C/*.step $C/*.stp $C/*.STEP)
w=$(mktemp -d); trap 'rm -rf "$w"' EXIT
judge() { $J "$1" 2>/dev/null | awk '/^tets /{t=$2} /^min_dihedral_deg /{a=$2} /^max_dihedral_deg /{b=$2} /^tets_min_dihedral_below_5 /{c=$2} /^tets_min_dihedral_below_10 /{d=$2} END{if (t=="") print "- - - - -"; else printf "%s %.2f %.2f %s %s", t, a, b, c, d}'; }
printf "%-28s | %-40s | %-40s\n" file "fepre: tets min max <5 <10 s" "tetgen: tets min max <5 <10 s"
nf=0; gf=0; gt=0
for f in "${files[@]}"; do
  [ -f "$f" ] || continue
  n=$(basename "$f"); rm -f $w/*
  printf '[input]\nfile = "%s"\n[require]\nmin_dihedral = 0\n[[output]]\nfile = "s.obj"\n[[output]]\nfile = "m.mesh"\n' "$f" > $w/job.toml
  s=$(date +%s.%N); (cd $w && timeout 300 $F run job.toml > /dev/null 2>&1); rc=$?; e=$(date +%s.%N)
  if [ $rc -ne 0 ] || [ ! -f $w/m.mesh ]; then printf "%-28s | fepre exit %s\n" "$n" "$rc"; nf=$((nf + 1)); continue; fi
  a="$(judge $w/m.mesh) $(printf %.2f $(echo "$e - $s" | bc))"
  $F convert $w/s.obj $w/s.poly > /dev/null 2>&1
  s=$(date +%s.%N); timeout 300 tetgen -pq1.414/18Q $w/s.poly > /dev/null 2>&1; rc=$?; e=$(date +%s.%N)
  if [ $rc -ne 0 ] || [ ! -f $w/s.1.ele ]; then b="tetgen exit $rc"; else b="$(judge $w/s.1.ele) $(printf %.2f $(echo "$e - $s" | bc))"; fi
  printf "%-28s | %-40s | %-40s\n" "$n" "$a" "$b"
  nf=$((nf + 1))
  [ "$(echo "$a" | awk '{print ($2 >= 10)}')" = 1 ] && gf=$((gf + 1))
  [ "$(echo "$b" | awk '$1 ~ /^[0-9]+$/ {print ($2 >= 10)}')" = 1 ] && gt=$((gt + 1))
done
echo "every dihedral angle >= 10 degrees (tetquality): fepre $gf of $nf files, tetgen -pq1.414/18 $gt of $nf"
