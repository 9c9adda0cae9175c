#!/usr/bin/env bash
# Records what fepre writes and reports for every input, and compares two records: the check
# that a restructuring changed no output (mesh and deck bytes, report values).
#
#   tools/same_outputs.sh record DIR [FILE ...]   run $FEPRE (default target/release/fepre) on
#                                                 every corpus and step_sweep file (or the FILEs)
#                                                 and the bundled jobs; keep outputs in DIR
#   tools/same_outputs.sh compare DIR_A DIR_B     byte-compare the meshes and decks; compare the
#                                                 JSON reports with timing fields and `warnings`
#                                                 left out; the exit codes; the standard error
#                                                 with its timing figures masked
#
# Per STEP file: cad-info, tessellate (.stl), mesh (Delaunay, .msh), mesh2d (planar
# faces, .vtu). Per surface mesh (STL, OBJ, glTF): inspect, mesh (Delaunay, .msh), mesh
# --method octree (.vtu), convert (.msh). Per job (cad_fixtures/*.toml): run, with every file
# it writes. Every command runs with --json where it has it. Typical use:
#
#   FEPRE=/tmp/old/fepre tools/same_outputs.sh record /tmp/before
#   cargo build --release && tools/same_outputs.sh record /tmp/after
#   tools/same_outputs.sh compare /tmp/before /tmp/after
#
# Needs: FEPRE_CORPUS or ../shared/cad_corpus, and ../shared/step_sweep (FEPRE_SWEEP).
# JOBS=N runs N files at once (default 2); TIMEOUT=S bounds each command (default 900).
set -uo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
shared="${FEPRE_SHARED:-$root/../shared}"
# real paths: reports echo the input's path, and two records must name it alike
corpus="$(realpath -m "${FEPRE_CORPUS:-$shared/cad_corpus}")"
sweep="$(realpath -m "${FEPRE_SWEEP:-$shared/step_sweep}")"
fepre="${FEPRE:-${CARGO_TARGET_DIR:-$root/target}/release/fepre}"

usage() { sed -n 2,22p "$0" | sed 's/^# \{0,1\}//'; exit 2; }

# One input: every command of its kind, each into DIR/<file>/<command>.{out,err,rc,...}.
record_one() {
  local f="$1" dir="$2" b d lower
  # DIR/<folder>/<file>: the same name in two folders (corpus and sweep) kept apart
  b="$(basename "$f")"; d="$dir/$(basename "$(dirname "$f")")/$b"; mkdir -p "$d"; lower="${b,,}"
  run() {  # run NAME ARGS...: stdout, stderr and exit code of one command
    local name="$1"; shift
    (cd "$d" && timeout "${TIMEOUT:-900}" "$fepre" "$@" > "$name.out" 2> "$name.err"; echo $? > "$name.rc")
  }
  case "$lower" in
    *.step|*.stp)
      run cad-info cad-info "$f" --json
      run tessellate tessellate "$f" -o tessellate.stl --json
      run mesh mesh "$f" -o mesh.msh --json
      run mesh2d mesh2d "$f" --all-planar -o mesh2d.vtu --json
      ;;
    *.stl|*.obj|*.glb|*.gltf)
      run inspect inspect "$f" --json
      run mesh mesh "$f" -o mesh.msh --json
      run octree mesh "$f" -o octree.vtu --method octree --json
      run convert convert "$f" convert.msh
      ;;
    *.toml)
      # a job writes next to its own paths: run a copy with its input beside it
      # (outputs go to its ../target: a copy in DIR/<job>/job with DIR/<job>/target beside it)
      mkdir -p "$d/job" "$d/target"
      cp "$(dirname "$f")"/* "$d/job/" 2>/dev/null
      run run run "$d/job/$b" --json
      rm -rf "$d/job"
      ;;
  esac
}

record() {
  local dir="${1:?usage: record DIR [FILE ...]}"; shift
  [ -x "$fepre" ] || { echo "error: $fepre is not built (cargo build --release, or set FEPRE)"; exit 1; }
  mkdir -p "$dir"
  local files=("$@")
  if [ ${#files[@]} -eq 0 ]; then
    for f in "$corpus"/* "$sweep"/* "$root"/cad_fixtures/*.toml; do
      case "${f,,}" in *.step|*.stp|*.stl|*.obj|*.glb|*.gltf|*.toml) files+=("$f") ;; esac
    done
  fi
  for i in "${!files[@]}"; do files[$i]="$(realpath "${files[$i]}")"; done
  export -f record_one; export fepre
  printf '%s\n' "${files[@]}" | xargs -P "${JOBS:-2}" -I{} bash -c 'record_one "$1" "$2"' _ {} "$dir"
  echo "recorded ${#files[@]} inputs in $dir with $fepre"
}

compare() {
  local a="${1:?usage: compare DIR_A DIR_B}" b="${2:?usage: compare DIR_A DIR_B}"
  python3 - "$a" "$b" <<'PY'
import json, os, re, sys
a, b = sys.argv[1:]
# report keys that are timings (or that this comparison leaves out on purpose)
SKIP = re.compile(r"(^|_)(seconds|secs|time|times|elapsed|ms)$|^warnings$|^timings?$|^stage_seconds$|^threads$")
def clean(v):
    if isinstance(v, dict):
        return {k: clean(x) for k, x in v.items() if not SKIP.search(k)}
    if isinstance(v, list):
        return [clean(x) for x in v]
    return v
def mask(text):
    # timing figures on standard error and in text output: '1.23 s', '0.5s', '(12 ms)'
    return re.sub(r"\d+(\.\d+)?(e-?\d+)? ?(s|ms|seconds)\b", "<t>", text)
def first_diff(x, y, path="$"):
    if type(x) != type(y):
        return f"{path}: {x!r:.80} vs {y!r:.80}"
    if isinstance(x, dict):
        for k in sorted(set(x) | set(y)):
            if k not in x or k not in y:
                return f"{path}.{k}: only in {'B' if k not in x else 'A'}"
            d = first_diff(x[k], y[k], f"{path}.{k}")
            if d: return d
        return None
    if isinstance(x, list):
        if len(x) != len(y):
            return f"{path}: {len(x)} items vs {len(y)}"
        for i, (p, q) in enumerate(zip(x, y)):
            d = first_diff(p, q, f"{path}[{i}]")
            if d: return d
        return None
    return None if x == y else f"{path}: {x!r:.80} vs {y!r:.80}"
same = differ = 0
notes = []
inputs = sorted(os.path.join(g, n) for g in os.listdir(a) for n in os.listdir(os.path.join(a, g)))
for inp in inputs:
    da, db = os.path.join(a, inp), os.path.join(b, inp)
    if not os.path.isdir(db):
        notes.append(f"{inp}: missing in B"); differ += 1; continue
    names = sorted(os.path.relpath(os.path.join(r, n), da) for r, _, ns in os.walk(da) for n in ns)
    for name in names:
        pa, pb = os.path.join(da, name), os.path.join(db, name)
        if not os.path.exists(pb):
            notes.append(f"{inp}/{name}: missing in B"); differ += 1; continue
        # the record's own folder appears in paths that reports and decks echo
        ra = open(pa, "rb").read().replace(os.path.abspath(a).encode(), b"<DIR>")
        rb = open(pb, "rb").read().replace(os.path.abspath(b).encode(), b"<DIR>")
        why = None
        if name.endswith(".out") or name.endswith(".json"):
            try:
                ja, jb = json.loads(ra), json.loads(rb)
                why = first_diff(clean(ja), clean(jb))
            except ValueError:
                if mask(ra.decode(errors="replace")) != mask(rb.decode(errors="replace")):
                    why = "text output differs"
        elif name.endswith(".err"):
            ta, tb = mask(ra.decode(errors="replace")), mask(rb.decode(errors="replace"))
            if ta != tb:
                la, lb = ta.splitlines(), tb.splitlines()
                i = next((i for i, (p, q) in enumerate(zip(la, lb)) if p != q), min(len(la), len(lb)))
                why = f"stderr line {i + 1}: {(la[i] if i < len(la) else '<end>')[:100]!r} vs {(lb[i] if i < len(lb) else '<end>')[:100]!r}"
        elif ra != rb:
            why = f"bytes differ ({len(ra)} vs {len(rb)})"
        if why:
            differ += 1; notes.append(f"{inp}/{name}: {why}")
        else:
            same += 1
    for name in sorted(os.path.relpath(os.path.join(r, n), db) for r, _, ns in os.walk(db) for n in ns):
        if not os.path.exists(os.path.join(da, name)):
            notes.append(f"{inp}/{name}: only in B"); differ += 1
for n in notes:
    print("DIFF", n)
print(f"{len(inputs)} inputs, {same + differ} outputs compared: {same} the same, {differ} different")
sys.exit(1 if differ else 0)
PY
}

case "${1:-}" in
  record) shift; record "$@" ;;
  compare) shift; compare "$@" ;;
  *) usage ;;
esac
