"""The unobstructed horizontal illuminance of the sky a result was solved under: what daylight
factors are a percentage of. The native core computes it from the study's own sky section (the
sky settings may have changed since the solve); it is asked once, when daylight factors are first
shown, and kept on the results."""

import json
import tempfile

from ..com import native


def ensure_horizontal_illuminance(scene):
    """Lux, computed when not known yet; 0 when it cannot be (no result, no native module, no study)."""
    results = scene.fenestra.results
    if not results.valid:
        return 0.0
    if results.horizontal_illuminance <= 0.0 and native.unavailable() is None:
        from ... import api as fenestra
        try:
            with open(results.study_path) as f:
                sky = json.load(f)["sky"]
            with tempfile.TemporaryDirectory() as probe:
                summary = fenestra.sky(native.probe_scene(probe, sky=sky))
            results.horizontal_illuminance = summary["horizontal_illuminance"]["total"]
        except (OSError, KeyError, ValueError):
            return 0.0
    return results.horizontal_illuminance
