"""The add-on's study folder and study fingerprints, without Blender (their modules import no bpy):
a solve's staging folder replaces the study folder only on commit, carries the files it does not
write over, and leaves the previous study whole when discarded; fingerprints tell apart what a
result and what the contributions depend on."""

import importlib.util
import os

import pytest

from conftest import ROOT

BLENDER_MODULES = os.path.join(ROOT, "addon", "fenestra", "blender")


def load(name):
    """A module of the add-on that imports no bpy, loaded without the package (which does)."""
    spec = importlib.util.spec_from_file_location("fenestra_blender_" + name.replace("/", "_"),
                                                  os.path.join(BLENDER_MODULES, name + ".py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


study_folder = load("com/study_folder")
study_fingerprint = load("com/study_fingerprint")


def write(folder, files):
    os.makedirs(folder, exist_ok=True)
    for name, text in files.items():
        with open(os.path.join(folder, name), "w") as f:
            f.write(text)


def read(folder):
    return {name: open(os.path.join(folder, name)).read() for name in sorted(os.listdir(folder))
            if os.path.isfile(os.path.join(folder, name))}


def siblings(folder):
    return sorted(n for n in os.listdir(os.path.dirname(folder)) if n != os.path.basename(folder))


PREVIOUS = {"scene.json": "old scene", "scene.obj": "old obj", "result.json": "old result"}
NEW = {"scene.json": "new scene", "scene.obj": "new obj", "result.json": "new result"}


def test_commit_replaces_the_study_and_carries_the_other_files_over(tmp_path):
    study = str(tmp_path / "model_fenestra")
    write(study, dict(PREVIOUS, **{"sky.exr": "previewed sky", "check.json": "the user's"}))
    os.makedirs(os.path.join(study, "notes"))
    staging = study_folder.StagingFolder(study)
    assert os.path.dirname(staging.path) == str(tmp_path) and os.path.basename(staging.path).startswith(".")
    write(staging.path, NEW)
    assert read(study)["scene.json"] == "old scene"  # nothing changes before the commit
    assert staging.commit() is None
    assert read(study) == dict(NEW, **{"sky.exr": "previewed sky", "check.json": "the user's"})
    assert os.path.isdir(os.path.join(study, "notes"))
    assert siblings(study) == []  # no staging or previous folder left


def test_discard_leaves_the_previous_study_whole(tmp_path):
    study = str(tmp_path / "study")
    write(study, PREVIOUS)
    staging = study_folder.StagingFolder(study)
    write(staging.path, {"scene.json": "half written"})
    staging.discard()
    assert read(study) == PREVIOUS
    assert siblings(study) == []


def test_first_study(tmp_path):
    study = str(tmp_path / "deep" / "study")
    staging = study_folder.StagingFolder(study)
    write(staging.path, NEW)
    assert staging.commit() is None
    assert read(study) == NEW


def test_through_a_link_the_folder_it_points_to_is_replaced(tmp_path):
    real = str(tmp_path / "real")
    write(real, PREVIOUS)
    link = str(tmp_path / "link")
    os.symlink(real, link)
    staging = study_folder.StagingFolder(link)
    write(staging.path, NEW)
    staging.commit()
    assert os.path.islink(link) and read(real) == NEW


def test_a_file_in_the_way_is_refused_before_any_work(tmp_path):
    path = tmp_path / "study"
    path.write_text("a file")
    with pytest.raises(OSError, match="is a file"):
        study_folder.StagingFolder(str(path))
    assert path.read_text() == "a file"


def test_without_an_atomic_exchange_two_renames_do(tmp_path, monkeypatch):
    monkeypatch.setattr(study_folder, "_renameat2", None)
    study = str(tmp_path / "study")
    write(study, dict(PREVIOUS, **{"sky.exr": "sky"}))
    staging = study_folder.StagingFolder(study)
    write(staging.path, NEW)
    assert staging.commit() is None
    assert read(study) == dict(NEW, **{"sky.exr": "sky"})
    assert siblings(study) == []


class Study:
    def __init__(self, scene, obj_text="v 0 0 0\n"):
        self.scene, self.obj_text = scene, obj_text


def scene(**changes):
    s = {"fenestra": 1, "geometry": "scene.obj", "materials": {"wall": {"type": "diffuse"}},
         "opening_domain": {"groups": ["Room.domain"], "element_size": 0.25},
         "sensors": {"points": [[1, 1, 0.8]], "normals": [[0, 0, 1]], "goals": [0.4], "goal_units": "normalized"},
         "sky": {"type": "uniform", "radiance": 100}, "render": {"paths_per_sensor": 2048, "seed": 1},
         "solver": {"paths": 2048, "generations": 150, "population": 32, "seed": 1}}
    for path, value in changes.items():
        owner = s
        keys = path.split(".")
        for key in keys[:-1]:
            owner = owner[key]
        owner[keys[-1]] = value
    return s


@pytest.mark.parametrize("change", [
    {"sensors.goals": [0.6]}, {"sensors.goal_units": "lux"}, {"goals": {"units": "lux", "uniform": []}},
    {"solver.generations": 500}, {"solver.population": 64}, {"solver.seed": 7},
    {"solver.constraints": {"max_openings": 1}}, {"solver.verify_paths": 512},
])
def test_goals_and_solver_settings_keep_the_contributions(change):
    before, after = Study(scene()), Study(scene(**change))
    assert study_fingerprint.fingerprint(before) != study_fingerprint.fingerprint(after)
    assert study_fingerprint.contributions_fingerprint(before) == study_fingerprint.contributions_fingerprint(after)


@pytest.mark.parametrize("change", [
    {"opening_domain.element_size": 0.3}, {"sensors.points": [[1, 1, 0.9]]}, {"sky.radiance": 200},
    {"render.seed": 2}, {"render.paths_per_sensor": 4096}, {"solver.paths": 4096},
    {"materials": {"wall": {"type": "diffuse", "reflectance": 0.2}}}, {"solver.element_size": 0.3},
    {"solver.a_future_setting": 1},
])
def test_what_the_contributions_depend_on(change):
    before, after = Study(scene()), Study(scene(**change))
    assert study_fingerprint.contributions_fingerprint(before) != study_fingerprint.contributions_fingerprint(after)


def test_the_geometry_counts():
    assert (study_fingerprint.contributions_fingerprint(Study(scene(), "v 0 0 0\n"))
            != study_fingerprint.contributions_fingerprint(Study(scene(), "v 0 0 1\n")))


def test_an_annual_folder_replaces_its_own_files(tmp_path):
    """Annual Daylight stages `annual/` with its own list of files: the previous run's outputs are
    replaced, not carried over onto the new ones; the user's files are."""
    files = ("scene.json", "scene.obj", "openings.json", "annual.json", "annual.npz")
    annual = str(tmp_path / "study" / "annual")
    write(annual, dict({name: "old " + name for name in files}, **{"notes.txt": "the user's"}))
    staging = study_folder.StagingFolder(annual, files)
    write(staging.path, {name: "new " + name for name in files})
    assert staging.commit() is None
    assert read(annual) == dict({name: "new " + name for name in files}, **{"notes.txt": "the user's"})


def test_a_weather_file_replaced_under_its_name_counts(tmp_path):
    """A climate study names its weather file by path: the file's size and time of change count too."""
    weather = tmp_path / "site.epw"
    weather.write_text("LOCATION,one\n")
    climate = scene(sky={"type": "climate", "weather": str(weather)})
    before = study_fingerprint.contributions_fingerprint(Study(climate))
    assert study_fingerprint.contributions_fingerprint(Study(climate)) == before
    weather.write_text("LOCATION,another place\n")
    assert study_fingerprint.contributions_fingerprint(Study(climate)) != before
