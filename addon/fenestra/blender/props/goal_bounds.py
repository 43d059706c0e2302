"""The uniform goal's fields hold only goals the solver takes.

A normalized goal lies in [0, 1] (1 is the light with every element open), a daylight factor in
[0, 100] %, lux from 0 up; and Minimum <= Goal <= Maximum. A property's hard limits cannot depend
on the units, so the fields' update callbacks clamp: the edited value to its units' range, and
the other two values it would cross follow it (as Blender's frame range does).
"""

# The most each unit allows (the core's limits: native/src/scene/sensor_input.cpp check_goals).
TOP = {'NORMALIZED': 1.0, 'DAYLIGHT_FACTOR': 100.0, 'LUX': 1e12}
HARD_MAX = max(TOP.values())


def top(units):
    return TOP.get(units, HARD_MAX)


def _set(goals, name, value):
    if getattr(goals, name) != value:
        setattr(goals, name, value)  # runs that field's callback, which finds nothing to change


def _settle(goals, edited):
    """Clamps the edited field to the units' range, then moves the others it crosses."""
    limit = top(goals.units)
    _set(goals, edited, min(getattr(goals, edited), limit))
    value = getattr(goals, edited)
    if edited == "level":
        _set(goals, "min", min(goals.min, value))
        _set(goals, "max", max(goals.max, value))
    elif edited == "min":
        _set(goals, "level", max(goals.level, value))
        _set(goals, "max", max(goals.max, goals.level))
    elif edited == "max":
        _set(goals, "level", min(goals.level, value))
        _set(goals, "min", min(goals.min, goals.level))


def level_changed(goals, context):
    _settle(goals, "level")


def min_changed(goals, context):
    _settle(goals, "min")


def max_changed(goals, context):
    _settle(goals, "max")


def units_changed(goals, context):
    """Values kept from other units are clamped into the new units' range."""
    limit = top(goals.units)
    for name in ("max", "level", "min"):
        _set(goals, name, min(getattr(goals, name), limit))
