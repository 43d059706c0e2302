"""The Python API's arguments are checked in Fenestra's words: a value of the wrong type in any
argument of any public function gives a TypeError or ValueError that names the argument, never
pybind11's "incompatible function arguments" dump of signatures. And NumPy values in a scene dict
are written as plain numbers (they used to give "Object of type float32 is not JSON serializable")."""

import inspect
import json

import numpy as np
import pytest

import fenestra

# Values of every common wrong type (and some right types with wrong values).
BAD = [object(), "abc", 1.5, [1, 2], {"a": 1}, b"x", 1j, np.float32(2.0), True, -1, np.array([[1.0, 2.0]]),
       float("nan"), "x" * 500]

LIBRARY_WORDING = ("incompatible function arguments", "Invoked with", "pybind11", "_core.", "arg0",
                   "could not convert", "is not JSON serializable", "object is not iterable")


def valid_arguments(small_room, tmp_path):
    """For each public function, arguments with which it does its work (or refuses for a reason
    other than a type), by parameter name; parameters not named keep their defaults."""
    scene = fenestra.load_scene(small_room)
    scene.render.paths_per_sensor = 16
    openings = np.array([[[0.5, 0.0, 0.5], [1.5, 0.0, 0.5], [1.5, 0.0, 1.5], [0.5, 0.0, 1.5]]])
    (tmp_path / "openings.json").write_text(json.dumps({"openings": [{"corners": openings[0].tolist()}]}))
    scene_dict = json.loads(small_room.read_text())
    return {
        "annual": dict(scene=scene, openings=openings),
        "automatic_constraints": dict(),
        "available_memory": dict(),
        "catalogues": dict(),
        "check_cost": dict(scene=scene),
        "check_setup": dict(scene=scene, command="solve"),
        "climate_reach": dict(scene=scene),
        "constraint_violations": dict(scene=scene, openings=openings),
        "contributions": dict(scene=scene),
        "estimate_cost": dict(scene=scene),
        "evaluate": dict(scene=scene, openings=openings),
        "goal_error": dict(goals=[100.0, 200.0, 300.0], values=[110.0, 190.0, 300.0]),
        "load_scene": dict(path=small_room),
        "openings_array": dict(openings=openings),
        "preetham_radiance": dict(turbidity=3.0, sun_direction=[0.0, 0.6, 0.8], directions=[[0.0, 0.0, 1.0]]),
        "preetham_sun": dict(turbidity=3.0, sun_zenith_deg=30.0),
        "read_openings": dict(path=tmp_path / "openings.json"),
        "scene_from_dict": dict(scene=scene_dict, base_dir=small_room.parent),
        "sensor_grid": dict(vertices=[[0, 0, 0], [4, 0, 0], [4, 4, 0], [0, 4, 0]], triangles=[[0, 1, 2], [0, 2, 3]]),
        "sky": dict(scene=scene),
        "solar_position": dict(utc_seconds=1.7e9, latitude_deg=45.0, longitude_deg=7.0),
        "solve": dict(scene=scene),
        "sun_direction": dict(zenith_deg=30.0, azimuth_deg=180.0),
        "sunrise_sunset": dict(date="2024-06-21", latitude_deg=45.0, longitude_deg=7.0, utc_offset=1.0),
        "utc_seconds": dict(date="2024-06-21", clock="12:00", utc_offset=1.0),
        "write_image": dict(path=tmp_path / "image.exr", image=np.ones((2, 4, 3), np.float32)),
        "write_sky": dict(scene=scene, path=tmp_path / "sky.exr"),
    }


def public_functions():
    return sorted(name for name in fenestra.__all__
                  if callable(getattr(fenestra, name)) and not inspect.isclass(getattr(fenestra, name)))


def test_every_public_function_is_walked(small_room, tmp_path):
    assert set(public_functions()) == set(valid_arguments(small_room, tmp_path))


@pytest.mark.parametrize("name", public_functions())
def test_wrong_types_are_refused_in_fenestras_words(small_room, tmp_path, name):
    function = getattr(fenestra, name)
    valid = valid_arguments(small_room, tmp_path)[name]
    parameters = inspect.signature(function).parameters
    cases = [("(extra)", None)] + [(p, bad) for p in parameters for bad in BAD]
    for parameter, bad in cases:
        if parameter == "(extra)":
            args = dict(valid)
            call = lambda: function(*[args.get(p, parameters[p].default) for p in parameters], "extra")  # noqa: E731
        else:
            args = dict(valid, **{parameter: bad})
            call = lambda: function(**args)  # noqa: E731
        try:
            call()
        except (TypeError, ValueError, MemoryError) as exc:
            message = str(exc)
            for words in LIBRARY_WORDING:
                assert words not in message, (name, parameter, bad, message)
            assert len(message) < 1000, (name, parameter, message)
        except fenestra.Cancelled:
            pass


def test_numpy_values_in_a_scene_dict_are_plain_numbers(small_room):
    scene = json.loads(small_room.read_text())
    scene["materials"]["grey"]["reflectance"] = np.float32(0.6)
    scene["sensors"]["points"] = np.array(scene["sensors"]["points"], np.float32)
    scene["render"]["paths_per_sensor"] = np.int64(64)
    built = fenestra.scene_from_dict(scene, small_room.parent)
    assert built.sensor_count == 3 and built.render.paths_per_sensor == 64
    reference = fenestra.load_scene(small_room)
    assert np.allclose(built.sensor_points, reference.sensor_points, atol=1e-6)


def test_a_scene_dict_value_without_a_json_form_is_named(small_room):
    scene = json.loads(small_room.read_text())
    scene["render"]["seed"] = {1, 2}
    with pytest.raises(ValueError, match=r"render\.seed: a set is not a JSON value"):
        fenestra.scene_from_dict(scene, small_room.parent)
    scene["render"]["seed"] = float("nan")
    with pytest.raises(ValueError, match=r"render\.seed: nan is not a finite"):
        fenestra.scene_from_dict(scene, small_room.parent)


def test_methods_of_the_native_classes_name_wrong_types_in_fenestras_words(small_room, tmp_path):
    """Contributions.save(scene, 5), Progress("x"), ...: the method, what it takes and the types it
    got, never pybind11's listing of overloads."""
    scene = fenestra.load_scene(small_room)
    scene.render.paths_per_sensor = 16
    c = fenestra.contributions(scene)
    calls = {
        "Contributions.save()": lambda bad: c.save(scene, bad),
        "Contributions.evaluate_openings()": lambda bad: c.evaluate_openings(bad, bad),
        "Contributions.annual_openings()": lambda bad: c.annual_openings(bad, None),
        "Contributions.save_annual()": lambda bad: c.save_annual(scene, None, bad),
        "Progress()": lambda bad: fenestra.Progress(bad),
        "Progress.cancel()": lambda bad: fenestra.Progress().cancel(bad),
        "Scene.elements_json()": lambda bad: scene.elements_json(bad),
    }
    for name, call in calls.items():
        for bad in (object(), 5, 1.5j):
            with pytest.raises(TypeError) as refused:
                call(bad)
            message = str(refused.value)
            assert message.startswith(name + " takes ("), message
            for words in LIBRARY_WORDING:
                assert words not in message, (name, message)
            assert len(message) <= 320, message
    c.save(scene, str(tmp_path / "kept"))  # the methods still work
    assert (tmp_path / "kept.npz").exists()
