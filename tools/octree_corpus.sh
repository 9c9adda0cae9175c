#!/usr/bin/env bash
# Uniform octree meshing (isosurface stuffing) of the corpus: every closed mesh and STEP solid
# and the dirty meshes, at cell size diagonal / DIV (default 100; -d 0: the default cell, which
# fepre chooses to hold every solid's volume within 1 %). Per file: tets, the shared
# judge's min/max dihedral (shared/tools/cgal_ref/tetquality), the volume against the input's
# (divergence theorem on the surface meshed; for a STEP part the certified tessellation's;
# marked w: where the input has no exact volume, open or overlapping, the volume its winding
# number encloses, from the report),
# the sampled Hausdorff distance and its upper bound against the cell size (status ok: angles
# inside [10.7°, 164.8°], volume within 1 %, the bound within the cell, each solid's own), unresolved
# feature edges, seconds. With -g: graded octrees, and the uniform mesh's tet count at the same
# cell size beside them (`uniform` and `ratio` = graded / uniform).
#
# Usage: tools/octree_corpus.sh [-d DIV] [-g] [FILE ...]   (default: the files of the issue)
# Needs: cargo build --release; FEPRE_CORPUS or ../shared/cad_corpus.
set -uo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
shared="${FEPRE_SHARED:-$root/../shared}"
corpus="${FEPRE_CORPUS:-$shared/cad_corpus}"
fepre="${FEPRE:-${CARGO_TARGET_DIR:-$root/target}/release/fepre}"
judge="$shared/tools/cgal_ref/tetquality"
div=100
graded=0
files=()
while [ $# -gt 0 ]; do
  case "$1" in
    -d) div="$2"; shift 2 ;;
    -g) graded=1; shift ;;
    *) files+=("$1"); shift ;;
  esac
done
[ -x "$fepre" ] || { echo "build first: cargo build --release"; exit 1; }
[ -x "$judge" ] || make -C "$shared/tools/cgal_ref" tetquality > /dev/null
if [ ${#files[@]} -eq 0 ]; then
  for f in "$corpus"/*.STL "$corpus"/*.obj "$corpus"/*.stl "$corpus"/*.glb "$corpus"/*.step "$corpus"/*.stp "$corpus"/*.STEP; do
    [ -f "$f" ] && files+=("$(basename "$f")")
  done
fi
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
grading=(); [ "$graded" = 1 ] && grading=(--octree-grading graded)
if [ "$graded" = 1 ]; then
  printf '%-28s %8s %8s %8s %8s %6s %9s %9s %10s %10s %6s %7s %s\n' file tets uniform ratio min_dih max_dih vol_err% cell hausdorff bound unres seconds status
else
  printf '%-28s %8s %8s %8s %9s %9s %10s %10s %6s %7s %s\n' file tets min_dih max_dih vol_err% cell hausdorff bound unres seconds status
fi
for name in "${files[@]}"; do
  f="$corpus/$name"
  # the cell size: the diagonal over DIV (the default run's first cell is diagonal / 25;
  # -d 0: the default cell, chosen to hold every solid's volume; that first run is the result)
  start=$(date +%s.%N)
  if ! "$fepre" mesh "$f" -o "$tmp/a.mesh" --method octree "${grading[@]}" --json > "$tmp/a.json" 2> "$tmp/a.err"; then
    printf '%-28s %s\n' "$name" "error: $(head -c 300 "$tmp/a.err" | tr '\n' ' ')"
    continue
  fi
  diag=$(python3 -c 'import json,sys; o=json.load(open(sys.argv[1]))["octree"]; print(25 * (o.get("cell_tries") or [{"cell": o["cell_size"]}])[0]["cell"])' "$tmp/a.json")
  if [ "$div" = 0 ]; then
    end=$(date +%s.%N)
    mv "$tmp/a.mesh" "$tmp/o.mesh"; mv "$tmp/a.json" "$tmp/o.json"; mv "$tmp/a.err" "$tmp/o.err"
    rc=0
  else
    start=$(date +%s.%N)
    "$fepre" mesh "$f" -o "$tmp/o.mesh" --method octree "${grading[@]}" --size "$(python3 -c "print($diag/$div)")" --json > "$tmp/o.json" 2> "$tmp/o.err"
    rc=$?
    end=$(date +%s.%N)
  fi
  if [ "$rc" = 0 ]; then
    uniform=""
    if [ "$graded" = 1 ]; then
      "$fepre" mesh "$f" -o "$tmp/u.mesh" --method octree --size "$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["octree"]["cell_size"])' "$tmp/o.json")" --json > "$tmp/u.json" 2> /dev/null
      uniform=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["octree"]["tets"])' "$tmp/u.json" 2> /dev/null)
    fi
    read -r tets lo hi < <("$judge" "$tmp/o.mesh" | awk '$1=="tets"{t=$2} $1=="min_dihedral_deg"{a=$2} $1=="max_dihedral_deg"{b=$2} END{print t, a, b}')
    python3 - "$tmp/o.json" "$name" "$tets" "$lo" "$hi" "$start" "$end" "$uniform" <<'PY'
import json,sys
j=json.load(open(sys.argv[1])); o=j["octree"]; d=o["deviation"]
name,tets,lo,hi,s,e,uni=sys.argv[2:9]
# an input without an exact volume (open, overlapping): the winding number's volume, which
# the report carries for it
w=o.get("winding_volume")
ref=w["volume"] if w else o["input_volume"]
ve=100*(o["volume"]-ref)/abs(ref)
# each solid's bound against its own cell (the default cell is chosen solid by solid)
ok=float(lo)>=10.7 and float(hi)<=164.8 and abs(ve)<=1.0 and o["bound_over_cell"]<=1.0
if uni:
    name=f'{name:<28} {tets:>8} {uni:>8} {int(tets)/int(uni):6.3f}'
else:
    name=f'{name:<28} {tets:>8}'
print(f'{name} {float(lo):8.2f} {float(hi):8.2f} {ve:8.3f}{"w" if ref is not o["input_volume"] else " "} {o["cell_size"]:9.3e} {d["hausdorff"]:10.3e} {d["hausdorff_bound"]:10.3e} {d["unresolved_feature_edges"]:6d} {float(e)-float(s):7.2f} {"ok" if ok else "FAIL"}')
PY
  else
    printf '%-28s %s\n' "$name" "error: $(head -c 200 "$tmp/o.err" | tr '\n' ' ')"
  fi
done
