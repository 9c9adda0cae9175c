#!/usr/bin/env python3
"""Checks docs/benchmarks.md and the size of ARCHITECTURE.md (python3, standard library only).

docs/benchmarks.md holds today's figures, one `## ` section per area. Each section must have
  - a `**Command:**` line (it may run on to the `**Taken:**` line) whose backticked commands
    name at least one thing that exists: a script `tools/NAME`, a criterion target
    `cargo bench --bench NAME` (benches/NAME.rs), an integration test `--test NAME`
    (tests/NAME.rs) or an example `--example NAME` (examples/NAME.rs); every one named must exist;
  - a `**Taken:**` line with the date (YYYY-MM-DD) the figure was taken at;
  - at least one table, and fit one screenful: at most SECTION_LINES lines, each table at most
    TABLE_LINES lines.
Every tools/bench_*.sh and every benches/*.rs must be cited by some section's command.
ARCHITECTURE.md must be under ARCH_BYTES bytes and hold its module graph (a fenced block).

Usage: python3 tools/check_benchmarks.py [REPO_ROOT]   (default: the folder above tools/)
Prints the areas checked; exits 1 with every reason found otherwise.
"""
import os
import re
import sys

SECTION_LINES = 40
TABLE_LINES = 35
ARCH_BYTES = 12 * 1024


def sections(text):
    """(title, first line number, lines) of each `## ` section."""
    out, cur = [], None
    for no, line in enumerate(text.splitlines(), 1):
        if line.startswith("## "):
            cur = (line[3:].strip(), no, [])
            out.append(cur)
        elif cur is not None:
            cur[2].append(line)
    return out


def command_block(lines):
    """The text from the `**Command:**` line up to the `**Taken:**` line."""
    block, on = [], False
    for line in lines:
        if line.startswith("**Command:**"):
            on = True
        elif line.startswith("**Taken:**") or not line.strip():
            on = False
        if on:
            block.append(line)
    return "\n".join(block)


def references(command):
    """(kind, name, path relative to the root) of every script or cargo target named."""
    refs = []
    for span in re.findall(r"`([^`]+)`", command):
        for m in re.finditer(r"(?<![\w./-])(tools/[\w./-]+)", span):
            refs.append(("script", m.group(1), m.group(1)))
        for kind, folder in (("bench", "benches"), ("test", "tests"), ("example", "examples")):
            for m in re.finditer(r"--%s[ =]([\w-]+)" % kind, span):
                refs.append((kind, m.group(1), "%s/%s.rs" % (folder, m.group(1))))
    return refs


def tables(lines):
    """Lengths of the runs of table lines."""
    runs, n = [], 0
    for line in lines + [""]:
        if line.lstrip().startswith("|"):
            n += 1
        elif n:
            runs.append(n)
            n = 0
    return runs


def check(root):
    errors, cited, report = [], set(), []
    bench_md = os.path.join(root, "docs", "benchmarks.md")
    if not os.path.isfile(bench_md):
        return ["docs/benchmarks.md is missing"], []
    text = open(bench_md, encoding="utf-8").read()
    secs = sections(text)
    if not secs:
        errors.append("docs/benchmarks.md has no `## ` area sections")
    for title, no, lines in secs:
        where = "docs/benchmarks.md:%d (%s)" % (no, title)
        # a section ends at the next heading; trailing blank lines do not count
        while lines and not lines[-1].strip():
            lines.pop()
        n = len(lines) + 1
        if n > SECTION_LINES:
            errors.append("%s: %d lines, more than a screenful (%d)" % (where, n, SECTION_LINES))
        runs = tables(lines)
        if not runs:
            errors.append("%s: no table" % where)
        for r in runs:
            if r > TABLE_LINES:
                errors.append("%s: a table of %d lines, more than %d" % (where, r, TABLE_LINES))
        command = command_block(lines)
        if not command:
            errors.append("%s: no **Command:** line" % where)
        refs = references(command)
        found = 0
        for kind, name, rel in refs:
            if os.path.isfile(os.path.join(root, rel)):
                found += 1
                cited.add(rel)
            else:
                errors.append("%s: the command names %s `%s`, but %s does not exist" % (where, kind, name, rel))
        if command and not refs:
            errors.append("%s: the command names no script in tools/ and no cargo bench/test/example target" % where)
        taken = [l for l in lines if l.startswith("**Taken:**")]
        if not taken:
            errors.append("%s: no **Taken:** line" % where)
        elif not re.search(r"\d{4}-\d{2}-\d{2}", taken[0]):
            errors.append("%s: the **Taken:** line gives no date (YYYY-MM-DD)" % where)
        report.append("%-62s %2d lines, %d table(s), %d command reference(s)" % (title[:62], n, len(runs), found))
    tools = os.path.join(root, "tools")
    for name in sorted(os.listdir(tools)) if os.path.isdir(tools) else []:
        if name.startswith("bench_") and name.endswith(".sh") and "tools/" + name not in cited:
            errors.append("tools/%s is cited by no area of docs/benchmarks.md" % name)
    benches = os.path.join(root, "benches")
    for name in sorted(os.listdir(benches)) if os.path.isdir(benches) else []:
        if name.endswith(".rs") and "benches/" + name not in cited:
            errors.append("benches/%s (`cargo bench --bench %s`) is cited by no area of docs/benchmarks.md" % (name, name[:-3]))
    arch = os.path.join(root, "ARCHITECTURE.md")
    if not os.path.isfile(arch):
        errors.append("ARCHITECTURE.md is missing")
    else:
        size = os.path.getsize(arch)
        if size >= ARCH_BYTES:
            errors.append("ARCHITECTURE.md is %d bytes, not under %d" % (size, ARCH_BYTES))
        if "```" not in open(arch, encoding="utf-8").read():
            errors.append("ARCHITECTURE.md has no module graph (a fenced block)")
        report.append("ARCHITECTURE.md: %d bytes (limit %d)" % (size, ARCH_BYTES))
    return errors, report


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    errors, report = check(root)
    for line in report:
        print(line)
    if errors:
        for e in errors:
            print("error: " + e, file=sys.stderr)
        sys.exit(1)
    print("docs/benchmarks.md and ARCHITECTURE.md: ok")


if __name__ == "__main__":
    main()
