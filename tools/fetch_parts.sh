#!/bin/bash
# Usage: tools/fetch_parts.sh [DIR]  (default ../fetched beside the repository, or $FEPRE_FETCHED)
# Downloads the fetched real parts listed in tools/fetched/SOURCES.tsv (file, kind, repo, path,
# commit, licence, exporting system, bytes: public GitHub repositories at a fixed commit) into
# DIR/step and DIR/mesh, for tools/sweep_fetched.py. The parts stay outside the repository
# (their licences are their authors'); a file whose size differs from the list is reported.
set -u
root="$(cd "$(dirname "$0")/.." && pwd)"
dir="${1:-${FEPRE_FETCHED:-$root/../fetched}}"
mkdir -p "$dir/step" "$dir/mesh"
fail=0
tail -n +2 "$root/tools/fetched/SOURCES.tsv" | while IFS=$'\t' read -r file kind repo path commit licence system bytes; do
  sub=$([ "$kind" = step ] && echo step || echo mesh)
  out="$dir/$sub/$file"
  [ -s "$out" ] && continue
  url="https://raw.githubusercontent.com/$repo/$commit/$(printf '%s' "$path" | sed 's/ /%20/g')"
  if ! curl -fsSL --retry 3 -o "$out.part" "$url"; then echo "failed: $url" >&2; rm -f "$out.part"; continue; fi
  mv "$out.part" "$out"
  got=$(stat -c %s "$out")
  [ "$got" = "$bytes" ] || echo "size differs: $file ($got bytes, listed $bytes)" >&2
done
echo "parts in $dir; then: $root/tools/sweep_fetched.py (OpenCASCADE references: --phase occ)"
