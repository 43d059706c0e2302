"""Fenestra as a Blender 4.2+ extension (bl_ext.<repository>.fenestra).

The add-on itself is fenestra.blender, in the fenestra wheel that this extension bundles
(blender_manifest.toml) and Blender installs into its extensions' site-packages: this module only
hands Blender its register/unregister, so every Python file exists once. Blender 3.4 takes the
package directly instead (`make install-addon`, bl_info in fenestra/__init__.py).
"""

from fenestra import register, unregister  # noqa: F401
