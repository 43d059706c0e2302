"""The add-on's Blender modules run under any package name: as `fenestra` (linked into Blender 3.4's
add-ons) and as `bl_ext.user_default.fenestra` (an extension, 4.2+). They import the package and each
other relatively, and never name the add-on `fenestra` where Blender looks add-ons up
(preferences.addons[...], addon_utils, an AddonPreferences' bl_idname)."""

import ast
import os

from conftest import ROOT

BLENDER_MODULES = os.path.join(ROOT, "addon", "fenestra", "blender")


def name_assumptions(folder):
    """file:line: what, for each place that takes the add-on's module name to be `fenestra`."""
    found = []
    paths = sorted(os.path.join(here, f) for here, _, names in os.walk(folder) for f in names if f.endswith(".py"))
    for path in paths:
        name = os.path.relpath(path, folder)
        with open(path) as f:
            tree = ast.parse(f.read(), path)
        for node in ast.walk(tree):
            where = "%s:%d" % (name, getattr(node, "lineno", 0))
            if isinstance(node, ast.Import):
                found += ["%s: import %s" % (where, a.name) for a in node.names if a.name.split(".")[0] == "fenestra"]
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and (node.module or "").split(".")[0] == "fenestra":
                found.append("%s: from %s import" % (where, node.module))
            elif isinstance(node, ast.Subscript) and isinstance(node.value, ast.Attribute) and node.value.attr == "addons":
                found.append("%s: an add-on looked up in preferences.addons" % where)
            elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
                  and isinstance(node.func.value, ast.Name) and node.func.value.id == "addon_utils"):
                found.append("%s: addon_utils.%s" % (where, node.func.attr))
            elif isinstance(node, ast.ClassDef) and any("AddonPreferences" in ast.unparse(b) for b in node.bases):
                for item in node.body:
                    if (isinstance(item, ast.Assign) and any(getattr(t, "id", None) == "bl_idname" for t in item.targets)
                            and isinstance(item.value, ast.Constant)):
                        found.append("%s: AddonPreferences.bl_idname = %r (not __package__)" % (where, item.value.value))
    return found


def test_blender_modules_assume_no_package_name():
    assert name_assumptions(BLENDER_MODULES) == []


def test_assumptions_are_found(tmp_path):
    (tmp_path / "room").mkdir()
    (tmp_path / "room" / "bad.py").write_text(
        "import addon_utils\nimport bpy\nimport fenestra.api\nfrom fenestra import api\n"
        "prefs = bpy.context.preferences.addons['fenestra'].preferences\n"
        "addon_utils.enable('fenestra')\n"
        "class P(bpy.types.AddonPreferences):\n    bl_idname = 'fenestra'\n"
        "from . import api as fine\n")
    found = name_assumptions(tmp_path)
    assert all(line.startswith(os.path.join("room", "bad.py")) for line in found), found
    assert sorted(int(line.split(":")[1]) for line in found) == [3, 4, 5, 6, 7], found
