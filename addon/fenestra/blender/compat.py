"""Where Blender's Python API differs between the versions the add-on runs in (3.4 to 5.x): each
entry names the versions it serves. The rest of the add-on calls these and never reads
bpy.app.version. Tested in 3.4 and 4.5 (python_tests/test_blender_api_names.py lists what the
add-on uses and checks it in each); the 5.0 entries follow its release notes.

Gone from the add-on rather than wrapped here, because each has one spelling that serves 3.4 to 5.x:
bgl (removed in 5.0: drawing is gpu and blf only); the Boolean solver 'FAST' (renamed 'FLOAT' in
5.0: BOOLEAN_SOLVER); dict context overrides (removed in 4.0: Context.temp_override, 3.2+);
use_auto_smooth and Mesh.calc_normals (removed in 4.1: never used); Operator.__init__ (must pass
its arguments on from 4.4: no operator defines one); blf.size's dpi argument (removed in 4.0:
optional since 3.4); the render engine id (BLENDER_EEVEE_NEXT in 4.2 to 4.5: the add-on sets no
engine)."""

import bpy

VERSION = tuple(bpy.app.version[:2])

# The Boolean modifier's exact solver: 'EXACT' from 2.91 through 5.x ('FAST' became 'FLOAT' in 5.0).
BOOLEAN_SOLVER = 'EXACT'

# Built-in shaders: these names from 3.4 on; the '2D_' / '3D_' prefixed ones were removed in 4.0.
FLAT_COLOR_SHADER = 'FLAT_COLOR'
SMOOTH_COLOR_SHADER = 'SMOOTH_COLOR'
UNIFORM_COLOR_SHADER = 'UNIFORM_COLOR'

# The Principled BSDF's transmission input: "Transmission" up to 3.6, "Transmission Weight" from 4.0.
PRINCIPLED_TRANSMISSION = "Transmission" if VERSION < (4, 0) else "Transmission Weight"


def new_group_socket(tree, in_out, socket_type, name):
    """A node group's input or output socket (in_out 'INPUT' or 'OUTPUT'): tree.inputs / tree.outputs
    up to 3.6, tree.interface from 4.0 (the former were removed)."""
    if VERSION < (4, 0):
        return (tree.inputs if in_out == 'INPUT' else tree.outputs).new(socket_type, name)
    return tree.interface.new_socket(name, in_out=in_out, socket_type=socket_type)


def use_nodes(idblock):
    """Gives a material or world its node tree: use_nodes must be set up to 4.5; from 5.0 the tree is
    always used and the flag is deprecated (a no-op, to be removed)."""
    if VERSION < (5, 0):
        idblock.use_nodes = True


def uses_nodes(idblock):
    """Whether a material or world is drawn by its node tree: use_nodes up to 4.5, always from 5.0."""
    if VERSION < (5, 0) and not idblock.use_nodes:
        return False
    return idblock.node_tree is not None
