#!/bin/bash
# Usage: tools/mesh_dir.sh DIR [fepre mesh options ...]   (after cargo build --release)
# Meshes every STEP, STL, OBJ and glTF file in DIR with `fepre mesh` (defaults, or the options
# given) and prints one line a file: exit code, tets, smallest and largest dihedral angle, tets
# under 5 degrees (and of those, how many touch no input angle as small), tets under 10
# degrees (likewise), of those the tets that lie between the two sides of an input angle under
# 10 degrees (btw: a thin wedge, a sliver face, a knife edge), seconds, and the error where it
# failed. Then the counts: meshed, with
# every angle >= 10 degrees, those whose tets under 10 degrees all touch an input angle under
# 10 degrees (the solver-grade issue lets the bound give way there), refused. For parts fepre has never seen (a library, another
# export of a data set): the figures the solver-grade issue is judged on. At the defaults a
# mesh with a tet under 1° that touches no input angle under 1° is refused (rc 1, the error
# shown); pass --require-min-dihedral 0 to measure such meshes too.
root="$(cd "$(dirname "$0")/.." && pwd)"; F=${FEPRE:-$root/target/release/fepre}
dir=${1:?usage: tools/mesh_dir.sh DIR [options]}; shift
w=$(mktemp -d); trap 'rm -rf "$w"' EXIT
printf "%-40s %3s %8s %7s %7s %9s %9s %4s %6s  %s\n" file rc tets "min°" "max°" "<5(un)" "<10(un)" btw s error
meshed=0; good=0; explained=0; between=0; refused=0
for f in "$dir"/*; do
  case "${f,,}" in *.step|*.stp|*.stl|*.obj|*.glb|*.gltf) ;; *) continue ;; esac
  s=$(date +%s.%N); timeout 600 "$F" mesh "$f" -o "$w/m.mesh" --json "$@" > "$w/j" 2> "$w/e"; rc=$?; e=$(date +%s.%N)
  line=$(python3 - "$w/j" "$(basename "$f")" "$rc" "$(echo "$e - $s" | bc)" "$w/e" <<'P'
import json, sys
j, n, rc, t, err = sys.argv[1:]
try:
    d = json.load(open(j))
except Exception:
    d = {}
if "tets" in d:
    print("%-40s %3s %8d %7.2f %7.2f %4d(%3d) %4d(%3d) %4d %6.2f" % (n[:40], rc, d["tets"], d["min_dihedral_deg"], d["max_dihedral_deg"], d["tets_under_5_deg"], d["tets_under_5_deg_unexplained"], d["tets_under_10_deg"], d["tets_under_10_deg_unexplained"], d["tets_under_10_deg_between_sides"], float(t)))
else:
    msg = d.get("error") or open(err).read().strip().splitlines()[-1:] or [""]
    msg = msg if isinstance(msg, str) else msg[0]
    msg = " / ".join(l.strip() for l in msg.split(": ", 1)[-1].splitlines())
    print("%-40s %3s %8s %7s %7s %9s %9s %4s %6.2f  %s" % (n[:40], rc, "-", "-", "-", "-", "-", "-", float(t), msg[:150]))
P
)
  echo "$line"
  if [ "$rc" = 0 ]; then
    meshed=$((meshed + 1)); m=$(echo "$line" | awk '{print $4}')
    # the tets under 10 degrees that touch no input angle as small: "N(  U)" in the 7th column
    un=$(echo "$line" | grep -oE '[0-9]+\( *[0-9]+\)' | sed -n 2p | sed -E 's/.*\( *([0-9]+)\)/\1/')
    # of those, the ones between the two sides of an input angle under 10 degrees: the 8th column
    btw=$(echo "$line" | sed -E 's/.*\( *[0-9]+\) +[0-9]+\( *[0-9]+\) +([0-9]+) .*/\1/')
    if [ "$(echo "$m >= 10" | bc)" = 1 ]; then good=$((good + 1)); elif [ "$un" = 0 ]; then explained=$((explained + 1)); elif [ "$un" = "$btw" ]; then between=$((between + 1)); fi
  else refused=$((refused + 1)); fi
done
echo "meshed $meshed, every angle >= 10 degrees $good, and $explained more whose tets under 10 degrees all touch an input angle under 10 degrees (the solver-grade issue's count: $((good + explained)) of $meshed), refused $refused"
echo "and $between more whose tets under 10 degrees each touch an input angle under 10 degrees or lie between its two sides (with them: $((good + explained + between)) of $meshed)"
