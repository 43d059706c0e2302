"""The Python package's rooms (docs/architecture.md, "The add-on's rooms"), from the imports in the
sources' syntax trees (`import` and `from ... import`, at the top of a module or inside a function
alike):
- no import circles anywhere in addon/fenestra: a circle fails naming its modules and the lines of
  its arrows;
- Blender's modules (bpy, bmesh, gpu, ...) are imported only in the add-on, fenestra.blender, and
  not in its plain room, com/;
- the numpy-level package does not import the add-on (but its register() hands on to it);
- each of the add-on's rooms imports only its own room, the rooms below it, compat (not com/) and the
  numpy-level package; every module of the add-on is in a room."""

import ast
import importlib.machinery
import os

from conftest import ROOT

PACKAGE = os.path.join(ROOT, "addon", "fenestra")
BLENDER_MODULES = {"bpy", "bmesh", "blf", "gpu", "gpu_extras", "mathutils", "bpy_extras", "addon_utils", "bgl",
                   "bl_math", "idprop", "aud", "freestyle", "bl_ui", "bl_operators"}
# The add-on's rooms, bottom to top: plain logic (no Blender), the scene read as a study, a result
# put into the scene, the settings, the viewport's drawing, the sidebar's operators and panels.
ROOMS = ("com", "study", "result", "props", "draw", "ui")
OUTSIDE_ROOMS = ("", "compat")  # fenestra.blender itself (the register order) and compat.py
NATIVE_SUFFIXES = (".pyi",) + tuple(importlib.machinery.EXTENSION_SUFFIXES)


def modules(folder, package):
    """Each module's dotted name -> (its Python file or None for a native one, whether it is a
    package's __init__). A native module (`_core`) is known by its stub or its built file."""
    found = {}
    for here, dirs, names in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if not d.startswith((".", "__")))
        parts = [package] + os.path.relpath(here, folder).split(os.sep)
        parts = [p for p in parts if p != "."]
        for name in sorted(names):
            if name.endswith(".py"):
                stem = name[:-3]
                dotted = ".".join(parts if stem == "__init__" else parts + [stem])
                found[dotted] = (os.path.join(here, name), stem == "__init__")
            elif name.endswith(NATIVE_SUFFIXES):
                found.setdefault(".".join(parts + [name.split(".")[0]]), (None, False))
    return found


def arrows(known, folder, outside=False):
    """(importer, imported) -> the first `file:line` where the importer imports it; only modules of
    the package are kept (and, with `outside`, the top-level names of other modules: bpy, numpy, ...).
    `from P import n` imports P.n when that is a module, else P itself."""
    found = {}
    for name, (path, is_init) in known.items():
        if path is None:
            continue
        with open(path) as f:
            tree = ast.parse(f.read(), path)
        here = name if is_init else name.rpartition(".")[0]
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    up = here.split(".")
                    up = up[:len(up) - (node.level - 1)]
                    base = ".".join(up + ([base] if base else []))
                targets = [base + "." + a.name if base + "." + a.name in known else base for a in node.names]
            else:
                continue
            where = "%s:%d" % (os.path.relpath(path, os.path.dirname(folder)), node.lineno)
            for target in targets:
                if target in known and target != name:
                    found.setdefault((name, target), where)
                elif outside and target and target.split(".")[0] not in known:
                    found.setdefault((name, target.split(".")[0]), where)
    return found


def cycles(edges):
    """Circles [a, b, ..., a] within each strongly connected group of modules (Tarjan's), enough to
    pass through every module of the group."""
    following = {}
    for a, b in sorted(edges):
        following.setdefault(a, []).append(b)
    index, low, stack, on_stack, groups = {}, {}, [], set(), []

    def connect(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in following.get(v, []):
            if w not in index:
                connect(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            group = set()
            while True:
                w = stack.pop()
                on_stack.discard(w)
                group.add(w)
                if w == v:
                    break
            if len(group) > 1:
                groups.append(group)

    for v in sorted(following):
        if v not in index:
            connect(v)
    found = []
    for group in groups:
        covered = set()
        for start in sorted(group):  # circles through every module of the group, the shortest first
            if start not in covered:
                circle = shortest_circle(start, group, following)
                covered.update(circle)
                found.append(circle)
    return found


def shortest_circle(start, group, following):
    """The shortest way from `start` back to itself within `group` (breadth first)."""
    came_from, frontier = {start: None}, [start]
    while True:
        reached = []
        for v in frontier:
            for w in following.get(v, []):
                if w == start:
                    path = [v]
                    while path[-1] != start:
                        path.append(came_from[path[-1]])
                    return path[::-1] + [start]
                if w in group and w not in came_from:
                    came_from[w] = v
                    reached.append(w)
        frontier = reached


def describe(cycle, edges):
    return " -> ".join(cycle) + " (%s)" % ", ".join(edges[a, b] for a, b in zip(cycle, cycle[1:]))


def import_cycles(folder, package):
    edges = arrows(modules(folder, package), folder)
    return [describe(c, edges) for c in cycles(edges)]


def room_of(module, addon):
    """The add-on room a module is in: "com", ..., or "" / "compat" outside the rooms; None outside the add-on."""
    if module != addon and not module.startswith(addon + "."):
        return None
    return module[len(addon) + 1:].split(".")[0]


def room_breaches(folder, package):
    """`file:line: what` for each import that breaks the rooms' rules."""
    addon = package + ".blender"
    known = modules(folder, package)
    found = ["%s: %s is in no room of %s" % (path, name, ROOMS) for name, (path, _) in known.items()
             if room_of(name, addon) not in ROOMS + OUTSIDE_ROOMS + (None,)]
    for (a, b), where in sorted(arrows(known, folder, outside=True).items(), key=lambda item: item[1]):
        here, there = room_of(a, addon), room_of(b, addon)
        if b in BLENDER_MODULES:
            if here is None or here == "com":
                found.append("%s: %s imports %s (Blender's modules only in the add-on's Blender rooms)" % (where, a, b))
        elif b not in known or there is None or here in OUTSIDE_ROOMS[:1]:
            continue  # stdlib, numpy, the numpy-level package; the add-on's __init__ orders everything
        elif here is None and not (a == package and b == addon):  # but the package's register() hands on
            found.append("%s: %s imports the add-on's %s" % (where, a, b))
        elif here == "com" and there != "com":
            found.append("%s: %s imports %s (com/ imports only com/ and the numpy-level package)" % (where, a, b))
        elif here in ROOMS and there in ROOMS and ROOMS.index(there) > ROOMS.index(here):
            found.append("%s: %s imports %s, a room above its own (rooms bottom to top: %s)"
                         % (where, a, b, ", ".join(ROOMS)))
        elif here == "compat" and there != "compat":
            found.append("%s: compat imports %s (compat is below every room)" % (where, b))
    return found


def test_the_package_has_no_import_cycles():
    assert import_cycles(PACKAGE, "fenestra") == []


def test_the_walk_sees_the_addon():
    edges = arrows(modules(PACKAGE, "fenestra"), PACKAGE)
    assert any(a.startswith("fenestra.blender.") and b.startswith("fenestra.blender.") for a, b in edges)
    assert len(edges) > 100, len(edges)


def test_the_addon_keeps_to_its_rooms():
    assert room_breaches(PACKAGE, "fenestra") == []


def test_room_breaches_are_found(tmp_path):
    addon = tmp_path / "pkg" / "blender"
    for room in ROOMS:
        (addon / room).mkdir(parents=True)
        (addon / room / "__init__.py").write_text("")
    (addon.parent / "__init__.py").write_text("def register():\n    from . import blender\n")
    (addon.parent / "api.py").write_text("import numpy\nimport bpy\n\n\ndef f():\n    from .blender.ui import panels\n")
    (addon / "__init__.py").write_text("import bpy\nfrom .ui import panels\n")
    (addon / "compat.py").write_text("import bpy\nfrom .com import names\n")
    (addon / "loose.py").write_text("")
    (addon / "com" / "names.py").write_text("import os\nimport mathutils\nfrom ..study import export\nfrom ... import api\n")
    (addon / "study" / "export.py").write_text("import bpy\nfrom .. import compat\nfrom ..com import names\n"
                                               "from ..result import results\n")
    (addon / "result" / "results.py").write_text("from ..study import export\n")
    (addon / "ui" / "panels.py").write_text("import bpy\nfrom ..draw import overlay\nfrom ..study.export import f\n")
    (addon / "draw" / "overlay.py").write_text("import gpu\n")
    found = room_breaches(str(addon.parent), "pkg")
    assert [line.split(": ")[0] for line in found] == [
        str(addon / "loose.py"), "pkg/api.py:2", "pkg/api.py:6", "pkg/blender/com/names.py:2", "pkg/blender/com/names.py:3",
        "pkg/blender/compat.py:2", "pkg/blender/study/export.py:4"], found
    assert "a room above its own" in found[-1] and "pkg.blender.result.results" in found[-1]


def test_a_cycle_is_found_and_named(tmp_path):
    package = tmp_path / "pkg"
    (package / "ui").mkdir(parents=True)
    (package / "__init__.py").write_text("")
    (package / "ui" / "__init__.py").write_text("")
    (package / "names.py").write_text("import os\n")
    (package / "export.py").write_text("from . import names\n\n\ndef f():\n    from .ui import panel\n")
    (package / "ui" / "panel.py").write_text("from .. import names\nfrom ..results import apply\n")
    (package / "results.py").write_text("from .export import f\n")
    (package / "alone.py").write_text("from .alone import x\n")  # a module importing itself is no circle
    assert import_cycles(str(package), "pkg") == [
        "pkg.export -> pkg.ui.panel -> pkg.results -> pkg.export (pkg/export.py:5, pkg/ui/panel.py:2, pkg/results.py:1)"]
