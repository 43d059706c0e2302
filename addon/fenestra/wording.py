"""Counts in words a person reads: "1 face", "2 faces" (no bpy here)."""


def counted(n, noun, plural=None):
    """`n` and the noun, singular for exactly one: counted(1, "opening") is "1 opening",
    counted(3, "opening") "3 openings"; `plural` for nouns that do not take an s."""
    return "%d %s" % (n, noun if n == 1 else (plural or noun + "s"))
