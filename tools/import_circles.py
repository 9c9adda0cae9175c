#!/usr/bin/env python3
"""Import circles between the files of src/ (issue 72: "no import circle between files").

Usage: python3 tools/import_circles.py [REPO_ROOT]   (default: the repository holding this script)

For every file src/**/*.rs (test files `tests.rs` / `tests_*.rs` and `#[cfg(test)]` modules
left out) it reads the files that file imports:
  - `use crate::...`, `use super::...`, `use self::...` and `use child::...` (a module the file
    declares with `mod child;`), nested braces expanded;
  - inline paths in code: `crate::a::b::Item`, `super::Item`, `self::m::Item`.
A path is resolved to the deepest file it names (src/a/b.rs or src/a/b/mod.rs); a name that a
module only re-exports (`pub use x::Item`, or any `use`, which children see through `super::`)
is followed to the file that defines it. `mod x;` declarations are not imports.

A folder's `mod.rs` is the folder's front door: the arrows between it and the files of its own
folder (children taking the module's shared types, it re-exporting or calling them) are the
module tree, not arrows between files, and are not counted. Every other arrow is, such as
`tessellate/improve/mod.rs` -> `tessellate/refine.rs` or `face_mesh.rs` -> `improve/mod.rs`.

It prints every strongly connected component of more than one file (a circle) with the names
that tie each arrow, and exits 1 when a circle remains that is not in ALLOWED below.
Only the Python standard library is used.
"""

import os
import re
import sys
from collections import defaultdict

# Circles allowed: none. (The recursive geometry types keep the variants that hold them again
# in their own file: `Curve` with `OffsetCurve` and `CurveReplica` in curve.rs, `Surface` with
# `Offset` and `SurfaceReplica` in surface.rs.)
ALLOWED: list = []

ITEM_DEF = r"(?:pub(?:\([^)]*\))?\s+)?(?:unsafe\s+|const\s+|async\s+|extern\s+\"[^\"]*\"\s+)*" \
           r"(?:fn|struct|enum|trait|type|const|static|union|mod|macro_rules!)\s+"


def strip_comments_and_strings(text):
    """Blank out comments, string and char literals (keeping newlines)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            i = j
            continue
        if text.startswith("/*", i):
            depth, j = 1, i + 2
            while j < n and depth:
                if text.startswith("/*", j):
                    depth, j = depth + 1, j + 2
                elif text.startswith("*/", j):
                    depth, j = depth - 1, j + 2
                else:
                    j += 1
            out.append("\n" * text.count("\n", i, j))
            i = j
            continue
        m = re.match(r'b?r(#*)"', text[i:i + 40])
        if m and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            end = '"' + m.group(1)
            j = text.find(end, i + m.end())
            j = n if j < 0 else j + len(end)
            out.append('""' + "\n" * text.count("\n", i, j))
            i = j
            continue
        if c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            out.append('""' + "\n" * text.count("\n", i, j))
            i = j + 1
            continue
        if c == "'":
            m = re.match(r"'(\\.|\\u\{[0-9a-fA-F]+\}|\\x[0-9a-fA-F]{2}|[^\\'])'", text[i:i + 12])
            if m:
                out.append("' '")
                i += m.end()
                continue
        out.append(c)
        i += 1
    return "".join(out)


def matching_brace(text, open_at):
    depth = 0
    for j in range(open_at, len(text)):
        if text[j] == "{":
            depth += 1
        elif text[j] == "}":
            depth -= 1
            if depth == 0:
                return j
    return len(text) - 1


def strip_test_modules(code):
    """Blank `#[cfg(test)] mod name { ... }` blocks (and other `#[cfg(test)]` items with a body)."""
    while True:
        m = re.search(r"#\[cfg\(test\)\]\s*(?:#\[[^\]]*\]\s*)*(?:pub(?:\([^)]*\))?\s+)?mod\s+\w+\s*\{", code)
        if not m:
            return code
        end = matching_brace(code, m.end() - 1)
        code = code[:m.start()] + "\n" * code.count("\n", m.start(), end + 1) + code[end + 1:]


def expand_use_tree(tree):
    """`a::{b, c::{d, e as f}}` -> [['a','b'], ['a','c','d'], ['a','c','e']] (with local names)."""
    tree = re.sub(r"\s+", "", tree)
    results = []

    def walk(prefix, s):
        # split s on top-level commas
        parts, depth, cur = [], 0, ""
        for ch in s:
            if ch == "{":
                depth += 1
            elif ch == "}":
                depth -= 1
            if ch == "," and depth == 0:
                parts.append(cur)
                cur = ""
            else:
                cur += ch
        if cur:
            parts.append(cur)
        for part in parts:
            if not part:
                continue
            brace = part.find("{")
            if brace >= 0:
                head = part[:brace].rstrip(":")
                inner = part[brace + 1:part.rfind("}")]
                walk(prefix + [p for p in head.split("::") if p], inner)
            else:
                alias = None
                if "as" in part and re.search(r"\bas\b", part.replace("as", " as ", 1)):
                    m = re.match(r"(.*?)as(\w+)$", part)
                    if m and m.group(1).endswith(tuple("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_*}")):
                        part, alias = m.group(1), m.group(2)
                segs = prefix + [p for p in part.split("::") if p]
                if segs and segs[-1] == "self":
                    segs = segs[:-1]
                local = alias or (segs[-1] if segs else None)
                results.append((segs, local))

    walk([], tree)
    return results


class Module:
    def __init__(self, path, modpath):
        self.path = path          # src/a/b.rs
        self.modpath = modpath    # ('a', 'b')
        self.code = ""
        self.children = set()     # `mod x;` names
        self.uses = []            # (segments, local name, is_glob)
        self.defined = set()


def module_path_of(rel):
    parts = rel[len("src/"):-len(".rs")].split("/")
    if parts[-1] in ("mod", "lib"):
        parts = parts[:-1]
    return tuple(parts)


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    src = os.path.join(root, "src")
    modules = {}
    for dirpath, _, files in os.walk(src):
        for f in files:
            if not f.endswith(".rs") or f == "main.rs":
                continue
            if f == "tests.rs" or f.startswith("tests_"):
                continue
            full = os.path.join(dirpath, f)
            rel = os.path.relpath(full, root).replace(os.sep, "/")
            if rel.startswith("src/bin/"):
                continue
            mod = Module(rel, module_path_of(rel))
            with open(full, encoding="utf-8") as fh:
                mod.code = strip_test_modules(strip_comments_and_strings(fh.read()))
            modules[mod.modpath] = mod

    use_re = re.compile(r"(?<![\w:])(?:pub(?:\([^)]*\))?\s+)?use\s+([^;]+);")
    for mod in modules.values():
        code = mod.code
        mod.children = set(re.findall(r"(?<![\w:])mod\s+(\w+)\s*;", code))
        mod.defined = set(re.findall(ITEM_DEF + r"(\w+)", code))
        mod.defined |= set(re.findall(r"\bmacro_rules!\s*(\w+)", code))
        for m in use_re.finditer(code):
            for segs, local in expand_use_tree(m.group(1)):
                if segs:
                    mod.uses.append((segs, local, segs[-1] == "*", m.start()))

    def absolute(mod, segs):
        """Resolve the leading crate/super/self/child segment; None for external crates."""
        if not segs:
            return None
        base = list(mod.modpath)
        i = 0
        if segs[0] == "crate":
            base, i = [], 1
        elif segs[0] in ("super", "self"):
            while i < len(segs) and segs[i] in ("super", "self"):
                if segs[i] == "super":
                    base = base[:-1]
                i += 1
        elif segs[0] in mod.children:
            i = 0
        else:
            return None
        return tuple(base) + tuple(segs[i:])

    def deepest(abspath):
        """Longest prefix of the path that is a module file; (module, rest)."""
        for k in range(len(abspath), -1, -1):
            if abspath[:k] in modules:
                return modules[abspath[:k]], abspath[k:]
        return None, abspath

    def defining(abspath, seen=None):
        """Follow re-exports: the module that defines the item the path names."""
        seen = seen or set()
        target, rest = deepest(abspath)
        if target is None or not rest or rest[0] == "*":
            return target, rest
        name = rest[0]
        if name in target.defined or name in target.children or (target.path, name) in seen:
            return target, rest
        seen.add((target.path, name))
        for segs, local, glob, _ in target.uses:
            if not glob and local == name:
                a = absolute(target, segs)
                if a is None:
                    return target, rest
                return defining(a + tuple(rest[1:]), seen)
        for segs, local, glob, _ in target.uses:
            if glob:
                a = absolute(target, segs[:-1])
                if a is None:
                    continue
                t2, r2 = defining(a + (name,), seen)
                if t2 is not None and r2 and r2[0] in t2.defined:
                    return t2, r2
        return target, rest

    edges = defaultdict(lambda: defaultdict(set))  # file -> file -> names

    def folder_of(path):
        """The folder a `mod.rs` (or `lib.rs`) stands for, else None."""
        if path.endswith("/mod.rs") or path == "src/lib.rs":
            return path.rsplit("/", 1)[0] + "/"
        return None

    def inside(a, b):
        """a is a `mod.rs` and b lies in its folder: the module tree, not a circle between files."""
        folder = folder_of(a)
        return folder is not None and b.startswith(folder)

    def add(mod, abspath):
        target, rest = defining(abspath)
        if target is None or target is mod:
            return
        if inside(mod.path, target.path) or inside(target.path, mod.path):
            return
        name = rest[0] if rest else target.path.split("/")[-1].replace(".rs", "")
        edges[mod.path][target.path].add(name)

    inline_re = re.compile(r"(?<![\w:])((?:crate|super|self)(?:::\w+)+)")
    for mod in modules.values():
        use_spans = [(m.start(), m.end()) for m in use_re.finditer(mod.code)]
        for segs, local, glob, _ in mod.uses:
            a = absolute(mod, segs[:-1] if glob else segs)
            if a is not None:
                add(mod, a + (("*",) if glob else ()))
        for m in inline_re.finditer(mod.code):
            if any(s <= m.start() < e for s, e in use_spans):
                continue
            segs = m.group(1).split("::")
            if re.match(r"\s*!", mod.code[m.end():m.end() + 3]):
                continue  # a macro path such as crate::some_macro!
            a = absolute(mod, segs)
            if a is not None:
                add(mod, a)

    # Tarjan's strongly connected components.
    index, low, stack, on, comps = {}, {}, [], set(), []
    counter = [0]
    nodes = sorted(set(m.path for m in modules.values()))
    sys.setrecursionlimit(10000)

    def strong(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(edges[v]):
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                comps.append(sorted(comp))

    for v in nodes:
        if v not in index:
            strong(v)

    comps.sort()
    bad = 0
    print(f"{len(nodes)} files read, {sum(len(t) for t in edges.values())} arrows, {len(comps)} circle(s)")
    for k, comp in enumerate(comps, 1):
        allowed = any(set(comp) <= a for a in ALLOWED)
        bad += not allowed
        tag = "allowed: a recursive type" if allowed else "NOT ALLOWED"
        print(f"circle {k} ({len(comp)} files, {tag}): {', '.join(comp)}")
        members = set(comp)
        for a in comp:
            for b in sorted(edges[a]):
                if b in members:
                    print(f"  {a} -> {b}: {', '.join(sorted(edges[a][b]))}")
    if bad:
        print(f"{bad} circle(s) not allowed")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
