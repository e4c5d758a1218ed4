#!/usr/bin/env python3
"""File-level dependency graph of object files, from their symbols; fails on a cycle.

Each group of object files (the library's, the CLI's) is read with `nm -P`: an
object that references a global symbol another object of the same group
defines depends on that object. Static functions never appear in the graph
(they are local to their file). Any strongly connected component of two files
or more is a cycle: it is printed as one concrete loop, each step with the
symbols that make it, and the check exits 1.

Usage: depgraph.py [--nm NM] [--dot FILE] [-v] --group NAME OBJ... [--group NAME OBJ...]
Exit status: 0 no cycle, 1 a cycle, 2 bad usage or nm failing
(--expect-cycles N: 0 when exactly N cycles).
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
from typing import Dict, List, Sequence, Set, Tuple

# nm -P types that define a symbol visible to other files (upper case = global;
# V/W weak, also definitions). U is a reference; lower case is file-local.
DEFINING = set("ABCDGRSTVWi")


def file_name(obj: str) -> str:
    """A readable name for an object: src/host/session/session.c.o -> posix/session.c."""
    obj = os.path.normpath(obj)
    base = os.path.basename(obj)
    parent = os.path.basename(os.path.dirname(obj))
    name = base[:-2] if base.endswith(".o") else base
    if parent and not parent.endswith(".dir"):
        return f"{parent}/{name}"
    return name


def read_symbols(nm: str, obj: str) -> Tuple[Set[str], Set[str]]:
    """(defined, referenced) global symbols of one object file."""
    try:
        out = subprocess.run(
            [nm, "-P", obj], check=True, capture_output=True, text=True
        ).stdout
    except (OSError, subprocess.CalledProcessError) as exc:
        print(f"depgraph: {nm} -P {obj}: {exc}", file=sys.stderr)
        raise SystemExit(2) from exc
    defined: Set[str] = set()
    referenced: Set[str] = set()
    for line in out.splitlines():
        parts = line.split()
        if len(parts) < 2:
            continue
        sym, kind = parts[0], parts[1]
        if kind == "U":
            referenced.add(sym)
        elif kind in DEFINING:
            defined.add(sym)
    return defined, referenced


Graph = Dict[str, Dict[str, List[str]]]  # file -> {file it uses: [symbols]}


def build_graph(nm: str, objs: Sequence[str]) -> Graph:
    names = {o: file_name(o) for o in objs}
    if len(set(names.values())) != len(objs):
        names = {o: o for o in objs}  # two files of one name: keep the paths
    syms = {names[o]: read_symbols(nm, o) for o in objs}
    owner: Dict[str, str] = {}
    for f, (defined, _) in syms.items():
        for s in defined:
            owner.setdefault(s, f)
    graph: Graph = {f: {} for f in syms}
    for f, (_, referenced) in syms.items():
        for s in sorted(referenced):
            g = owner.get(s)
            if g is not None and g != f:
                graph[f].setdefault(g, []).append(s)
    return graph


def components(graph: Graph) -> List[List[str]]:
    """Strongly connected components (Tarjan, iterative), each sorted."""
    index: Dict[str, int] = {}
    low: Dict[str, int] = {}
    on_stack: Set[str] = set()
    stack: List[str] = []
    out: List[List[str]] = []
    counter = 0
    for root in sorted(graph):
        if root in index:
            continue
        work: List[Tuple[str, List[str]]] = [(root, sorted(graph[root]))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack.add(root)
        while work:
            v, succ = work[-1]
            if succ:
                w = succ.pop(0)
                if w not in index:
                    index[w] = low[w] = counter
                    counter += 1
                    stack.append(w)
                    on_stack.add(w)
                    work.append((w, sorted(graph[w])))
                elif w in on_stack:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp: List[str] = []
                while True:
                    w = stack.pop()
                    on_stack.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                out.append(sorted(comp))
    return out


def one_loop(graph: Graph, comp: List[str]) -> List[str]:
    """A shortest loop through the component's first file (breadth first)."""
    members = set(comp)
    start = comp[0]
    prev: Dict[str, str] = {}
    frontier = [start]
    seen = {start}
    while frontier:
        nxt: List[str] = []
        for v in frontier:
            for w in sorted(graph[v]):
                if w not in members:
                    continue
                if w == start:
                    path = [v]
                    while path[-1] != start:
                        path.append(prev[path[-1]])
                    return list(reversed(path)) + [start]
                if w not in seen:
                    seen.add(w)
                    prev[w] = v
                    nxt.append(w)
        frontier = nxt
    return [start, start]


def write_dot(path: str, graphs: Dict[str, Graph]) -> None:
    with open(path, "w", encoding="utf-8") as f:
        f.write("digraph deps {\n  rankdir=LR;\n")
        for name, graph in graphs.items():
            f.write(f'  subgraph "cluster_{name}" {{\n    label="{name}";\n')
            for v in sorted(graph):
                f.write(f'    "{name}:{v}" [label="{v}"];\n')
                for w in sorted(graph[v]):
                    f.write(f'    "{name}:{v}" -> "{name}:{w}";\n')
            f.write("  }\n")
        f.write("}\n")


def parse(argv: Sequence[str]) -> Tuple[argparse.Namespace, Dict[str, List[str]]]:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--nm", default=os.environ.get("NM", "nm"))
    p.add_argument("--dot", help="also write the graphs as Graphviz dot to this file")
    p.add_argument("-v", "--verbose", action="store_true", help="print every edge")
    p.add_argument("--expect-cycles", type=int, default=0, metavar="N",
                   help="succeed when exactly N cycles are found (the check's own test)")
    args, rest = p.parse_known_args(argv)
    groups: Dict[str, List[str]] = {}
    current = None
    it = iter(rest)
    for a in it:
        if a == "--group":
            current = next(it, None)
            if current is None:
                p.error("--group needs a name")
            groups.setdefault(current, [])
        elif current is None:
            p.error(f"{a}: object files come after --group NAME")
        else:
            # a CMake list ($<TARGET_OBJECTS:...>) arrives as one argument
            groups[current].extend(x for x in a.split(";") if x)
    if not groups or any(not objs for objs in groups.values()):
        p.error("every --group needs a name and at least one object file")
    return args, groups


def main(argv: Sequence[str]) -> int:
    args, groups = parse(argv)
    graphs = {name: build_graph(args.nm, objs) for name, objs in groups.items()}
    cycles = 0
    for name, graph in graphs.items():
        edges = sum(len(v) for v in graph.values())
        loops = [c for c in components(graph) if len(c) > 1]
        print(f"{name}: {len(graph)} files, {edges} dependencies, {len(loops)} cycle(s)")
        if args.verbose:
            for v in sorted(graph):
                for w in sorted(graph[v]):
                    print(f"  {v} -> {w}: {', '.join(graph[v][w])}")
        for comp in loops:
            cycles += 1
            loop = one_loop(graph, comp)
            print(f"  CYCLE among {len(comp)} files: {' '.join(comp)}")
            print(f"    e.g. {' -> '.join(loop)}")
            for a, b in zip(loop, loop[1:]):
                print(f"      {a} -> {b}: {', '.join(graph[a][b])}")
    if args.dot:
        write_dot(args.dot, graphs)
    if cycles != args.expect_cycles:
        print(f"depgraph: {cycles} cycle(s) (expected {args.expect_cycles}): "
              "files must depend one way", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
