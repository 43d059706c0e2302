"""The native classes' methods (Contributions.save, Progress(), ...) called with arguments of the
wrong type: a TypeError in Fenestra's words, naming the method, what it takes and the types it got,
instead of pybind11's "incompatible function arguments" listing of every overload (no bpy here)."""

import functools
import re

from . import _core
from .arguments import MAX_SHOWN

_PYBIND_WORDING = ("incompatible function arguments", "incompatible constructor arguments")
_CLASSES = ("Scene", "Contributions", "Progress", "RecordQueries", "RegionSearch", "CostScope")


def _signature(text):
    """'(self: fenestra._core.Contributions, scene: fenestra._core.Scene, path: str) -> Tuple[str, str]'
    -> '(scene: Scene, path: str)'."""
    text = text.replace("fenestra._core.", "").split(" -> ")[0]
    return re.sub(r"^\(self: \w+(, )?", "(", text)


def _worded(owner, name, method):
    shown = "%s()" % owner if name == "__init__" else "%s.%s()" % (owner, name)

    @functools.wraps(method)
    def call(*args, **kwargs):
        try:
            return method(*args, **kwargs)
        except TypeError as exc:
            text = str(exc)
            if not any(words in text for words in _PYBIND_WORDING):
                raise
            takes = " or ".join(_signature(s) for s in re.findall(r"^\s*\d+\. (?:[\w.]+)?(\(.*\))", text, re.M))
            got = [type(a).__name__ for a in args[1:]] + ["%s=%s" % (k, type(v).__name__) for k, v in kwargs.items()]
            message = "%s takes %s; got (%s)" % (shown, takes or "other arguments", ", ".join(got))
            if len(message) > 4 * MAX_SHOWN:
                message = message[:4 * MAX_SHOWN - 3] + "..."
            raise TypeError(message) from None
    return call


def install():
    """Wraps every method and constructor of the native classes; calling it again does nothing."""
    for owner in _CLASSES:
        cls = getattr(_core, owner, None)
        if cls is None:
            continue
        for name, member in list(vars(cls).items()):
            if name.startswith("__") and name != "__init__":
                continue
            if type(member).__name__ not in ("instancemethod", "wrapper_descriptor") or getattr(member, "_worded", False):
                continue
            if name == "__init__" and type(member).__name__ == "wrapper_descriptor":
                continue  # no constructor from Python (object.__init__)
            wrapped = _worded(owner, name, member)
            wrapped._worded = True
            setattr(cls, name, wrapped)
