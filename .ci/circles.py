#!/usr/bin/env python3
"""Circles of imports inside a crate: which files (and which top-level folders) of a
crate's src/ reach each other through `crate::` paths.

A file imports the module a `crate::a::b::c` path names: the deepest of `a/b/c`, `a/b`,
`a` that is a file or folder of the crate (a folder is its mod.rs). `super::` paths and
re-exports through lib.rs count as imports of the module they name. Circles are the
strongly connected components of that graph with more than one member (Tarjan).

Usage: python3 .ci/circles.py CRATE_SRC [--folders] [--check]
  --folders  group files by their top-level folder of src/ (a file at the top is its own)
  --check    exit 1 if there is any circle
"""

import os
import re
import sys

PATH = re.compile(r"\bcrate((?:::[A-Za-z_][A-Za-z0-9_]*)+)")
USE_GROUP = re.compile(r"use\s+crate::\{([^;]*)\};", re.S)


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
            if parts == ["lib"] or parts == ["main"]:
                parts = []
            out[tuple(parts)] = rel
    return out


def targets(path, mods):
    """The module a crate path names: its longest prefix that is a module."""
    for k in range(len(path), 0, -1):
        if tuple(path[:k]) in mods:
            return tuple(path[:k])
    return None


def graph(src):
    mods = modules(src)
    edges = {m: set() for m in mods}
    for module, rel in mods.items():
        text = open(os.path.join(src, rel), encoding="utf-8").read()
        # Tests inside a file are not its layer.
        text = text.split("#[cfg(test)]")[0]
        paths = [m.group(1).split("::")[1:] for m in PATH.finditer(text)]
        for group in USE_GROUP.finditer(text):
            for item in re.split(r",(?![^{]*\})", group.group(1)):
                item = item.strip()
                if item:
                    paths.append(re.split(r"::|\s", item.replace("{", " "))[:1] + [])
        for path in paths:
            target = targets(path, mods)
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
        edges, names = grouped, lambda c: sorted("/".join(m) for m in c)
    else:
        nodes = sorted(m for m in mods if m)
        names = lambda c: sorted(mods[m] for m in c)
    circles = strongly_connected(nodes, edges)
    for c in circles:
        print(f"circle of {len(c)}: " + ", ".join(names(c)))
    if not circles:
        print(f"{src}: no circles")
    if check and circles:
        sys.exit(1)


if __name__ == "__main__":
    main(sys.argv[1:])
