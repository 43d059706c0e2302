"""Painting goals: a sensor object in Vertex Paint shows the goals being painted. Its achieved false
colour is hidden while it is painted (result_display.sensor_objects leaves it out) and its goal
attribute (names.GOAL_ATTRIBUTE) becomes the active colour attribute, the one the brush paints and
the viewport shows; back in Object Mode the false colour of the result is drawn again.

Blender tells of a mode change through its message bus (Object.mode); subscriptions end with the
file, so they are made again after each file is loaded."""

import bpy

from ..com import names

_owner = object()  # the message bus subscriptions' owner


def show_goals(obj):
    """Makes the goal attribute of a sensor object in Vertex Paint the active colour attribute;
    returns whether it did."""
    if obj is None or obj.type != 'MESH' or not obj.fenestra.is_sensor or obj.mode != 'VERTEX_PAINT':
        return False
    colours = obj.data.color_attributes
    if names.GOAL_ATTRIBUTE not in colours:
        return False  # goals not painted (uniform), or not as colours
    if colours.active_color_name != names.GOAL_ATTRIBUTE:
        colours.active_color_name = names.GOAL_ATTRIBUTE
    return True


def _mode_changed():
    show_goals(bpy.context.view_layer.objects.active if bpy.context.view_layer else None)


def _subscribe():
    bpy.msgbus.clear_by_owner(_owner)
    bpy.msgbus.subscribe_rna(key=(bpy.types.Object, "mode"), owner=_owner, args=(), notify=_mode_changed)


@bpy.app.handlers.persistent
def _file_loaded(*_):
    _subscribe()


def register():
    _subscribe()
    bpy.app.handlers.load_post.append(_file_loaded)


def unregister():
    if _file_loaded in bpy.app.handlers.load_post:
        bpy.app.handlers.load_post.remove(_file_loaded)
    bpy.msgbus.clear_by_owner(_owner)
