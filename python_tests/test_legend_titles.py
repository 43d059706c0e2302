"""The false colour legend's title says why no sensor has a value (docs/blender.md, "Results"):
a trade-off of a climate solve has no per-sensor year (only the answer's is kept), a daylight
factor must be chosen again, other quantities have no goals; a ratio with some sensors without a
goal says they are grey. blender/com/false_colour.py has no bpy: loaded on its own."""

import importlib.util
import math
import os

from conftest import ROOT

spec = importlib.util.spec_from_file_location(  # a module without bpy, loaded without the package (which has)
    "false_colour", os.path.join(ROOT, "addon", "fenestra", "blender", "com", "false_colour.py"))
false_colour = importlib.util.module_from_spec(spec)
spec.loader.exec_module(false_colour)

NONE = [math.nan, math.nan]


def test_a_tradeoff_has_no_per_sensor_year():
    for quantity in ('CLIMATE_DA', 'CLIMATE_MEAN', 'CLIMATE_ASE_HOURS'):
        scale = false_colour.Scale(quantity, 100.0)
        assert scale.title_for(NONE) == scale.title + ": not known for a trade-off (Annual Daylight gives it)"
        assert scale.title_for([50.0, math.nan]) == scale.title


def test_the_other_titles():
    assert false_colour.Scale('DAYLIGHT_FACTOR', 5.0).title_for(NONE).endswith(": not known (choose it again)")
    assert false_colour.Scale('ACHIEVED', 500.0).title_for(NONE) == "Achieved illuminance (lx): no goals"
    assert false_colour.Scale('RATIO', 1.0).title_for([1.0, math.nan]) == "Achieved / goal, grey: no goal"
    assert false_colour.Scale('RATIO', 1.0).title_for([1.0, 2.0]) == "Achieved / goal"
