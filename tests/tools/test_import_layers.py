# SPDX-License-Identifier: Apache-2.0
"""The import graph of the tools package (tools/uvms_tools) has no cycle and keeps its layers.

Every import in every module, function-level ones included, absolute and relative, that names
a module of the package is an arrow of the graph (an import of a name from a module: an arrow
to that module). Checked:
  - no cycle: each strongly connected component of more than one module fails, named as a path
    a -> b -> ... -> a;
  - the layers of uvms_tools/__init__.py: a module imports only from its own subpackage and
    from lower layers; each arrow that does not is named with its file and line;
  - every top-level unit of the package (subpackage or module) has a layer, so a new one must
    be placed;
  - the checker itself, on a scratch package with a relative module-level import one way and a
    function-level absolute import back, finds that cycle (so a broken parser cannot pass
    silently), and the real graph holds arrows known to exist.

Usage: test_import_layers.py SOURCE_DIR
"""
import ast
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import checklist  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "support"))
from scratch import scratch_dir  # noqa: E402  (tests/support/scratch.py)

SRC = sys.argv[1]
PACKAGE = "uvms_tools"
PACKAGE_DIR = os.path.join(SRC, "tools", PACKAGE)
TMP = scratch_dir("uvms-import-layers-")  # removed at exit (tests/support/scratch.py)

# The layers of uvms_tools/__init__.py, bottom up: a unit (top-level subpackage or module)
# imports only units of a lower layer.
LAYERS = {
    "env": 0,
    "log": 1, "models": 1, "campaign_dask": 1, "vehicle": 1,
    "viz": 2, "dashboard": 2,
    "report": 3, "uvmslog": 3,
}


def modules_of(package_dir, package):
    """{dotted module name: (path, is_package)} of every .py file below package_dir."""
    out = {}
    root = os.path.dirname(package_dir)
    for dp, dns, fns in os.walk(package_dir):
        dns[:] = [d for d in dns if d != "__pycache__"]
        for fn in fns:
            if not fn.endswith(".py"):
                continue
            rel = os.path.relpath(os.path.join(dp, fn), root)[:-3].split(os.sep)
            is_pkg = rel[-1] == "__init__"
            name = ".".join(rel[:-1] if is_pkg else rel)
            out[name] = (os.path.join(dp, fn), is_pkg)
    assert package in out, f"no {package}/__init__.py in {package_dir}"
    return out


def import_targets(node, module, is_pkg):
    """The dotted names an Import/ImportFrom node asks for (module names, or module.attr)."""
    if isinstance(node, ast.Import):
        return [a.name for a in node.names]
    if node.level:
        parts = module.split(".") if is_pkg else module.split(".")[:-1]
        parts = parts[:len(parts) - (node.level - 1)]
        base = ".".join(parts + ([node.module] if node.module else []))
    else:
        base = node.module
    return [f"{base}.{a.name}" for a in node.names]


def resolve(name, modules):
    """The longest prefix of `name` that is a module of the package, or None."""
    parts = name.split(".")
    while parts:
        candidate = ".".join(parts)
        if candidate in modules:
            return candidate
        parts.pop()
    return None


def import_graph(modules):
    """{module: {imported module: (path, line)}} over every import of every module."""
    graph = {m: {} for m in modules}
    for module, (path, is_pkg) in modules.items():
        with open(path, encoding="utf-8") as fh:
            tree = ast.parse(fh.read(), path)
        for node in ast.walk(tree):
            if not isinstance(node, (ast.Import, ast.ImportFrom)):
                continue
            # `from pkg import mod` is an arrow to pkg.mod, `from mod import func` one to mod:
            # the longest prefix of each name that is a module. A package's __init__ naming
            # its own attributes (`from . import x`, x not a module) is no arrow.
            for name in import_targets(node, module, is_pkg):
                target = resolve(name, modules)
                if target is not None and target != module:
                    graph[module].setdefault(target, (path, node.lineno))
    return graph


def cycles(graph):
    """Each strongly connected component with a cycle, as one cycle path [a, b, ..., a]
    (Tarjan's algorithm, iterative)."""
    index, low, on_stack, stack, found = {}, {}, set(), [], []
    counter = [0]

    def strongconnect(root):
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = counter[0]
        counter[0] += 1
        stack.append(root)
        on_stack.add(root)
        while work:
            v, it = work[-1]
            w = next(it, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = counter[0]
                    counter[0] += 1
                    stack.append(w)
                    on_stack.add(w)
                    work.append((w, iter(sorted(graph[w]))))
                elif w in on_stack:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on_stack.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    found.append(cycle_path(graph, set(comp)))

    for v in sorted(graph):
        if v not in index:
            strongconnect(v)
    return found


def cycle_path(graph, comp):
    """One cycle through the component: from its first module, breadth-first back to it."""
    start = min(comp)
    prev, frontier = {start: None}, [start]
    while frontier:
        nxt = []
        for v in frontier:
            for w in sorted(graph[v]):
                if w == start:
                    path = [v]
                    while prev[path[-1]] is not None:
                        path.append(prev[path[-1]])
                    return list(reversed(path)) + [start]
                if w in comp and w not in prev:
                    prev[w] = v
                    nxt.append(w)
        frontier = nxt
    return [start, start]


def unit_of(module):
    """The top-level unit of a module: uvms_tools.log.runlog -> log; the package itself: ''."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else ""


def layer_violations(graph):
    out = []
    for src, targets in sorted(graph.items()):
        for dst, (path, line) in sorted(targets.items()):
            a, b = unit_of(src), unit_of(dst)
            if a == b or a not in LAYERS or b not in LAYERS:
                continue
            if LAYERS[b] >= LAYERS[a]:
                out.append(f"{os.path.relpath(path, SRC)}:{line}: {src} ({a}, layer "
                           f"{LAYERS[a]}) imports {dst} ({b}, layer {LAYERS[b]})")
    return out


MODULES = modules_of(PACKAGE_DIR, PACKAGE)
GRAPH = import_graph(MODULES)


def the_checker_finds_a_function_level_relative_cycle():
    pkg = os.path.join(TMP, "scratch")
    os.makedirs(pkg)
    files = {"__init__.py": "",
             "a.py": "from . import b\n",
             "b.py": "def f():\n    from scratch.a import g\n    return g\n",
             "c.py": "from .a import b\n"}
    for name, text in files.items():
        with open(os.path.join(pkg, name), "w", encoding="utf-8") as fh:
            fh.write(text)
    graph = import_graph(modules_of(pkg, "scratch"))
    found = cycles(graph)
    assert found == [["scratch.a", "scratch.b", "scratch.a"]], found
    assert graph["scratch.c"] == {"scratch.a": (os.path.join(pkg, "c.py"), 1)}, graph


def the_graph_holds_known_arrows():
    n = sum(len(t) for t in GRAPH.values())
    known = [("uvms_tools.dashboard.page", "uvms_tools.log.runlog"),
             ("uvms_tools.report.cli", "uvms_tools.report.document"),
             ("uvms_tools.campaign_dask.cli", "uvms_tools.campaign_dask.engine"),
             ("uvms_tools.log.runlog", "uvms_tools.log.records")]
    missing = [f"{a} -> {b}" for a, b in known if b not in GRAPH.get(a, {})]
    assert not missing and n > 100, f"{len(MODULES)} modules, {n} arrows; missing {missing}"
    print(f"     {len(MODULES)} modules, {n} import arrows within {PACKAGE}")


def no_import_cycle():
    found = cycles(GRAPH)
    assert not found, "import cycle(s): " + "; ".join(" -> ".join(c) for c in found)


def every_unit_has_a_layer():
    units = sorted({unit_of(m) for m in MODULES} - {""})
    unplaced = [u for u in units if u not in LAYERS]
    stale = [u for u in LAYERS if u not in units]
    assert not unplaced and not stale, \
        f"units without a layer: {unplaced}; layers of no unit: {stale} (units: {units})"


def imports_follow_the_layers():
    bad = layer_violations(GRAPH)
    assert not bad, "imports against the layers:\n  " + "\n  ".join(bad)


def the_package_itself_imports_nothing():
    assert not GRAPH[PACKAGE], f"{PACKAGE}/__init__.py imports {sorted(GRAPH[PACKAGE])}"


if __name__ == "__main__":
    sys.exit(checklist.run([the_checker_finds_a_function_level_relative_cycle,
                            the_graph_holds_known_arrows, no_import_cycle,
                            every_unit_has_a_layer, imports_follow_the_layers,
                            the_package_itself_imports_nothing], TMP))
