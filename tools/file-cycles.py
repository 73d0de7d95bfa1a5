#!/usr/bin/env python3
"""Lists the `use crate::…` / `super::…` / `self::…` edges between the files of each crate
and prints every file circle (strongly connected set of files) it finds.

    tools/file-cycles.py [crates/conformap-disk ...]   (default: every crate in crates/)

An edge a → b means file a names an item defined in file b (a re-export `pub use` is
followed to the file that defines the item; `mod x;` declarations are not edges). Exit
code 1 when a circle exists, so CI can run it.
"""
import re
import sys
from pathlib import Path

USE = re.compile(r"\buse\s+((?:crate|super|self)\b[^;]*);", re.S)
PATH = re.compile(r"\b((?:crate|super|self)(?:::\w+)+)")
REEXPORT = re.compile(r"\bpub(?:\([^)]*\))?\s+use\s+([^;]*);", re.S)


def strip(text):
    """The code without comments and string literals."""
    text = re.sub(r"//[^\n]*", "", text)
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    text = re.sub(r'"(?:\\.|[^"\\])*"', '""', text)
    return drop_test_modules(text)


def drop_test_modules(text):
    """The code without its `#[cfg(test)] mod … { … }` blocks (test-only imports)."""
    while (m := re.search(r"#\[cfg\(test\)\]\s*(?:#\[[^\]]*\]\s*)*(?:pub(?:\([^)]*\))?\s+)?mod\s+\w+\s*\{", text)):
        depth, k = 1, m.end()
        while depth and k < len(text):
            depth += {"{": 1, "}": -1}.get(text[k], 0)
            k += 1
        text = text[: m.start()] + text[k:]
    return text


def expand(tree):
    """`a::{b, c::{d, e}}` → ['a::b', 'a::c::d', 'a::c::e'] (aliases dropped)."""
    tree = re.sub(r"\s+", "", tree)
    if "{" not in tree:
        return [re.sub(r"as\w+$", "", tree.split(" as ")[0])]
    head, rest = tree.split("{", 1)
    inner, depth, parts, cur = rest[:-1], 0, [], ""
    for ch in inner:
        if ch == "," and depth == 0:
            parts.append(cur)
            cur = ""
            continue
        depth += ch == "{"
        depth -= ch == "}"
        cur += ch
    parts.append(cur)
    out = []
    for p in filter(None, parts):
        for e in expand(p):
            out.append(head + e if e != "self" else head.rstrip(":"))
    return out


class Crate:
    def __init__(self, root):
        self.src = root / "src"
        self.files = {}  # module path (tuple) -> file
        for f in sorted(self.src.rglob("*.rs")):
            rel = f.relative_to(self.src).with_suffix("").parts
            if rel in (("lib",), ("main",)):
                rel = ()
            elif rel[-1] == "mod":
                rel = rel[:-1]
            elif (len(rel) > 1 and rel[0] == "bin") or rel[-1].endswith("tests"):
                continue  # binaries and test-only files
            self.files[rel] = f
        self.code = {f: strip(f.read_text()) for f in self.files.values()}
        self.macros = {  # `#[macro_export]` macros live at the crate root
            name: f
            for f, code in self.code.items()
            for name in re.findall(r"#\[macro_export\]\s*macro_rules!\s*(\w+)", code)
        }

    def module_of(self, f):
        return next(m for m, g in self.files.items() if g == f)

    def resolve(self, f, path, seen=()):
        """The file defining the item `path` names from file `f` (None: outside the crate)."""
        segs = path.split("::")
        mod = list(self.module_of(f))
        if segs[0] == "crate":
            mod, segs = [], segs[1:]
            if segs and segs[0] in self.macros:
                return self.macros[segs[0]]
        while segs and segs[0] in ("super", "self"):
            if segs[0] == "super" and mod:
                mod.pop()
            segs = segs[1:]
        while segs and tuple(mod + [segs[0]]) in self.files:
            mod.append(segs.pop(0))
        target = self.files.get(tuple(mod))
        if target is None or not segs or (target, segs[0]) in seen:
            return target
        # follow a re-export of the item in the target file
        for tree in REEXPORT.findall(self.code[target]):
            for p in expand(tree):
                if p.split("::")[-1] == segs[0] and p.split("::")[0] in ("crate", "super", "self"):
                    return self.resolve(target, p, seen + ((target, segs[0]),))
                if p.split("::")[-1] == segs[0] and tuple(mod + [p.split("::")[0]]) in self.files:
                    return self.resolve(target, "self::" + p, seen + ((target, segs[0]),))
        return target

    def edges(self):
        out = {f: set() for f in self.files.values()}
        for f, code in self.code.items():
            paths = [p for t in USE.findall(code) for p in expand(t)]
            paths += PATH.findall(USE.sub("", code))
            for tree in REEXPORT.findall(code):  # `pub use child::X` of a mod.rs
                paths += ["self::" + p for p in expand(tree)
                          if p.split("::")[0] not in ("crate", "super", "self")]
            for p in paths:
                t = self.resolve(f, p)
                if t is not None and t != f:
                    out[f].add(t)
        return out


def cycles(graph):
    """Strongly connected components of more than one file (Tarjan)."""
    index, low, stack, on, out, n = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = n[0]
        n[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
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
                out.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def main():
    roots = [Path(a) for a in sys.argv[1:]] or sorted(Path("crates").glob("*/"))
    bad = 0
    for root in roots:
        if not (root / "src").is_dir():
            continue
        crate = Crate(root)
        found = cycles(crate.edges())
        n = len(crate.files)
        if not found:
            print(f"{root.name}: {n} files, no circle")
        for comp in found:
            bad = 1
            names = ", ".join(str(f.relative_to(crate.src)) for f in comp)
            print(f"{root.name}: circle {names}")
    return bad


if __name__ == "__main__":
    sys.exit(main())
