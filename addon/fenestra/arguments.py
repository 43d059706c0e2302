"""Checks of the Python API's arguments before they reach the native module (no bpy here).

A value of the wrong type handed straight to the native module gets pybind11's "incompatible
function arguments" with a dump of every signature; these checks say instead which argument is
wrong and what it accepts: "latitude_deg must be a number, got 'abc'" (TypeError for a wrong type,
ValueError for a value of the right type out of range).
"""

import numbers
import os

import numpy as np

MAX_SHOWN = 80  # characters of a value quoted in a message


def shown(value):
    """repr(value), cut to about MAX_SHOWN characters."""
    try:
        text = repr(value)
    except Exception:  # a repr that fails still names the type
        text = "<%s>" % type(value).__name__
    return text if len(text) <= MAX_SHOWN else text[:MAX_SHOWN - 3] + "..."


def number(value, name):
    """A real number (int, float or a NumPy scalar; not bool) as a float."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise TypeError("%s must be a number, got %s" % (name, shown(value)))
    return float(value)


def optional_number(value, name):
    return None if value is None else number(value, name)


def integer(value, name, lo, hi):
    """A whole number in [lo, hi] (int or a NumPy integer; not bool) as an int."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        raise TypeError("%s must be an integer in [%d, %d], got %s" % (name, lo, hi, shown(value)))
    if not lo <= int(value) <= hi:
        raise ValueError("%s must be an integer in [%d, %d], got %s" % (name, lo, hi, shown(value)))
    return int(value)


def flag(value, name):
    """True or False (a bool or NumPy bool)."""
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError("%s must be True or False, got %s" % (name, shown(value)))
    return bool(value)


def text(value, name):
    if not isinstance(value, str):
        raise TypeError("%s must be a string, got %s" % (name, shown(value)))
    return value


def optional_text(value, name):
    return None if value is None else text(value, name)


def path(value, name="path"):
    """A file path (str, bytes or os.PathLike) as a str or bytes (bytes that are not UTF-8 stay
    bytes: the native module takes them as they are)."""
    try:
        return os.fspath(value)
    except TypeError:
        raise TypeError("%s must be a file path (a str or os.PathLike), got %s" % (name, shown(value))) from None


def array(value, name, form, ndim=None):
    """A float64 array from anything NumPy reads as numbers; `form` says what is expected, e.g.
    "of shape (n, 3)". With `ndim`, an array of another number of dimensions is refused; the sizes
    are the native module's to check."""
    try:
        result = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise TypeError("%s must be an array of numbers %s, got %s" % (name, form, shown(value))) from None
    if ndim is not None and result.ndim != ndim:
        raise ValueError("%s must be an array of numbers %s, got %s" % (name, form, shown(value)))
    return result


def instance(value, cls, name, what):
    """`value` itself when it is a `cls`; `what` names where such a value comes from."""
    if not isinstance(value, cls):
        raise TypeError("%s must be %s, got %s" % (name, what, shown(value)))
    return value


def optional_instance(value, cls, name, what):
    return None if value is None else instance(value, cls, name, what)


def callback(value):
    """None or a callable taking (fraction, status)."""
    if value is not None and not callable(value):
        raise TypeError("callback must be a function of (fraction, status) or None, got %s" % shown(value))
    return value
