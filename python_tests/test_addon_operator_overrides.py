"""The add-on runs no operator (bpy.ops) under Context.temp_override. Blender 3.4 to 4.5 (Python
3.11) crash when an operator runs from Python under a context override while another Python thread
holds the GIL, and the add-on's own solve runs on a thread (docs/blender.md, "Scripts and
threads"). Read from the source: no Blender needed."""

import ast

from test_addon_removed_api import addon_files, is_operator_call


def is_override(item):
    """`with ....temp_override(...)`."""
    call = item.context_expr
    return isinstance(call, ast.Call) and isinstance(call.func, ast.Attribute) and call.func.attr == "temp_override"


def operators_under_overrides(files):
    found = []
    for path in files:
        with open(path) as f:
            tree = ast.parse(f.read(), path)
        for node in ast.walk(tree):
            if isinstance(node, ast.With) and any(is_override(item) for item in node.items):
                found += ["%s:%d: %s" % (path, call.lineno, ast.unparse(call.func))
                          for statement in node.body for call in ast.walk(statement)
                          if isinstance(call, ast.Call) and is_operator_call(call)]
    return found


def test_the_addon_runs_no_operator_under_an_override():
    assert operators_under_overrides(addon_files()) == []


def test_an_operator_under_an_override_is_found(tmp_path):
    path = tmp_path / "plot.py"
    path.write_text("import bpy\n"
                    "def show(context):\n"
                    "    with context.temp_override(area=context.area):\n"
                    "        if context.area:\n"
                    "            bpy.ops.screen.area_dupli('INVOKE_DEFAULT')\n"
                    "    with context.temp_override(area=context.area):\n"
                    "        nearest(context)\n")
    assert operators_under_overrides([str(path)]) == ["%s:5: bpy.ops.screen.area_dupli" % path]
