"""Blender materials as Fenestra materials (docs/scene-format.md): what daylight sees of a surface."""

from .. import compat

GREY = {"type": "diffuse", "reflectance": 0.5}
CLEAR_PANE = 0.9  # a thin pane cannot transmit more than a clear pane of its index (0.918 at 1.52)
LUMINANCE = (0.2126, 0.7152, 0.0722)


def _rgb(value):
    return [round(min(max(float(c), 0.0), 1.0), 4) for c in value[:3]]


def _input(node, name, fallback):
    """An input's own value; a linked input (a texture, ...) gives the fallback."""
    socket = node.inputs.get(name)
    if socket is None or socket.is_linked:
        return fallback
    return socket.default_value


def _surface_node(material):
    """The shader plugged into the active material output's Surface, or None."""
    if not compat.uses_nodes(material):
        return None
    outputs = [n for n in material.node_tree.nodes if n.bl_idname == "ShaderNodeOutputMaterial"]
    active = [n for n in outputs if n.is_active_output] or outputs
    if not active:
        return None
    surface = active[0].inputs["Surface"]
    return surface.links[0].from_node if surface.is_linked else None


def material_dict(material):
    """Principled BSDF: base colour -> reflectance, roughness and metallic -> glossy (diffuse when
    fully rough and not metallic), transmission -> a thin glass pane. Glass BSDF -> glass; Diffuse
    BSDF -> diffuse; another shader -> its viewport colour, diffuse; no node tree -> diffuse grey."""
    if material is None:
        return dict(GREY)
    node = _surface_node(material)
    viewport = _rgb(material.diffuse_color)
    if node is None:
        return dict(GREY)
    kind = node.bl_idname
    if kind == "ShaderNodeBsdfPrincipled":
        color = _rgb(_input(node, "Base Color", material.diffuse_color))
        transmission = float(_input(node, compat.PRINCIPLED_TRANSMISSION, 0.0))
        if transmission > 0.5:
            lum = sum(c * w for c, w in zip(color, LUMINANCE))
            return {"type": "glass", "transmittance": round(min(CLEAR_PANE, transmission * lum), 4),
                    "ior": round(float(_input(node, "IOR", 1.52)), 4)}
        roughness = float(_input(node, "Roughness", 0.5))
        metallic = float(_input(node, "Metallic", 0.0))
        if roughness >= 0.99 and metallic <= 0.0:
            return {"type": "diffuse", "reflectance": color}
        return {"type": "glossy", "reflectance": color, "roughness": round(roughness, 4),
                "metallic": round(metallic, 4)}
    if kind == "ShaderNodeBsdfGlass":
        color = _rgb(_input(node, "Color", (1, 1, 1)))
        lum = sum(c * w for c, w in zip(color, LUMINANCE))
        return {"type": "glass", "transmittance": round(min(CLEAR_PANE, lum), 4),
                "ior": round(float(_input(node, "IOR", 1.52)), 4)}
    if kind == "ShaderNodeBsdfDiffuse":
        return {"type": "diffuse", "reflectance": _rgb(_input(node, "Color", material.diffuse_color))}
    return {"type": "diffuse", "reflectance": viewport}
