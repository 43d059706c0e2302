"""Fenestra's keyboard shortcuts: Solve Openings, Evaluate, Annual Daylight and Check Setup in the
add-on key configuration's "Object Mode" keymap (the pointer over the 3D View, in Object Mode).

Blender's right-click menu on a button offers *Change Shortcut* for an operator that has a
keyboard shortcut, and *Assign Shortcut* only for operators whose name tells it a keymap (object.*,
mesh.*, ...): for fenestra.* it offers neither until the operator has a keymap item. These items
give every command a shortcut to change or remove from the right-click menu (on its button or in
Object > Fenestra) or in Preferences > Keymap. Their keys are among the F-keys Blender leaves free."""

import bpy

KEYMAP = ("Object Mode", 'EMPTY')  # name, space type: as Blender's own keymap of that name
SHORTCUTS = (  # operator, key, modifiers
    ("fenestra.solve_openings", 'F5', {"shift": True}),
    ("fenestra.evaluate_openings", 'F6', {"shift": True}),
    ("fenestra.annual_daylight", 'F7', {"shift": True}),
    ("fenestra.check_setup", 'F8', {"shift": True}),
)
_added = []  # (keymap, item): removed again on unregister


def register():
    keyconfig = bpy.context.window_manager.keyconfigs.addon
    if keyconfig is None:  # background mode: no key configurations
        return
    name, space = KEYMAP
    keymap = keyconfig.keymaps.new(name=name, space_type=space)
    for operator, key, modifiers in SHORTCUTS:
        _added.append((keymap, keymap.keymap_items.new(operator, key, 'PRESS', **modifiers)))


def unregister():
    for keymap, item in _added:
        keymap.keymap_items.remove(item)
    _added.clear()
