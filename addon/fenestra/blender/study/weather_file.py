"""The climate sky's weather file: where the setting points to, and whether it can be used.

Checked before anything is exported or written, so that a bad path is refused with a sentence for
the panel rather than the native loader's message about a scene file. Only the name and the file's
existence are checked here; what is inside is the native core's to judge."""

import os

import bpy

EXTENSIONS = (".epw", ".wea")


def path(sky_settings):
    """The weather file as an absolute path ('//' is the .blend file's folder), or "" when unset."""
    chosen = sky_settings.weather_file.strip()
    return os.path.abspath(bpy.path.abspath(chosen)) if chosen else ""


def problem(sky_settings):
    """None when the weather file can be read, else what to change, in the panel's words."""
    chosen = sky_settings.weather_file.strip()
    if not chosen:
        return "Choose a weather file (.epw or .wea) in Sky > Weather File"
    where = path(sky_settings)
    name = os.path.basename(where) or chosen
    if not where.lower().endswith(EXTENSIONS):
        return ("'%s' is not a weather file: choose an EnergyPlus .epw (or a .wea) file in Sky > Weather File"
                % name)
    if not os.path.exists(where):  # the folder is not named: the panel shows the path itself
        relative = " (// is the .blend file's folder)" if chosen.startswith("//") else ""
        return "Weather file '%s' not found: check Sky > Weather File%s" % (name, relative)
    if not os.path.isfile(where) or not os.access(where, os.R_OK):
        return "Weather file '%s' cannot be read: choose a readable .epw or .wea file" % name
    return None
