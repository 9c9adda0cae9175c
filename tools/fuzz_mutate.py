#!/usr/bin/env python3
"""Mutation fuzzing of fepre's surface readers and dirty-input paths.

Byte-level mutations (a chunk duplicated, a chunk deleted, numbers replaced) of seed surface
files, each run through `fepre inspect --json` and `fepre mesh --method octree` under a
timeout. Prints one line per slow or crashing input and a summary: how many ran past the
limit, the slowest times, and any exit other than 0 or 1 (a panic, a signal). Deterministic
for a seed (`--seed`), so a slow input can be made again.

  python3 tools/fuzz_mutate.py --fepre target/release/fepre --count 200 \
      ../shared/cad_corpus/featuretype.STL ../shared/tools/data/plc.off
  python3 tools/fuzz_mutate.py --keep /tmp/slow --limit 1.0 SEED...   # keep inputs over 1 s

Exit 1 when any input ran past `--limit` or crashed.
"""
import argparse
import os
import random
import re
import subprocess
import sys
import tempfile
import time

NUMBER = re.compile(rb"-?\d+\.?\d*(?:[eE][-+]?\d+)?")


def mutate(data: bytes, rng: random.Random) -> bytes:
    kind = rng.choice(["dup", "del", "num", "num", "bytes"])
    n = len(data)
    if n < 16:
        return data + data
    if kind == "dup":
        a = rng.randrange(n)
        b = min(n, a + rng.randint(1, max(1, n // 20)))
        at = rng.randrange(n)
        return data[:at] + data[a:b] + data[at:]
    if kind == "del":
        a = rng.randrange(n)
        b = min(n, a + rng.randint(1, max(1, n // 50)))
        return data[:a] + data[b:]
    if kind == "bytes":
        out = bytearray(data)
        for _ in range(rng.randint(1, 8)):
            out[rng.randrange(n)] = rng.randrange(256)
        return bytes(out)
    # numbers replaced (text formats): a few of them by nearby or wild values
    matches = list(NUMBER.finditer(data))
    if not matches:
        return mutate(data, rng)
    out = data
    for m in sorted(rng.sample(matches, min(len(matches), rng.randint(1, 6))), key=lambda m: -m.start()):
        v = rng.choice([b"0", b"1e30", b"-1e-30", b"nan", str(rng.uniform(-3, 3)).encode(), m.group(0) + b"1"])
        out = out[: m.start()] + v + out[m.end():]
    return out


def run(cmd, limit):
    t = time.monotonic()
    try:
        p = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, timeout=limit * 3 + 5)
        return p.returncode, time.monotonic() - t, p.stderr[-300:].decode("utf-8", "replace")
    except subprocess.TimeoutExpired:
        return "timeout", time.monotonic() - t, ""


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("seeds", nargs="+")
    ap.add_argument("--fepre", default="target/release/fepre")
    ap.add_argument("--count", type=int, default=100, help="mutated inputs per seed")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--limit", type=float, default=10.0, help="seconds an input may take")
    ap.add_argument("--no-octree", action="store_true", help="inspect only")
    ap.add_argument("--keep", help="folder to keep slow or crashing inputs in")
    a = ap.parse_args()
    rng = random.Random(a.seed)
    worst, bad, total = [], 0, 0
    with tempfile.TemporaryDirectory() as tmp:
        for seed in a.seeds:
            data = open(seed, "rb").read()
            ext = os.path.splitext(seed)[1]
            for i in range(a.count):
                m = data
                for _ in range(rng.randint(1, 3)):
                    m = mutate(m, rng)
                path = os.path.join(tmp, f"m{i}{ext}")
                open(path, "wb").write(m)
                cmds = [("inspect", [a.fepre, "inspect", path, "--json"])]
                if not a.no_octree:
                    cmds.append(("octree", [a.fepre, "mesh", path, "--method", "octree", "-o", os.path.join(tmp, "o.vtu")]))
                for name, cmd in cmds:
                    rc, dt, err = run(cmd, a.limit)
                    total += 1
                    worst.append((dt, name, os.path.basename(seed), i))
                    if rc not in (0, 1) or dt > a.limit:
                        bad += 1
                        print(f"{os.path.basename(seed)} #{i} {name}: exit {rc} in {dt:.2f} s {err.strip()[-160:]}", flush=True)
                        if a.keep:
                            os.makedirs(a.keep, exist_ok=True)
                            open(os.path.join(a.keep, f"{os.path.basename(seed)}.{i}{ext}"), "wb").write(m)
    worst.sort(reverse=True)
    print(f"{total} runs, {bad} past {a.limit} s or crashed; slowest: " + ", ".join(f"{n} {s}#{i} {t:.2f} s" for t, n, s, i in worst[:5]))
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
