"""The Python API (import fenestra) over the native core."""

import threading

import numpy as np
import pytest

import fenestra
from conftest import write_stacked_panels

WINDOW = [[1.0, 0, 1.0], [2.0, 0, 1.0], [2.0, 0, 2.0], [1.0, 0, 2.0]]


def test_import_does_not_need_blender():
    import sys

    assert "bpy" not in sys.modules
    assert fenestra.bl_info["blender"] >= (3, 4, 0)


def test_scene_properties(small_room):
    scene = fenestra.load_scene(small_room)
    assert scene.sensor_count == 3
    assert scene.element_count == 6 * 5  # 3 m x 2.5 m wall, 0.5 m elements
    corners = scene.element_corners
    assert corners.shape == (30, 4, 3)
    assert np.allclose(corners[:, :, 1], 0.0)
    grid = scene.element_grid
    assert grid.shape == (30, 3)
    assert set(grid[:, 1]) == set(range(5)) and set(grid[:, 2]) == set(range(6))
    assert "30 elements" in repr(scene)


def test_contributions_and_exact_evaluation_agree_with_ground_truth(small_room):
    scene = fenestra.load_scene(small_room)
    c = fenestra.contributions(scene)
    assert c.E.shape == (3, 30) and c.A.shape == (3, 30) and c.T.shape == (30, 30)
    assert np.all(c.E_stderr >= 0) and np.allclose(c.T, c.T.T)
    assert np.all(c.closed == 0)  # the room is closed: dark without openings
    centres = scene.element_corners.mean(axis=1)
    mask = (centres[:, 0] > 1) & (centres[:, 0] < 2) & (centres[:, 2] > 1) & (centres[:, 2] < 2)
    assert mask.sum() == 4
    exact, exact_err = c.evaluate(mask)
    truth, truth_err = fenestra.evaluate(scene, [WINDOW])
    sigma = np.hypot(exact_err, truth_err)
    assert np.all(np.abs(exact - truth) <= 4 * sigma), (exact, truth, sigma)
    # The linear model (others closed) is an approximation; the exact evaluation is what counts.
    linear = c.closed + c.E[:, mask].sum(axis=1)
    assert np.all(linear > 0)


def test_arrays_are_read_only_views(small_room):
    scene = fenestra.load_scene(small_room)
    scene.render.paths_per_sensor = 64
    c = fenestra.contributions(scene)
    with pytest.raises(ValueError):
        c.E[0, 0] = 1.0
    E = c.E
    del c
    assert np.isfinite(E).all()  # the view keeps its owner alive


def test_save_writes_npz_numpy_can_read(small_room, tmp_path):
    scene = fenestra.load_scene(small_room)
    scene.render.paths_per_sensor = 256
    c = fenestra.contributions(scene)
    npz_path, json_path = c.save(scene, str(tmp_path / "contrib"))
    with np.load(npz_path) as data:
        assert np.array_equal(data["E"], c.E)
        assert data["element_corners"].shape == (30, 4, 3)
        assert np.array_equal(data["all_open"], c.all_open)


def test_bad_scene_raises_value_error_naming_the_file(tmp_path):
    bad = tmp_path / "broken.json"
    bad.write_text("{not json")
    with pytest.raises(ValueError, match="broken.json"):
        fenestra.load_scene(bad)
    with pytest.raises(ValueError, match="cannot open"):
        fenestra.load_scene(tmp_path / "missing.json")


def test_bad_openings_raise(small_room):
    scene = fenestra.load_scene(small_room)
    with pytest.raises(ValueError, match="four"):
        fenestra.evaluate(scene, [[[0, 0, 0], [1, 0, 0]]])
    with pytest.raises(ValueError, match="opening 0"):
        fenestra.evaluate(scene, [[[1, 3, 1], [2, 3, 1], [2, 3, 2], [1, 3, 2]]])  # north wall
    with pytest.raises(ValueError, match="non-finite"):
        fenestra.evaluate(scene, [[[1, 0, np.nan], [2, 0, 1], [2, 0, 2], [1, 0, 2]]])


def test_openings_array_accepts_the_file_format():
    arr = fenestra.openings_array({"openings": [{"corners": WINDOW}]})
    assert arr.shape == (1, 4, 3)
    assert fenestra.openings_array([]).shape == (0, 4, 3)


def test_callback_reports_progress_and_can_cancel(small_room):
    scene = fenestra.load_scene(small_room)
    scene.render.paths_per_sensor = 1 << 18
    seen = []

    def callback(fraction, status):
        seen.append(fraction)
        return len(seen) < 3  # cancel on the third report

    with pytest.raises(fenestra.Cancelled):
        fenestra.contributions(scene, callback=callback)
    assert len(seen) >= 3 and all(0.0 <= f <= 1.0 for f in seen)


def test_gil_is_released_during_computation(small_room):
    scene = fenestra.load_scene(small_room)
    scene.render.paths_per_sensor = 1 << 16
    progress = fenestra.Progress()
    ticks = []
    done = threading.Event()

    def ticker():
        while not done.is_set():
            ticks.append(progress.fraction)
            done.wait(0.01)

    t = threading.Thread(target=ticker)
    t.start()
    try:
        fenestra.contributions(scene, progress=progress)
    finally:
        done.set()
        t.join()
    assert len(ticks) >= 3  # the ticker ran while native code worked


def test_same_seed_same_numbers_across_thread_counts(small_room):
    scene = fenestra.load_scene(small_room)
    scene.render.paths_per_sensor = 500
    scene.render.threads = 1
    a = fenestra.contributions(scene).E.copy()
    scene.render.threads = 2
    b = fenestra.contributions(scene).E.copy()
    assert np.array_equal(a, b)
    scene.render.seed = 99
    assert not np.array_equal(a, fenestra.contributions(scene).E)


def test_goal_error_is_the_solvers_measure():
    goals = np.array([100.0, 200.0, -1.0, np.nan, 50.0])
    values = np.array([110.0, 180.0, 5.0, 7.0, 50.0])
    has = np.array([True, True, False, False, True])
    d, g = values[has] - goals[has], goals[has]
    e = fenestra.goal_error(goals, values)
    assert e["relative_rms"] == pytest.approx(np.sqrt(np.sum(d * d) / np.sum(g * g)), rel=1e-12)
    assert e["max_relative"] == pytest.approx(0.1) and e["worst_sensor"] == 0
    weighted = fenestra.goal_error(goals, values, weights=[1.0, 0.0, 1.0, 1.0, 1.0])
    assert weighted["relative_rms"] == pytest.approx(10.0 / np.sqrt(100.0 ** 2 + 50.0 ** 2), rel=1e-12)
    with pytest.raises(ValueError, match="one entry per sensor"):
        fenestra.goal_error(goals, values[:3])


def test_render_sampler_is_read_set_and_checked(small_room):
    scene = fenestra.load_scene(small_room)
    assert scene.render.sampler == "sobol"  # the default
    scene.render.sampler = "independent"
    assert scene.render.sampler == "independent" and "independent" in repr(scene.render)
    with pytest.raises(ValueError, match="render.sampler.*'sobol' or 'independent'.*'halton'"):
        scene.render.sampler = "halton"
    assert scene.render.sampler == "independent"  # a refused value changes nothing


def test_both_samplers_estimate_the_same_light(small_room):
    # Two unbiased estimators: every sensor's all-open value agrees within a t bound (15 degrees of
    # freedom per standard error, 30 combined at most: scipy's quantile for a normal 4 sigma).
    from scipy import stats

    bound = stats.t.isf(stats.norm.sf(4.0), 15)
    values = {}
    for sampler in ("sobol", "independent"):
        scene = fenestra.load_scene(small_room)
        scene.render.paths_per_sensor = 2048
        scene.render.sampler = sampler
        c = fenestra.contributions(scene)
        values[sampler] = (c.all_open, c.all_open_stderr)
    (a, sa), (b, sb) = values["sobol"], values["independent"]
    assert np.all(a > 0)
    assert np.all(np.abs(a - b) <= bound * np.hypot(sa, sb)), (a, b, sa, sb)


def test_contributions_count_what_the_tracer_dropped(small_room, tmp_path):
    scene = fenestra.load_scene(small_room)
    scene.render.paths_per_sensor = 256
    assert fenestra.contributions(scene).dropped == {"non_finite": 0, "truncated_conditions": 0}
    folder = tmp_path / "stacked"
    folder.mkdir()
    stacked = fenestra.contributions(fenestra.load_scene(write_stacked_panels(folder)))
    assert stacked.dropped["truncated_conditions"] > 0 and stacked.dropped["non_finite"] == 0
    # The same totals for any thread count (counted per task of paths).
    one = fenestra.load_scene(write_stacked_panels(folder))
    one.render.threads = 1
    assert fenestra.contributions(one).dropped == stacked.dropped
