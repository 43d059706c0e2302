"""Marked objects that a study leaves out because they are hidden, and how each one is hidden.

The export reads what the viewport shows (a hidden object is not part of the building), while
the panel counts every marked face and sensor: these name the hidden ones, so that "no domain"
or "no sensors" is not said of a scene where the user sees both marked.
"""

import numpy as np

from ..com.names import DOMAIN_ATTRIBUTE


def _layer_path(layer_collection, collection):
    """The layer collections from the view layer's root down to the one of `collection`, or None."""
    if layer_collection.collection == collection:
        return [layer_collection]
    for child in layer_collection.children:
        path = _layer_path(child, collection)
        if path is not None:
            return [layer_collection] + path
    return None


def hidden_reason(obj, view_layer):
    """How obj is hidden in the view layer, in the Outliner's words."""
    if obj.hide_viewport:
        return "it is disabled in viewports, the monitor icon in the Outliner"
    for collection in obj.users_collection:
        for layer in (_layer_path(view_layer.layer_collection, collection) or [])[1:]:
            if layer.exclude:
                return "its collection '%s' is excluded from the view layer" % layer.name
            if layer.collection.hide_viewport:
                return "its collection '%s' is disabled in viewports" % layer.name
            if layer.hide_viewport:
                return "its collection '%s' is hidden" % layer.name
    if obj.name not in view_layer.objects:
        return "it is in no collection of the view layer '%s'" % view_layer.name
    if obj.hide_get(view_layer=view_layer):
        return "it is hidden, Alt+H shows it"
    return "it is not shown in the viewport"


def _domain_faces(obj):
    attr = obj.data.attributes.get(DOMAIN_ATTRIBUTE)
    if attr is None or attr.domain != 'FACE' or attr.data_type != 'BOOLEAN' or len(attr.data) == 0:
        return 0
    flags = np.zeros(len(attr.data), bool)
    attr.data.foreach_get("value", flags)
    return int(flags.sum())


def hidden_domain(context):
    """[(object, domain faces, how it is hidden)] for the hidden meshes with domain faces."""
    found = []
    for obj in context.scene.objects:
        if obj.type != 'MESH' or obj.fenestra.is_sensor or obj.fenestra.is_opening or obj.visible_get():
            continue
        faces = _domain_faces(obj)
        if faces:
            found.append((obj, faces, hidden_reason(obj, context.view_layer)))
    return found


def hidden_sensors(context):
    """[(object, vertices, how it is hidden)] for the hidden sensor objects."""
    return [(obj, len(obj.data.vertices) if obj.type == 'MESH' else 0, hidden_reason(obj, context.view_layer))
            for obj in context.scene.objects if obj.fenestra.is_sensor and not obj.visible_get()]


def _listed(found):
    return "; ".join("'%s' (%s)" % (obj.name, reason) for obj, _, reason in found)


def no_domain_message(context):
    """Why a scene without visible domain faces has none, when hidden objects hold them; else None."""
    found = hidden_domain(context)
    if not found:
        return None
    if len(found) == 1:
        return ("The domain faces of '%s' are on a hidden object: %s. Unhide it, or mark faces of a visible "
                "object" % (found[0][0].name, found[0][2]))
    return ("The domain faces are on hidden objects: %s. Unhide them, or mark faces of a visible object"
            % _listed(found))


def no_sensors_message(context):
    """Why a scene without visible sensors has none, when hidden objects are sensors; else None."""
    found = hidden_sensors(context)
    if not found:
        return None
    if len(found) == 1:
        return ("The sensors of '%s' are on a hidden object: %s. Unhide it, or add a sensor grid"
                % (found[0][0].name, found[0][2]))
    return "The sensors are on hidden objects: %s. Unhide them, or add a sensor grid" % _listed(found)
