"""The solver's automatic constraints as the Constraints panel shows them, greyed beside the
fields left at 0 (the values come from the native module: one source of truth)."""

from ..com import native

_cache = {}

# Keys a chosen catalogue replaces: its sizes are the openings' sizes.
_CATALOGUE_SIZES = ("min_width", "min_height")


def _defaults(full_height, climate):
    if (full_height, climate) not in _cache:
        from ...api import automatic_constraints
        _cache[full_height, climate] = automatic_constraints(full_height=full_height, climate=climate)
    return _cache[full_height, climate]


def _text(key, value):
    if key == "panel_width_per_opening":
        return "auto 1 per %g m" % value
    if key == "min_area":
        return "auto %g m\u00b2" % value
    return "auto %g m" % value


def automatic_values(constraints, climate=False):
    """{key: greyed text} for the keys left at 0 that the solver fills in; `climate`: the study has
    climate goals."""
    if not constraints.automatic or native.unavailable() is not None:
        return {}
    values = _defaults(bool(constraints.full_height), bool(climate))
    return {key: _text(key, value) for key, (value, _why) in values.items()
            if getattr(constraints, key) == 0 and not (constraints.catalogue != 'NONE' and key in _CATALOGUE_SIZES)}


# Sills and heads the solver aligns by default, where that costs at most a point of error.
_ALIGNED = ("align_sills", "align_heads")


def aligned_by_default(constraints):
    """The composition keys the solver applies by default (docs/solver.md, "Facade composition"):
    with Automatic on, Full Height off and none of Align Sills, Align Heads or Sill Heights set."""
    if not constraints.automatic or constraints.full_height or constraints.sill_heights.strip():
        return ()
    if any(getattr(constraints, key) for key in _ALIGNED):
        return ()
    return _ALIGNED
