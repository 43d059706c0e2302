"""The add-on as the Blender running a test script has it: enabled, and its modules by name.

The pytest driver (python_tests/blenders.py) says how it is installed, in the environment:
FENESTRA_ADDON_MODULE is the module Blender knows it by, "fenestra" when the checkout's
addon/fenestra is linked into the add-on folder (Blender 3.4, or 4.5 before an extension zip is
built), "bl_ext.user_default.fenestra" when it is installed as an extension; FENESTRA_EXTENSION_ZIP,
when set, is the zip that enable() first installs with Blender's own installer. The add-on's Python
API is `import fenestra` in both cases (the checkout's package, or the wheel the zip bundles); the
Blender modules are package().blender.*, wherever the add-on module keeps them."""

import importlib
import importlib.util
import os

import addon_utils
import bpy

NAME = os.environ.get("FENESTRA_ADDON_MODULE", "fenestra")
ZIP = os.environ.get("FENESTRA_EXTENSION_ZIP")


def _install_zip():
    if NAME in bpy.context.preferences.addons or importlib.util.find_spec(NAME) is not None:
        return  # enabled, or installed by an earlier run in the same user folder
    result = bpy.ops.extensions.package_install_files(filepath=ZIP, repo="user_default", enable_on_install=True)
    assert result == {'FINISHED'}, "the extension %s did not install: %s" % (ZIP, result)


def enable():
    if ZIP:
        _install_zip()
    addon_utils.enable(NAME, default_set=True, handle_error=None)
    assert hasattr(bpy.types.Scene, "fenestra"), "the add-on %s did not register" % NAME


def disable():
    addon_utils.disable(NAME, default_set=True, handle_error=None)


def package():
    """The package that holds the add-on's modules: the one whose register() Blender calls
    (`fenestra` itself when linked; the bundled wheel's when the extension hands it on)."""
    return importlib.import_module(importlib.import_module(NAME).register.__module__)


def blender(name):
    """The add-on's Blender module `name`, by its room (study.export, result.results, ...)."""
    return importlib.import_module("%s.blender.%s" % (package().__name__, name))
