#!/usr/bin/python3
"""The house rule of the native core: each layer includes only layers below it (docs/architecture.md).

Reads every `#include "..."` of native/src, native/images, native/cli, native/python and bench/ and
fails, naming file:line and the arrow, when a file includes a room on a higher floor or another room
on its own floor. Standard library only; exit status 1 on a broken rule."""

import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent

# Floors from the bottom up; rooms on one floor may not include each other.
FLOORS = [
    ["util"],  # plain helpers and the memory budget
    ["format"],  # JSON text, npz, atomic files, image I/O: no Fenestra type
    ["images"],  # the OpenImageIO module, built apart, behind format's image ABI
    ["math"],
    ["sampling"],
    ["daylight"],  # daylight skies, weather, sky patches, the annual sources, the sky in figures
    ["scene"],  # what a study is: geometry, sky settings, sensors, constraints
    ["trace"],
    ["annual"],
    ["solve"],
    ["study"],  # the cost model and the checks before each stage
    ["io"],  # result writers
    ["cli", "python", "bench"],
]
FLOOR = {room: level for level, rooms in enumerate(FLOORS) for room in rooms}

# Folders outside native/src that are rooms of their own.
TOP = {"images": ROOT / "native/images", "cli": ROOT / "native/cli",
       "python": ROOT / "native/python", "bench": ROOT / "bench"}

# Arrows up that are known and being taken down, each with its reason (issue 37). Empty when done.
ALLOWED = {}

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def room_of(path):
    """The room a source file belongs to: its folder under native/src, or cli, python, bench."""
    for room, folder in TOP.items():
        if folder in path.parents:
            return room
    return path.relative_to(ROOT / "native/src").parts[0]


def included_room(name, source_room):
    """The room an include names: the folder of "room/file.h", or the includer's own for "file.h"."""
    parts = pathlib.PurePosixPath(name).parts
    return parts[0] if len(parts) > 1 else source_room


def arrows():
    """(file, line, from room, to room) of every include that breaks the rule."""
    files = sorted(p for p in (ROOT / "native/src").rglob("*") if p.suffix in (".h", ".cpp"))
    for folder in TOP.values():
        files += sorted(p for p in folder.rglob("*") if p.suffix in (".h", ".cpp"))
    found = []
    for path in files:
        source = room_of(path)
        if source not in FLOOR:
            found.append((path, 0, source, "?"))
            continue
        for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
            match = INCLUDE.match(line)
            if not match:
                continue
            target = included_room(match.group(1), source)
            if target == source:
                continue
            if target not in FLOOR or FLOOR[target] >= FLOOR[source]:
                found.append((path, number, source, target))
    return found


def main():
    broken, seen = [], set()
    for path, number, source, target in arrows():
        seen.add((source, target))
        if (source, target) in ALLOWED:
            continue
        where = f"{path.relative_to(ROOT)}:{number}"
        if target == "?":
            broken.append(f"{where}: folder '{source}' is on no floor (scripts/check_layers.py FLOORS)")
        elif target not in FLOOR:
            broken.append(f"{where}: {source} -> {target}: '{target}' is on no floor")
        else:
            side = "on its own floor" if FLOOR[target] == FLOOR[source] else "a floor up"
            broken.append(f"{where}: {source} -> {target}: includes a room {side}")
    stale = sorted(set(ALLOWED) - seen)
    for source, target in stale:
        broken.append(f"scripts/check_layers.py: allowed arrow {source} -> {target} is gone: "
                      "take it off ALLOWED")
    for line in broken:
        print(line)
    known = len(seen & set(ALLOWED))
    print(f"layers: {len(broken)} broken, {known} known arrows up still allowed")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
