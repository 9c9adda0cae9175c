#!/usr/bin/env bash
# Imprinting assemblies: `fepre mesh --json` on the corpus and step_sweep assemblies, the share
# of the contacts' area that shares nodes (conforming), the smallest dihedral, tets and seconds;
# with OLD=path/to/an/earlier/fepre the same for that binary beside it (same machine, one run).
#
#   tools/bench_imprint.sh                      # this build
#   OLD=/path/to/fepre tools/bench_imprint.sh   # this build against an earlier one
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
corpus=${FEPRE_CORPUS:-$root/../shared/cad_corpus}
sweep=${FEPRE_SWEEP:-$root/../shared/step_sweep}
fepre=${FEPRE:-$root/target/release/fepre}
[ -x "$fepre" ] || cargo build --release --manifest-path "$root/Cargo.toml"
files=("$corpus/wing_fuselage.step" "$corpus/abc-0000.step" "$corpus/as1-tu-203.stp"
       "$sweep/as1-oc-214-mat.stp" "$sweep/trj6_as1-hc-214.stp" "$sweep/trj3_as1-ec-203.stp")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
row() { # binary file label
    local json="$out/r.json"
    if ! timeout 600 "$1" mesh "$2" -o "$out/m.vtu" --json > "$json" 2> "$out/err"; then
        printf '| %s | %s | failed: %s |\n' "$(basename "$2")" "$3" "$(tail -1 "$out/err")"
        return
    fi
    python3 - "$json" "$(basename "$2")" "$3" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
c = d.get("contacts", [])
area = sum(x["area"] for x in c)
shared = sum(x["shared_area"] for x in c)
imp = d.get("imprinted")
print(f"| {sys.argv[2]} | {sys.argv[3]} | {len(c)} | {100 * shared / area if area else 0:.1f} % | {imp[1] if imp else '-'}/{imp[0] if imp else '-'} | {d['tets']} | {d['min_dihedral_deg']:.2f}° | {d['seconds']:.2f} |")
PY
}
echo "| assembly | binary | contacts | area conforming | groups imprinted | tets | min dihedral | s |"
echo "|---|---|---|---|---|---|---|---|"
for f in "${files[@]}"; do
    [ -f "$f" ] || { echo "missing $f" >&2; continue; }
    [ -n "${OLD:-}" ] && row "$OLD" "$f" old
    row "$fepre" "$f" new
done
