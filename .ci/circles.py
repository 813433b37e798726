#!/usr/bin/env python3
"""Circles of imports inside a crate: which files (and which top-level folders) of a
crate's src/ reach each other through `crate::`, `super::` and `self::` paths.

Every `use` tree is expanded into paths, and so is every `crate::` path in code. A path
names the deepest module it reaches (a folder is its mod.rs); a name that module
re-exports (`pub use`) is followed to the module that defines it, so an import through
lib.rs or a folder's mod.rs counts as an import of the defining file, and a re-export
alone is not an import. Circles are the
strongly connected components of that graph with more than one member (Tarjan). Tests
inside a file (`#[cfg(test)]` and below) are not its layer, and comments (doc links
among them) are not imports.

Usage: python3 .ci/circles.py CRATE_SRC [--folders] [--edges] [--check]
  --folders  group files by their top-level folder of src/ (a file at the top is its own)
  --edges    print each circle's edges (who imports whom)
  --check    exit 1 if there is any circle
"""

import os
import re
import sys

CRATE_PATH = re.compile(r"(?<![:\w])crate((?:::[A-Za-z_][A-Za-z0-9_]*)+)")
USE = re.compile(r"(?:^|\n)\s*(pub(?:\([^)]*\))?\s+)?use\s+([^;]+);", re.S)


def modules(src):
    """Module path (tuple) -> file, for every .rs file under src."""
    out = {}
    for root, _, files in os.walk(src):
        for name in files:
            if not name.endswith(".rs"):
                continue
            rel = os.path.relpath(os.path.join(root, name), src)
            parts = rel[:-3].split(os.sep)
            if parts[-1] == "mod":
                parts = parts[:-1]
            if parts in (["lib"], ["main"]):
                parts = []
            out[tuple(parts)] = rel
    return out


def expand(tree):
    """The paths of a use tree: `a::{b, c::{d, e as f}}` -> [a::b, a::c::d, a::c::e]."""
    tree = re.sub(r"\s+", "", tree)
    out = []

    def walk(prefix, text):
        depth, start, items = 0, 0, []
        for i, ch in enumerate(text):
            if ch == "{":
                depth += 1
            elif ch == "}":
                depth -= 1
            elif ch == "," and depth == 0:
                items.append(text[start:i])
                start = i + 1
        items.append(text[start:])
        for item in items:
            if not item:
                continue
            if "{" in item:
                head, rest = item.split("{", 1)
                walk(prefix + [p for p in head.split("::") if p], rest[:-1])
            else:
                name = item.split("as")[0] if "as" in item.split("::")[-1] else item
                out.append(prefix + [p for p in name.split("::") if p])

    walk([], tree)
    return out


def absolute(path, module):
    """A path as seen from `module`, from the crate root (None: another crate)."""
    if not path:
        return None
    if path[0] == "crate":
        return path[1:]
    if path[0] in ("super", "self"):
        base = list(module)
        while path and path[0] in ("super", "self"):
            if path[0] == "super":
                base = base[:-1]
            path = path[1:]
        return base + path
    return None


def graph(src):
    mods = modules(src)
    texts = {}
    uses = {}
    reexports = {m: {} for m in mods}
    for module, rel in mods.items():
        text = open(os.path.join(src, rel), encoding="utf-8").read().split("#[cfg(test)]")[0]
        # Comments (and doc links) are not imports.
        text = re.sub(r"//[^\n]*", "", text)
        texts[module] = text
        paths = []
        # Where a re-exported name is used: not in `use` lines, nor in `mod` declarations.
        without_uses = re.sub(r"(?m)^\s*(pub(\([^)]*\))?\s+)?mod\s+\w+\s*;", "", USE.sub("", text))
        for m in USE.finditer(text):
            public = m.group(1) is not None
            for path in expand(m.group(2)):
                if path and path[-1] == "*":
                    continue
                full = absolute(path, module)
                if full is None and path[0] in {p[-1] for p in mods if len(p) == len(module) + 1 and p[:-1] == module}:
                    full = list(module) + path  # `use child::X` in a mod.rs
                if full is None:
                    continue
                if public:
                    # A folder's interface, not a use of what it names, unless the
                    # module's own code uses the name too.
                    reexports[module][path[-1]] = full
                    if re.search(r"\b" + re.escape(path[-1]) + r"\b", without_uses):
                        paths.append(full)
                else:
                    paths.append(full)
        paths += [m.group(1).split("::")[1:] for m in CRATE_PATH.finditer(text)]
        uses[module] = paths

    def resolve(path, seen=0):
        """The module defining what `path` names."""
        for k in range(len(path), -1, -1):
            if tuple(path[:k]) in mods:
                module, rest = tuple(path[:k]), path[k:]
                if rest and rest[0] in reexports[module] and seen < 16:
                    return resolve(reexports[module][rest[0]] + rest[1:], seen + 1)
                return module
        return None

    edges = {m: set() for m in mods}
    for module, paths in uses.items():
        for path in paths:
            target = resolve(path)
            if target is not None and target != module and target != ():
                edges[module].add(target)
    return mods, edges


def strongly_connected(nodes, edges):
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on.discard(w)
                component.append(w)
                if w == v:
                    break
            out.append(component)

    sys.setrecursionlimit(10000)
    for v in nodes:
        if v not in index:
            visit(v)
    return [c for c in out if len(c) > 1]


def main(argv):
    if not argv or argv[0].startswith("-"):
        sys.exit(__doc__)
    src, folders, check = argv[0], "--folders" in argv, "--check" in argv
    mods, edges = graph(src)
    if folders:
        top = lambda m: m[:1]
        nodes = sorted({top(m) for m in mods if m})
        grouped = {n: set() for n in nodes}
        for m, ts in edges.items():
            for t in ts:
                if m and top(m) != top(t):
                    grouped[top(m)].add(top(t))
        edges = grouped
        name = lambda m: "/".join(m)
    else:
        nodes = sorted(m for m in mods if m)
        name = lambda m: mods[m]
    circles = strongly_connected(nodes, edges)
    for c in circles:
        print(f"circle of {len(c)}: " + ", ".join(sorted(name(m) for m in c)))
        if "--edges" in argv:
            for m in sorted(c, key=name):
                inside = sorted(name(t) for t in edges[m] if t in c)
                print(f"  {name(m)} -> {', '.join(inside)}")
    if not circles:
        print(f"{src}: no circles")
    if check and circles:
        sys.exit(1)


if __name__ == "__main__":
    main(sys.argv[1:])
