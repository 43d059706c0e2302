"""Dicts in the scene-file and openings-file formats as JSON text for the native loaders, which
check them as they check files. What JSON cannot hold is refused here, naming its key, rather
than by json.dumps (NaN would pass as the non-JSON word NaN, a NumPy float32 not at all)."""

import json
import math

import numpy as np

MAX_DEPTH = 64  # as the native reader (io/json_input.h)
QUOTED_CHARS = 80  # as util/quoted_text.h


def quoted(text):
    """`text` cut to about 80 characters, as the native messages quote user text."""
    text = str(text)
    return text if len(text) <= QUOTED_CHARS else text[:QUOTED_CHARS] + "..."


def _plain(value, source, path, depth):
    where = lambda: "%s: %s" % (source, quoted(path or "(top level)"))
    if depth > MAX_DEPTH:
        raise ValueError("%s: lists and objects nest deeper than %d levels" % (where(), MAX_DEPTH))
    if isinstance(value, dict):
        out = {}
        for key, item in value.items():
            if not isinstance(key, str):
                raise ValueError("%s: key %s is not a string" % (where(), quoted(repr(key))))
            out[key] = _plain(item, source, path + "." + key if path else key, depth + 1)
        return out
    if isinstance(value, (list, tuple, np.ndarray)):
        return [_plain(item, source, "%s[%d]" % (path, i), depth + 1) for i, item in enumerate(value)]
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        raise ValueError("%s: %s is not a finite number; JSON holds finite numbers only" % (where(), value))
    if value is None or isinstance(value, (str, bool, int, float)):
        return value
    raise ValueError("%s: a %s is not a JSON value (numbers, strings, true or false, null, lists and dicts are)"
                     % (where(), type(value).__name__))


def json_text(value, source):
    """JSON text of `value` (dicts, lists, tuples, NumPy arrays and scalars, numbers, strings, bools,
    None); ValueError "<source>: <key path>: ..." for anything else. `source` as the native
    messages name it, e.g. "scene '<dict>'"."""
    return json.dumps(_plain(value, source, "", 0))
