"""Whether the native module loaded with the package, and if not, why: set once by the package's
__init__ (inside Blender the add-on registers without it), read by the add-on's panel."""

import_error = None  # the ImportError that kept fenestra._core (or its API) from loading
