#!/usr/bin/env python3
"""Whether a source folder's files include each other in a circle.

    tools/include_cycles.py engine/raytrace [engine/render ...]

Reads the `#include "<folder>/name.ext"` lines of the folder's .h, .cpp and .inl
files (<folder> is the folder's own name: raytrace/ for engine/raytrace) and makes a
graph of them by file stem: x.h, x.cpp and x.inl are one node, so that x.cpp
including y.h while y.cpp includes x.h is a circle too (the two files depend on each
other, whichever way their headers are arranged). A file including its own stem's
header is no edge. A class's private header x_impl.h (its insides, shared by the
files that implement it) is part of x's node. Exits 0 when the graph is acyclic; else prints one circle, as the
files whose lines make it, and exits 1. Includes of other folders are ignored. Several folders: each on its own.
"""
import re
import sys
from pathlib import Path

SUFFIXES = (".h", ".cpp", ".inl")


def node(stem: str) -> str:
    return stem[: -len("_impl")] if stem.endswith("_impl") else stem


def include_graph(folder: Path):
    """{stem: {included stem: the including file and line}}."""
    pattern = re.compile(r'^\s*#\s*include\s+"' + re.escape(folder.name) + r'/([^"/]+)"')
    graph = {}
    for path in sorted(folder.iterdir()):
        if path.suffix not in SUFFIXES or not path.is_file():
            continue
        edges = graph.setdefault(node(path.stem), {})
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            match = pattern.match(line)
            if not match:
                continue
            target = node(Path(match.group(1)).stem)
            if target != node(path.stem):
                edges.setdefault(target, f"{path.name}:{number}: {line.strip()}")
    return graph


def find_cycle(graph):
    """One circle as a list of stems (first == last), or None. Depth first, iterative."""
    done, on_path = set(), []
    for root in sorted(graph):
        if root in done:
            continue
        stack = [(root, iter(sorted(graph.get(root, {}))))]
        on_path.append(root)
        while stack:
            node, children = stack[-1]
            child = next(children, None)
            if child is None:
                stack.pop()
                on_path.pop()
                done.add(node)
            elif child in on_path:
                return on_path[on_path.index(child):] + [child]
            elif child not in done:
                stack.append((child, iter(sorted(graph.get(child, {})))))
                on_path.append(child)
    return None


def main(argv):
    if len(argv) < 2:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    return max(check(Path(folder)) for folder in argv[1:])


def check(folder: Path):
    if not folder.is_dir():
        print(f"{folder}: not a folder", file=sys.stderr)
        return 2
    graph = include_graph(folder.resolve())
    cycle = find_cycle(graph)
    if cycle is None:
        edges = sum(len(e) for e in graph.values())
        print(f"{folder}: no include cycle ({len(graph)} stems, {edges} edges)")
        return 0
    print(f"{folder}: include cycle {' -> '.join(cycle)}")
    for a, b in zip(cycle, cycle[1:]):
        print(f"  {graph[a][b]}")
    return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
