#!/usr/bin/python3
"""The include graph of cpp/ by folder, and whether it has a cycle.

Prints each folder with the project folders it includes (cpp/<folder>/... or
cpp/main.cpp), then the cycles and the includes that go up the layers; exits 1
if there is one. The folders are layered (LAYERS, lowest first; the map in
docs/architecture.md): a file includes only its own folder and the folders
below it, so data flows one way, scene -> mesh -> model -> solver ->
stepping -> driver -> study. Used by the test include_graph.

  scripts/include_graph.py [--dot]    (--dot: Graphviz text instead)
"""
import re
import argparse
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent / "cpp"
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


# Lowest first: each folder may include only the folders before it.
LAYERS = ["common", "laws", "scene", "bulk", "mesh", "interface", "model", "solver",
          "output", "record", "specimen", "stepping", "driver", "study", "main"]


def folder_of(path: Path) -> str:
    rel = path.relative_to(ROOT)
    return rel.parts[0] if len(rel.parts) > 1 else "main"


def graph():
    edges = {}
    for f in sorted(ROOT.rglob("*")):
        if f.suffix not in (".h", ".cpp"):
            continue
        src = folder_of(f)
        edges.setdefault(src, set())
        for inc in INCLUDE.findall(f.read_text()):
            target = (f.parent / inc).resolve()
            if not target.exists() or ROOT not in target.parents:
                continue  # generated (elasticity.h) or outside the project
            dst = folder_of(target)
            if dst != src:
                edges[src].add(dst)
    return edges


def cycles(edges):
    """Every elementary cycle's folders, found by depth-first search."""
    found, seen = [], set()

    def visit(node, path):
        for nxt in sorted(edges.get(node, ())):
            if nxt in path:
                cyc = path[path.index(nxt):]
                key = frozenset(cyc)
                if key not in seen:
                    seen.add(key)
                    found.append(cyc + [nxt])
            else:
                visit(nxt, path + [nxt])
    for start in sorted(edges):
        visit(start, [start])
    return found


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dot", action="store_true", help="Graphviz text instead")
    dot = ap.parse_args().dot
    edges = graph()
    if dot:
        print("digraph cpp {")
        for a in sorted(edges):
            for b in sorted(edges[a]):
                print(f"  {a} -> {b};")
        print("}")
    else:
        for a in sorted(edges):
            print(f"{a:10s} -> {', '.join(sorted(edges[a])) or '(nothing)'}")
    found = cycles(edges)
    for c in found:
        print("cycle: " + " -> ".join(c), file=sys.stderr)
    if not found:
        print("no cycle between folders")
    unknown = sorted(set(edges) - set(LAYERS))
    for folder in unknown:
        print(f"cpp/{folder}/ is not in LAYERS (scripts/include_graph.py): place it",
              file=sys.stderr)
    upward = [f"{a} includes {b}, a layer above it" for a in sorted(edges) for b in sorted(edges[a])
              if a in LAYERS and b in LAYERS and LAYERS.index(b) > LAYERS.index(a)]
    for up in upward:
        print(up, file=sys.stderr)
    if not upward and not unknown:
        print("every include goes down the layers: " + " < ".join(LAYERS))
    return 1 if found or upward or unknown else 0


if __name__ == "__main__":
    sys.exit(main())
