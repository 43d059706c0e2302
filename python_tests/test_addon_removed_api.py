"""The add-on uses none of the Blender API that 4.0 to 5.0 removed or changed, even where the
tested Blenders (3.4, 4.5) still have it (docs/blender.md, "Blender versions"): bgl (removed in
5.0), the Boolean solver 'FAST' (renamed 'FLOAT' in 5.0), dict context overrides to operators
(removed in 4.0), use_auto_smooth and calc_normals (4.1), an Operator.__init__ that does not pass
its arguments on (4.4), '2D_' / '3D_' built-in shader names (4.0), a render engine id (one per
version range), use_nodes outside compat.py (deprecated in 5.0)."""

import ast
import os

from conftest import ROOT

ADDON = os.path.join(ROOT, "addon", "fenestra")
REMOVED_ATTRIBUTES = {"use_auto_smooth", "auto_smooth_angle", "calc_normals", "calc_normals_split"}


def is_operator_call(node):
    """bpy.ops.GROUP.NAME(...)."""
    f = node.func
    return (isinstance(f, ast.Attribute) and isinstance(f.value, ast.Attribute)
            and isinstance(f.value.value, ast.Attribute) and f.value.value.attr == "ops")


def removed_uses(files):
    found = []
    for path in files:
        with open(path) as f:
            tree = ast.parse(f.read(), path)
        name = os.path.relpath(path, ADDON) if path.startswith(ADDON) else os.path.basename(path)
        for node in ast.walk(tree):
            where = "%s:%d" % (name, getattr(node, "lineno", 0))
            if isinstance(node, (ast.Import, ast.ImportFrom)):
                modules = [a.name for a in node.names] if isinstance(node, ast.Import) else [node.module or ""]
                found += ["%s: bgl" % where for m in modules if m.split(".")[0] == "bgl"]
            elif isinstance(node, ast.Attribute) and node.attr in REMOVED_ATTRIBUTES:
                found.append("%s: %s" % (where, node.attr))
            elif (isinstance(node, ast.Attribute) and node.attr == "use_nodes" and ast.unparse(node.value) != "compat"
                  and name != os.path.join("blender", "compat.py")):
                found.append("%s: use_nodes outside compat.py" % where)
            elif isinstance(node, ast.Constant) and isinstance(node.value, str):
                if node.value == "FAST" or node.value.startswith(("2D_", "3D_")) or node.value.startswith("BLENDER_EEVEE"):
                    found.append("%s: '%s'" % (where, node.value))
            elif isinstance(node, ast.Call) and is_operator_call(node) and node.args and isinstance(node.args[0], ast.Dict):
                found.append("%s: a dict context override" % where)
            elif isinstance(node, ast.ClassDef) and any("Operator" in ast.unparse(b) for b in node.bases):
                for item in node.body:
                    if isinstance(item, ast.FunctionDef) and item.name == "__init__":
                        passes = any(isinstance(n, ast.Call) and ast.unparse(n.func) == "super().__init__"
                                     and any(isinstance(a, ast.Starred) for a in n.args) for n in ast.walk(item))
                        if not passes:
                            found.append("%s: Operator.__init__ without super().__init__(*args, **kwargs)" % where)
    return found


def addon_files():
    return [os.path.join(folder, f) for folder, _, names in os.walk(ADDON) for f in names if f.endswith(".py")]


def test_the_addon_uses_no_removed_api():
    assert removed_uses(addon_files()) == []


def test_removed_uses_are_found(tmp_path):
    bad = tmp_path / "bad.py"
    bad.write_text(
        "import bgl\nimport bpy\n"
        "def f(mesh, m, world, ctx):\n"
        "    mesh.use_auto_smooth = True\n"
        "    mesh.calc_normals()\n"
        "    m.solver = 'FAST'\n"
        "    bpy.ops.object.delete({'selected_objects': []})\n"
        "    world.use_nodes = True\n"
        "    return bpy.context.scene.render.engine == 'BLENDER_EEVEE_NEXT', '3D_UNIFORM_COLOR'\n"
        "class O(bpy.types.Operator):\n"
        "    def __init__(self):\n"
        "        self.x = 1\n"
        "class Fine(bpy.types.Operator):\n"
        "    def __init__(self, *args, **kwargs):\n"
        "        super().__init__(*args, **kwargs)\n")
    found = removed_uses([str(bad)])
    assert sorted(int(line.split(":")[1]) for line in found) == [1, 4, 5, 6, 7, 8, 9, 9, 10], found
