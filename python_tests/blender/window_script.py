"""What the screenshot scripts that drive Blender's window share: timer callbacks that end Blender
on an exception, the checks' verdict as the exit status, a sidebar showing only the Fenestra tab,
and an area cropped from a screenshot of the window."""

import os
import sys
import traceback

import bpy
import numpy as np


def guarded(step):
    """A timer callback that ends Blender with status 1 on an exception."""
    def run():
        try:
            return step()
        except Exception:
            traceback.print_exc()
            sys.stdout.flush()
            os._exit(1)
    return run


def exit_with_verdict(failed):
    """Prints RESULT (the names of the failed checks, or all ok) and ends Blender with its status."""
    print("RESULT %s" % ("FAILED " + " ".join(failed) if failed else "all checks ok"))
    sys.stdout.flush()
    os._exit(1 if failed else 0)


def hide_other_tabs():
    """Takes the 3D View sidebar's panels of the other tabs out (unregistered), so that the Fenestra
    tab is the one shown; returns their classes, to register back."""
    hidden = []
    for name in dir(bpy.types):
        cls = getattr(bpy.types, name)
        if (isinstance(cls, type) and issubclass(cls, bpy.types.Panel) and getattr(cls, "bl_space_type", "") == 'VIEW_3D'
                and getattr(cls, "bl_region_type", "") == 'UI' and getattr(cls, "bl_category", "") != "Fenestra"
                and not name.startswith("FENESTRA_")):
            try:
                bpy.utils.unregister_class(cls)
                hidden.append(cls)
            except RuntimeError:
                pass
    return hidden


def set_panel_options(options):
    """Registers each panel named in `options` again with those bl_options ({'DEFAULT_CLOSED'}: closed)."""
    for name, bl_options in options.items():
        panel = getattr(bpy.types, name)
        bpy.utils.unregister_class(panel)
        panel.bl_options = bl_options
        bpy.utils.register_class(panel)


def only_the_fenestra_tab(closed_panels):
    """The sidebar shows the Fenestra tab alone, with the panels named in `closed_panels` closed."""
    hide_other_tabs()
    set_panel_options({name: {'DEFAULT_CLOSED'} for name in closed_panels})


def save_area(pixels, area, path, name="area_crop"):
    """Writes `area` (its viewport and sidebar), cropped from the window's screenshot `pixels` ((h, w, 3)
    display values, bottom row first), to the PNG `path`."""
    crop = pixels[area.y:area.y + area.height, area.x:area.x + area.width]
    image = bpy.data.images.new(name, crop.shape[1], crop.shape[0])
    image.pixels.foreach_set(np.dstack([crop, np.ones(crop.shape[:2])]).astype(np.float32).ravel())
    image.filepath_raw, image.file_format = path, 'PNG'
    image.save()
    bpy.data.images.remove(image)
