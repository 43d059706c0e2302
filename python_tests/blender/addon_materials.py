"""Blender materials as Fenestra materials, headless (run by test_blender_addon.py in each Blender):
the Principled BSDF's transmission (an input renamed in 4.0), roughness and metallic, the Glass and
Diffuse BSDFs, and a material without nodes."""

import os
import sys
import unittest

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import installed  # noqa: E402


def principled(name, **inputs):
    """A material whose surface is a Principled BSDF with the given inputs (by 3.4 name:
    transmission, base_color, roughness, metallic)."""
    compat = installed.blender("compat")
    material = bpy.data.materials.new(name)
    compat.use_nodes(material)
    node = material.node_tree.nodes["Principled BSDF"]
    names = {"transmission": compat.PRINCIPLED_TRANSMISSION, "base_color": "Base Color",
             "roughness": "Roughness", "metallic": "Metallic"}
    for key, value in inputs.items():
        node.inputs[names[key]].default_value = value
    return material


def replaced_surface(name, node_type):
    compat = installed.blender("compat")
    material = bpy.data.materials.new(name)
    compat.use_nodes(material)
    tree = material.node_tree
    old = tree.nodes["Principled BSDF"]
    tree.nodes.remove(old)
    node = tree.nodes.new(node_type)
    tree.links.new(node.outputs[0], tree.nodes["Material Output"].inputs["Surface"])
    return material, node


class Materials(unittest.TestCase):
    def setUp(self):
        bpy.ops.wm.read_homefile(use_empty=True)
        installed.enable()
        self.materials = installed.blender("study.materials")

    def test_principled_transmission_is_glass(self):
        m = principled("Pane", transmission=1.0, base_color=(0.9, 0.9, 0.9, 1.0))
        d = self.materials.material_dict(m)
        self.assertEqual(d["type"], "glass", d)
        self.assertAlmostEqual(d["transmittance"], 0.9, places=4)  # capped at a clear pane's

    def test_principled_rough_is_diffuse_and_shiny_is_glossy(self):
        d = self.materials.material_dict(principled("Plaster", base_color=(0.6, 0.5, 0.4, 1.0), roughness=1.0))
        self.assertEqual(d, {"type": "diffuse", "reflectance": [0.6, 0.5, 0.4]})
        d = self.materials.material_dict(principled("Steel", roughness=0.2, metallic=1.0))
        self.assertEqual((d["type"], d["roughness"], d["metallic"]), ("glossy", 0.2, 1.0))

    def test_glass_and_diffuse_bsdfs(self):
        glass, node = replaced_surface("Glass", "ShaderNodeBsdfGlass")
        node.inputs["IOR"].default_value = 1.5
        self.assertEqual(self.materials.material_dict(glass), {"type": "glass", "transmittance": 0.9, "ior": 1.5})
        diffuse, node = replaced_surface("Matte", "ShaderNodeBsdfDiffuse")
        node.inputs["Color"].default_value = (0.25, 0.5, 0.75, 1.0)
        self.assertEqual(self.materials.material_dict(diffuse), {"type": "diffuse", "reflectance": [0.25, 0.5, 0.75]})

    def test_no_node_tree_is_grey(self):
        if bpy.app.version >= (5, 0, 0):
            self.skipTest("from 5.0 every material has its node tree")
        self.assertEqual(self.materials.material_dict(bpy.data.materials.new("Bare")), {"type": "diffuse", "reflectance": 0.5})


if __name__ == "__main__":
    result = unittest.main(argv=[sys.argv[0]], exit=False, verbosity=2).result
    sys.exit(0 if result.wasSuccessful() else 1)
