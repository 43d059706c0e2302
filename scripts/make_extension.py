"""Writes the Blender extension: DIST/fenestra-VERSION-linux_x64.zip, holding blender_manifest.toml,
the extension's __init__.py (addon/extension/) and the wheel (make wheel) under wheels/.

    python3 scripts/make_extension.py WHEEL DIST
"""

import os
import sys
import zipfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SOURCE = os.path.join(ROOT, "addon", "extension")
PLATFORM = "linux_x64"  # the zip's name; the manifest's platforms say "linux-x64"


def main(wheel, dist):
    name = os.path.basename(wheel)
    version = name.split("-")[1]
    with open(os.path.join(SOURCE, "blender_manifest.toml"), encoding="utf-8") as f:
        manifest = f.read().replace("@VERSION@", version).replace("@WHEEL@", name)
    out = os.path.join(dist, "fenestra-%s-%s.zip" % (version, PLATFORM))
    part = out + ".part"
    with zipfile.ZipFile(part, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("blender_manifest.toml", manifest)
        z.write(os.path.join(SOURCE, "__init__.py"), "__init__.py")
        z.write(wheel, "wheels/" + name, compress_type=zipfile.ZIP_STORED)  # a wheel is a zip already
    os.replace(part, out)
    print(out)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
