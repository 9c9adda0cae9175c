#!/usr/bin/env bash
# truck-stepio + truck-meshalgo against fepre's STEP reader + tessellator on every STEP file of
# the corpus, in one run: per file the times, their ratio, closed or not, volume / OpenCASCADE's
# (from the corpus README); then totals. Each file runs in a child process under a time-out and
# an address-space cap (truck never finishes linkrods.step and mambo_s34.step and grows past
# 14 GB on them).
#
# Usage: tools/bench_tessellate.sh [--timeout SECONDS] [--mem-gb GB] [CORPUS_DIR]
#   default corpus: $FEPRE_CORPUS, else ../shared/cad_corpus beside the checkout
# The bench is its own crate (tools/truck_bench, its own workspace): it is not built by
# `cargo build` or `cargo test` of fepre. It builds into fepre's target/ to reuse fepre's build.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
corpus="${FEPRE_CORPUS:-$root/../shared/cad_corpus}"
args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --timeout|--mem-gb) args+=("$1" "$2"); shift 2 ;;
    *) corpus="$1"; shift ;;
  esac
done
[ -d "$corpus" ] || { echo "no corpus at $corpus (set FEPRE_CORPUS or pass the folder)"; exit 1; }
export CARGO_TARGET_DIR="$root/target"
cargo build --release --quiet --manifest-path "$root/tools/truck_bench/Cargo.toml"
"$root/target/release/truck_bench" "$corpus" "${args[@]}"
