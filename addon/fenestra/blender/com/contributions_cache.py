"""The contributions of the last solve, kept in memory for the next one. They cost nearly all of a
solve's time and depend only on what study_fingerprint.contributions_fingerprint digests, so a
re-solve after repainting goals or changing constraints reuses them. One study is kept: taking
others frees these first, so that two sets never hold memory together; and none that holds more
than the memory still available. No bpy here."""

_kept = {"fingerprint": None, "contributions": None}


def take(fingerprint):
    """The kept contributions if they were computed for `fingerprint`; otherwise None, and the
    kept ones are freed (the caller is about to compute others)."""
    if _kept["fingerprint"] == fingerprint:
        return _kept["contributions"]
    clear()
    return None


def keep(fingerprint, contributions):
    """Keeps them, unless they hold more memory than the system still has available: the rest of
    Blender (a render, another study) comes first, and a re-solve then computes them again."""
    from ... import api as fenestra
    if int(contributions.memory_bytes) > fenestra.available_memory()["bytes"]:
        clear()
        return False
    _kept["fingerprint"], _kept["contributions"] = fingerprint, contributions
    return True


def clear():
    _kept["fingerprint"], _kept["contributions"] = None, None


def memory_bytes():
    """What the kept contributions hold (0: none kept)."""
    c = _kept["contributions"]
    return 0 if c is None else int(c.memory_bytes)
