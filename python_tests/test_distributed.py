"""Studies sharded by sensors over a Dask cluster (fenestra.distributed, docs/distributed.md): a
local cluster of 2 worker processes over TCP on localhost. Results must equal a single process's
bit for bit; a killed worker's shard is recomputed; a worker holds only its shards' records; a
cluster that cannot run Fenestra is named within seconds."""

import json
import os
import re
import signal
import subprocess
import sys
import threading
import time
import warnings

import numpy as np
import pytest

from conftest import CLI, ROOT, box_obj

distributed_module = pytest.importorskip("distributed")
import fenestra  # noqa: E402
from fenestra import distributed  # noqa: E402

# How long a Ctrl-C test waits for the CLI to reach the phase it interrupts: a guard against a hang,
# not a measure of speed (a local cluster's start and the tracing before it take longer on a loaded
# machine; 120 s ran out beside two other solves).
STARTUP_GUARD_S = 600


def write_floor(tmp_path, sensors=24, paths=512, element_size=0.5):
    """Two rooms side by side, 8 x 4 x 2.6 m, their south walls the opening domain (32 elements);
    sensors on a line through both."""
    (tmp_path / "floor.obj").write_text(
        box_obj((0, 0, 0), (8, 4, 2.6), lambda f: "facade" if f == "south" else "grey"))
    scene = {
        "fenestra": 1, "geometry": "floor.obj",
        "materials": {"grey": {"reflectance": 0.5}, "facade": {"reflectance": 0.5}},
        "opening_domain": {"materials": ["facade"], "element_size": element_size},
        "sensors": {"points": [[0.3 + i * 7.4 / (sensors - 1), 0.5 + 3.0 * (i % 3) / 2, 0.8] for i in range(sensors)]},
        "sky": {"type": "preetham", "turbidity": 3, "latitude": 45, "longitude": 0, "date": "2024-06-21",
                "time": "12:00", "timezone": "UTC"},
        "render": {"paths_per_sensor": paths, "seed": 7},
    }
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))
    return path


@pytest.fixture(scope="module")
def cluster():
    with distributed.Cluster(workers=2, threads_per_worker=1, timeout=30) as c:
        assert all(a.startswith("tcp://127.0.0.1:") for a in c.workers())
        yield c


def assert_same(a, b, names=("E", "E_stderr", "A", "T", "closed", "closed_stderr", "all_open", "all_open_stderr")):
    for name in names:
        x, y = np.asarray(getattr(a, name)), np.asarray(getattr(b, name))
        assert x.shape == y.shape, name
        assert np.array_equal(x, y), "%s differs: max |diff| %g" % (name, np.max(np.abs(x - y)))


def test_contributions_equal_one_process_bit_for_bit(tmp_path, cluster):
    path = write_floor(tmp_path)
    one = fenestra.contributions(fenestra.load_scene(str(path)))
    with distributed.contributions(str(path), cluster, shards=5) as many:  # uneven blocks: 24 = 5+5+5+4+5
        assert [e - b for b, e, _ in many.shards] == [5, 5, 4, 5, 5]
        assert_same(many, one)
        assert many.T.any() and many.E.any()
        rng = np.random.default_rng(4)
        masks = rng.random((6, one.E.shape[1])) < 0.4
        values, errors = many.evaluate_batch(masks)
        for m, v, e in zip(masks, values, errors):
            expected = one.evaluate(m)
            assert np.array_equal(v, expected[0]) and np.array_equal(e, expected[1])
        v, e = many.evaluate(masks[0])
        assert np.array_equal(v, values[0])
        window = [[[2.0, 0.0, 0.9], [3.5, 0.0, 0.9], [3.5, 0.0, 2.1], [2.0, 0.0, 2.1]]]
        assert np.array_equal(many.evaluate_openings(window)[0],
                              one.evaluate_openings(fenestra.load_scene(str(path)), window)[0])
        # The arrays saved as one process saves them.
        many.save(str(tmp_path / "many"))
        one.save(fenestra.load_scene(str(path)), str(tmp_path / "one"))
        a, b = np.load(tmp_path / "many.npz"), np.load(tmp_path / "one.npz")
        assert sorted(a.files) == sorted(b.files)
        for name in a.files:
            assert np.array_equal(a[name], b[name]), name


def test_the_shard_count_does_not_change_the_answer(tmp_path, cluster):
    path = write_floor(tmp_path, sensors=7, paths=256)
    with distributed.contributions(str(path), cluster, shards=1) as one_shard, \
            distributed.contributions(str(path), cluster, shards=7) as seven:
        assert_same(one_shard, seven)


def test_evaluate_with_real_cutters_equals_one_process(tmp_path, cluster):
    path = write_floor(tmp_path, paths=256)
    scene = fenestra.load_scene(str(path))
    window = [[[1.0, 0.0, 0.9], [2.5, 0.0, 0.9], [2.5, 0.0, 2.1], [1.0, 0.0, 2.1]]]
    single = fenestra.evaluate(scene, window)
    sharded = distributed.evaluate(str(path), window, cluster, shards=3)
    assert np.array_equal(single[0], sharded[0]) and np.array_equal(single[1], sharded[1])


def worker_pids(cluster):
    return cluster.client.run(os.getpid)


def test_a_worker_killed_mid_run_is_recomputed_and_the_result_is_unchanged(tmp_path, cluster):
    path = write_floor(tmp_path, sensors=16, paths=8192)
    one = fenestra.contributions(fenestra.load_scene(str(path)))
    result = {}
    run = threading.Thread(target=lambda: result.setdefault("c", distributed.contributions(str(path), cluster, shards=4)))
    run.start()
    deadline = time.monotonic() + 60
    while not any(cluster.client.processing().values()):  # the shards are being traced
        assert time.monotonic() < deadline
        time.sleep(0.05)
    victim, pid = sorted(worker_pids(cluster).items())[0]
    os.kill(pid, signal.SIGKILL)
    run.join(timeout=300)
    assert "c" in result
    assert victim not in cluster.workers()  # it died (its nanny starts a new one, at a new address)
    with result["c"] as many:
        assert_same(many, one)
        # Evaluations after a loss: kill the worker holding shard 0; it is recomputed elsewhere.
        cluster.client.wait_for_workers(2, timeout=60)
        holder = many.shards[0][2]
        os.kill(worker_pids(cluster)[holder], signal.SIGKILL)
        mask = np.ones(one.E.shape[1], dtype=bool)
        v, e = many.evaluate(mask)
        assert many.recomputed_shards >= 1
        assert np.array_equal(v, one.evaluate(mask)[0]) and np.array_equal(e, one.evaluate(mask)[1])
    cluster.client.wait_for_workers(2, timeout=60)


def test_a_worker_holds_only_its_shards_records(tmp_path, cluster):
    path = write_floor(tmp_path, sensors=20, paths=2048)
    one = fenestra.contributions(fenestra.load_scene(str(path)))
    records = one.memory_bytes - 8 * (3 * one.E.size + one.T.size)
    with distributed.contributions(str(path), cluster, shards=2) as many:
        held = distributed.worker_memory(cluster)
        by_worker = {}
        for (b, e, worker), size in zip(many.shards, many.shard_memory_bytes):
            by_worker[worker] = by_worker.get(worker, 0) + size
        assert held == {w: by_worker.get(w, 0) for w in held}
        # Each shard holds its sensors' records, about half of one process's, and nothing else
        # (its rows of E, E_stderr and A went to the client, and T is the client's).
        for size in many.shard_memory_bytes:
            assert 0.3 * records < size < 0.7 * records
        assert sum(many.shard_memory_bytes) <= records
    assert sum(distributed.worker_memory(cluster).values()) == 0  # closed: the records are freed


def test_an_unreachable_scheduler_is_named_within_seconds():
    start = time.monotonic()
    with pytest.raises(distributed.ClusterError, match="cannot reach the Dask scheduler at tcp://127.0.0.1:9"):
        distributed.Cluster(scheduler="tcp://127.0.0.1:9", timeout=3)
    assert time.monotonic() - start < 15


def test_a_version_mismatch_is_named(cluster, monkeypatch):
    monkeypatch.setattr(distributed.identity, "PROTOCOL", distributed.PROTOCOL + 1)
    with pytest.raises(distributed.ClusterError, match="runs Fenestra .* this client Fenestra .* same Fenestra build"):
        distributed.Cluster._check_workers(cluster, timeout=5)


def test_a_worker_without_fenestra_is_named(tmp_path):
    """A scheduler and a worker started by hand, the worker's Python unable to import Fenestra."""
    env = dict(os.environ, PYTHONPATH="")
    port = 18700 + os.getpid() % 500
    scheduler = subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1",
                                  "--port", str(port), "--no-dashboard"], env=env, cwd=tmp_path,
                                 stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    worker = subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_worker", "tcp://127.0.0.1:%d" % port,
                               "--nthreads", "1", "--no-dashboard", "--no-nanny"], env=env, cwd=tmp_path,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        start = time.monotonic()
        with pytest.raises(distributed.ClusterError, match="cannot run Fenestra.*PYTHONPATH"):
            distributed.Cluster(scheduler="tcp://127.0.0.1:%d" % port, timeout=30)
        assert time.monotonic() - start < 40
    finally:
        for p in (worker, scheduler):
            p.terminate()
            p.wait(timeout=30)


def test_bad_arguments_are_named(tmp_path, cluster):
    path = write_floor(tmp_path, sensors=4, paths=64)
    with pytest.raises(ValueError, match="shards must be a positive integer"):
        distributed.contributions(str(path), cluster, shards=0)
    with pytest.raises(TypeError, match="scene must be a scene file's path"):
        distributed.contributions(3.5, cluster)
    with pytest.raises(ValueError, match="was not read from a file"):
        distributed.contributions(fenestra.scene_from_dict(json.loads(path.read_text()), tmp_path), cluster)
    with pytest.raises(ValueError, match="give either scheduler"):
        distributed.Cluster(scheduler="tcp://127.0.0.1:9", workers=2)
    with distributed.contributions(str(path), cluster) as c:
        with pytest.raises(ValueError, match="masks must have shape"):
            c.evaluate_batch(np.ones((2, 3)))


# ---- the command line ----------------------------------------------------------------------------


def cli(*args, timeout=300):
    return subprocess.run([CLI] + [str(a) for a in args], capture_output=True, text=True, timeout=timeout)


def test_cli_contributions_and_evaluate_on_a_local_cluster_equal_one_process(tmp_path):
    path = write_floor(tmp_path, sensors=6, paths=256)
    r = cli("contributions", path, "-o", tmp_path / "many.npz", "--workers", 2, "--threads", 1, "--quiet")
    assert r.returncode == 0, r.stderr
    assert "2 shards" in r.stdout and "wrote" in r.stdout
    r = cli("contributions", path, "-o", tmp_path / "one.npz", "--quiet")
    assert r.returncode == 0, r.stderr
    a, b = np.load(tmp_path / "many.npz"), np.load(tmp_path / "one.npz")
    for name in b.files:
        assert np.array_equal(a[name], b[name]), name
    openings = tmp_path / "openings.json"
    openings.write_text(json.dumps({"openings": [{"corners": [[1, 0, 0.9], [2.5, 0, 0.9], [2.5, 0, 2.1], [1, 0, 2.1]]}]}))
    for out, extra in (("many.json", ["--workers", 2, "--shards", 3]), ("one.json", [])):
        r = cli("evaluate", path, "--openings", openings, "-o", tmp_path / out, "--quiet", *extra)
        assert r.returncode == 0, r.stderr
    many, one = json.loads((tmp_path / "many.json").read_text()), json.loads((tmp_path / "one.json").read_text())
    assert many["sensors"] == one["sensors"] if "sensors" in one else many == one


def test_cli_unreachable_scheduler_fails_fast_and_writes_nothing(tmp_path):
    path = write_floor(tmp_path, sensors=4, paths=64)
    start = time.monotonic()
    r = cli("contributions", path, "-o", tmp_path / "out.npz", "--scheduler", "tcp://127.0.0.1:9", timeout=60)
    assert r.returncode == 1
    assert "cannot reach the Dask scheduler at tcp://127.0.0.1:9" in r.stderr
    assert time.monotonic() - start < 30
    assert not (tmp_path / "out.npz").exists() and not (tmp_path / "out.json").exists()


def test_cli_usage_errors(tmp_path):
    path = write_floor(tmp_path, sensors=4, paths=64)
    for args, message in ((["--workers", 0], "--workers expects an integer from 1 to 1024"),
                          (["--workers", 2, "--scheduler", "tcp://127.0.0.1:9"], "give --workers N"),
                          (["--shards", 2], "give --workers N"),
                          (["--scheduler", "tcp://127.0.0.1:9", "--max-memory", "1G"], "--max-memory sets a local"),
                          (["--workers", 2, "--shards", "-1"], "--shards expects an integer from 1")):
        r = cli("contributions", path, "-o", tmp_path / "out.npz", *args)
        assert r.returncode == 2 and message in r.stderr, r.stderr
    for args, message in ((["annual", path, "-o", tmp_path / "out", "--workers", 2], "annual needs --openings"),
                          (["sky", path, "-o", tmp_path / "sky.exr", "--workers", 2, "--shards", 2],
                           "--shards does not apply to sky"),
                          (["sky", path, "-o", tmp_path / "sky.exr", "--workers", 2, "--paths", 8],
                           "--paths does not apply to sky"),
                          (["evaluate", path, "-o", tmp_path / "o.json", "--openings", path, "--workers", 2, "--cutters"],
                           "--cutters belongs to the annual command"),
                          (["annual", path, "-o", tmp_path / "o", "--openings", path, "--workers", 2, "--json", "s.json"],
                           "--json belongs to the sky command")):
        r = cli(*args)
        assert r.returncode == 2 and message in r.stderr, r.stderr
        assert not any(tmp_path.glob("o*")) and not (tmp_path / "sky.exr").exists()
    for args, message in ((["--workers", "two"], "--workers expects an integer"),):
        r = cli("contributions", path, "-o", tmp_path / "out.npz", *args)
        assert r.returncode == 2 and message in r.stderr, r.stderr


def test_cli_ctrl_c_cancels_the_cluster_and_writes_nothing(tmp_path):
    path = write_floor(tmp_path, sensors=8, paths=1 << 16)
    p = subprocess.Popen([CLI, "contributions", str(path), "-o", str(tmp_path / "out.npz"), "--workers", "2"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + STARTUP_GUARD_S
    line = ""
    while "tracing contribution paths" not in line and "cluster:" not in line:  # the cluster is up
        line = p.stderr.readline()
        assert line or p.poll() is None, "exited early"
        assert time.monotonic() < deadline
    time.sleep(2.0)
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=120)
    assert p.returncode == 130, err
    assert "interrupted by SIGINT; no output written" in err
    assert not (tmp_path / "out.npz").exists() and not (tmp_path / "out.json").exists()


def test_progress_is_aggregated_and_a_cancel_stops_the_workers(tmp_path, cluster):
    path = write_floor(tmp_path, sensors=8, paths=1 << 17)  # a minute or more of tracing
    seen = []

    def callback(fraction, status):
        seen.append((fraction, status))
        return not any(0.0 < f < 1.0 for f, _ in seen[:-1])  # cancel once a report showed work under way

    start = time.monotonic()
    with pytest.raises(fenestra.Cancelled):
        distributed.contributions(str(path), cluster, shards=4, callback=callback)
    assert time.monotonic() - start < 60
    assert any(0.0 < f < 1.0 for f, _ in seen), seen
    assert all(status == "tracing contribution paths" for _, status in seen)
    # The native work stops on the workers (cancelling a Dask task alone would leave it running).
    deadline = time.monotonic() + 15
    while any(cluster.client.run(lambda: len(distributed.worker._RUNNING)).values()):
        assert time.monotonic() < deadline, "shards still running on the workers"
        time.sleep(0.1)


def test_a_shard_too_large_for_its_worker_is_refused_before_any_work(tmp_path):
    path = write_floor(tmp_path, sensors=24, paths=1 << 16)
    estimate = fenestra.estimate_cost(fenestra.load_scene(str(path)), "contributions")
    blocks = distributed.client._blocks(24, 2)
    need = distributed.check_shards_fit(estimate, blocks, {"tcp://a:1": 0})  # no limit: fits, says how much
    assert need > estimate["memory"]["path_records"] / 2
    with pytest.raises(distributed.ClusterError, match=r"a shard of 12 sensors needs about .* MiB .* worker tcp://b:2's "
                                                       r"memory limit of .* use at least \d+ workers of this memory, one "
                                                       r"shard each"):
        distributed.check_shards_fit(estimate, blocks, {"tcp://a:1": 10 * need, "tcp://b:2": need / 3})
    # The suggested shard count fits.
    message = str(pytest.raises(distributed.ClusterError, distributed.check_shards_fit, estimate, blocks,
                                {"tcp://b:2": need / 3}).value)
    shards = int(message.split("use at least ")[1].split()[0])  # workers, a shard each
    distributed.check_shards_fit(estimate, distributed.client._blocks(24, shards), {"tcp://b:2": need / 3})


def test_a_climate_solves_shard_counts_its_part_of_the_hourly_model_before_any_work(tmp_path):
    """A solve with climate goals: each shard's worker also holds its goal sensors' part of the hourly
    model and of the search's years, so a worker limit that holds the records but not that is
    refused before any work, naming the shards that fit; the client holds none of it."""
    from test_climate_goals import SDA_ASE, climate_room

    path, _ = climate_room(tmp_path, SDA_ASE, paths=64)
    scene = fenestra.load_scene(str(path))
    estimate = fenestra.estimate_cost(scene, "contributions")
    climate = distributed.climate_share(scene)
    assert list(climate.sensors) == list(range(6)) and np.all(climate.model > 0) and np.all(climate.years > 0)
    solve = fenestra.estimate_cost(scene, "solve")["memory"]
    assert climate.model.sum() == pytest.approx(solve["climate_model"])
    assert climate.years.sum() == pytest.approx(solve["climate_population"])
    blocks = distributed.client._blocks(6, 2)
    records = distributed.check_shards_fit(estimate, blocks, {})
    need = distributed.check_shards_fit(estimate, blocks, {}, climate)
    assert need == pytest.approx(records + climate.bytes[:3].sum())
    with pytest.raises(distributed.ClusterError, match=r"a shard of 3 sensors \(3 of them climate goal sensors\) "
                                                       r"needs about .*hourly model.* use at least \d+ workers of this "
                                                       r"memory, one shard each"):
        distributed.check_shards_fit(estimate, blocks, {"tcp://a:1": (records + need) / 2}, climate)
    memory = distributed.solve_memory(scene, 2)
    assert memory["worker"] == pytest.approx(need)
    solve = fenestra.estimate_cost(scene, "solve")["memory"]
    # The client holds none of the climate goals' model or years: its parts are the contributions',
    # the solver's state and the process.
    parts = distributed.client._client_parts(scene, fenestra.estimate_cost(scene, "solve"))
    assert not {"climate_model", "climate_population"} & set(parts)
    assert memory["client"] == pytest.approx(sum(parts.values()))


def test_the_climate_share_knows_a_floors_rooms_apart_and_names_the_element_size_that_fits(tmp_path):
    """Closed rooms: each goal sensor's rows hold its own room's facade, not the floor's, so a floor
    is counted by what its rooms see, not sensors x elements. A refusal names the element size at
    which the shard would fit, and at that size it does."""
    sys.path.insert(0, os.path.join(ROOT, "scripts"))
    from office_floor import write_office_floor

    path = write_office_floor(str(tmp_path), element_size=0.5, spacing=1.5, paths=64, rooms_long=2, rooms_short=1,
                              width=18.0, depth=18.0)
    scene = fenestra.load_scene(path)
    climate = distributed.climate_share(scene)
    reach = fenestra.climate_reach(scene)
    assert len(climate.sensors) == scene.sensor_count and np.all(reach > 0)
    # A sensor sees its room's facade (one or two walls of the floor's eight), less than half the domain.
    assert reach.max() < 0.5 * scene.element_count, (reach.max(), scene.element_count)
    estimate = fenestra.estimate_cost(scene, "contributions")
    blocks = distributed.client._blocks(scene.sensor_count, 2)
    need = distributed.check_shards_fit(estimate, blocks, {}, climate)
    message = str(pytest.raises(distributed.ClusterError, distributed.check_shards_fit, estimate, blocks,
                                {"tcp://a:1": 0.6 * need}, climate).value)
    size = float(message.split("a larger element_size (")[1].split(" m")[0])
    assert size > scene.element_size
    with open(path) as f:
        spec = json.load(f)
    spec["opening_domain"]["element_size"] = size
    with open(path, "w") as f:
        json.dump(spec, f)
    larger = fenestra.load_scene(path)
    distributed.check_shards_fit(fenestra.estimate_cost(larger, "contributions"), blocks, {"tcp://a:1": 0.6 * need},
                                 distributed.climate_share(larger))


def test_a_climate_model_the_records_count_too_large_is_refused_before_it_is_built(tmp_path, monkeypatch):
    """The estimate before tracing can be short (light through a door meets another room's facade);
    the shards then count their parts of the model from their records, and a worker that would not
    hold its part is refused before any is built, naming the workers and the element size that fit."""
    weather = os.path.join(ROOT, "examples", "weather", "USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw")
    (tmp_path / "room.obj").write_text(box_obj((0, 0, 0), (6, 5, 3), lambda f: "facade" if f == "south" else "grey"))
    scene = {
        "fenestra": 1, "geometry": "room.obj",
        "materials": {"grey": {"reflectance": 0.5}, "facade": {"reflectance": 0.5}},
        "opening_domain": {"materials": ["facade"], "element_size": 0.125},
        "sensors": {"points": [[0.3 + 0.6 * (i % 10), 0.3 + 0.15 * (i // 10), 0.8] for i in range(300)]},
        "sky": {"type": "climate", "weather": weather},
        "goals": {"climate": [{"metric": "sda", "min_area_fraction": 0.5}]},
        "render": {"paths_per_sensor": 256, "seed": 2},
        "solver": {"population": 8, "generations": 2, "tradeoffs": False},
    }
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))
    local = fenestra.load_scene(str(path))
    real = distributed.client.climate_share
    # The estimate before tracing misses the model (as it may where doors join rooms).
    monkeypatch.setattr(distributed.client, "climate_share",
                        lambda s: None if real(s) is None else real(s)._replace(model=np.zeros(len(real(s).sensors))))
    years = real(local).years.sum()
    model = fenestra.estimate_cost(local, "solve")["memory"]["climate_model"]
    limit = 1 << 30  # ample for what a worker holds before the model (Dask's memory manager stops it at 95 %)
    assert model / 2 > limit > years  # each worker's half of the model alone would not fit
    with distributed.Cluster(workers=2, threads_per_worker=1, memory_limit=limit, timeout=30) as cluster:
        error = pytest.raises(distributed.ClusterError, distributed.solve, str(path), cluster).value
        assert len(cluster.workers()) == 2  # nobody died building it
    message = str(error)
    assert "the climate goals' hourly model: worker tcp://" in message, message
    assert "counted from their path records" in message, message
    workers = int(re.search(r"use at least (\d+) workers of this memory", message).group(1))
    held = float(re.search(r"would hold about ([\d.]+) GiB", message).group(1))
    assert held > 1 and workers >= 3 and workers >= 2 * held, message
    assert "or a larger element_size (" in message


def test_cli_refuses_shards_larger_than_a_workers_memory(tmp_path):
    path = write_floor(tmp_path, sensors=24, paths=1 << 18)
    r = cli("contributions", path, "-o", tmp_path / "out.npz", "--workers", 2, "--max-memory", "600M", "--quiet",
            timeout=120)
    assert r.returncode == 1, r.stderr
    assert "a shard of 12 sensors needs about" in r.stderr and "memory limit of 572 MiB" in r.stderr, r.stderr
    assert "use at least" in r.stderr
    assert not (tmp_path / "out.npz").exists()


def test_fuzzed_scheduler_addresses_are_refused_or_tried_never_crash():
    """Seeded mutations of an address: each is either refused at once (ValueError naming it) or a
    well-formed tcp:// address; Dask itself never sees a malformed one."""
    rng = np.random.default_rng(19)
    base = "tcp://127.0.0.1:8786"
    alphabet = "tcp:/[]1.9:x -\x00é"
    for _ in range(300):
        text = list(base)
        for _ in range(rng.integers(1, 4)):
            i = int(rng.integers(0, len(text) + 1))
            op = rng.integers(0, 3)
            if op == 0 and text:
                del text[min(i, len(text) - 1)]
            elif op == 1:
                text.insert(i, alphabet[rng.integers(0, len(alphabet))])
            elif text:
                text[min(i, len(text) - 1)] = alphabet[rng.integers(0, len(alphabet))]
        address = "".join(text)
        try:
            distributed.cluster._check_address(address)
        except ValueError as exc:
            assert repr(address)[:60] in str(exc)
            continue
        scheme, rest = address.split("://", 1)
        assert scheme == "tcp" and 1 <= int(rest.rsplit(":", 1)[1]) <= 65535, address
    for bad in (None, 8786, b"tcp://127.0.0.1:8786"):
        with pytest.raises(ValueError):
            distributed.cluster._check_address(bad)


def no_connecting(monkeypatch):
    """Dask's client and local cluster replaced by ones that fail the test: what is refused must be
    refused before any connection."""
    def connect(*args, **kwargs):
        raise AssertionError("connected to a cluster for options that should be refused")

    monkeypatch.setattr(distributed_module, "Client", connect)
    monkeypatch.setattr(distributed_module, "LocalCluster", connect)


def test_unsupported_addresses_and_options_are_refused_before_connecting(monkeypatch, tmp_path):
    """tls:// and ucx:// addresses, an over-long host name and a bad timeout gave Dask's internal
    errors (after 20 s for tls and ucx): refused at once, in words that say what is accepted."""
    no_connecting(monkeypatch)
    for address in ("tls://127.0.0.1:8786", "ucx://127.0.0.1:8786", "ws://127.0.0.1:8786", "inproc://127.0.0.1/1/2"):
        with pytest.raises(ValueError, match=r"scheme %s:// is not supported: Fenestra's clusters connect over tcp:// "
                                             r"only" % address.split(":")[0]):
            distributed.Cluster(scheduler=address)
    for host in ("a" * 254, "a" * 64 + ".example.org", "a..b", "-a.b", "a_b.c-"):
        with pytest.raises(ValueError, match=r"is not a host name or IPv4 address: at most 253 characters"):
            distributed.Cluster(scheduler="tcp://%s:8786" % host)
    with pytest.raises(ValueError, match=r"is not an IPv6 address"):
        distributed.Cluster(scheduler="tcp://[1::2::3]:8786")
    for timeout in (-1, 0, float("nan"), float("inf"), 1e300, "10", True, None, [10]):
        with pytest.raises(ValueError, match=r"timeout must be a finite number of seconds above 0 and at most 86400"):
            distributed.Cluster(scheduler="tcp://127.0.0.1:8786", timeout=timeout)
        with pytest.raises(ValueError, match=r"timeout must be a finite number"):
            distributed.Cluster(workers=1, timeout=timeout)
    for threads in (0, -1, 4097, 1.5, True, "2"):
        with pytest.raises(ValueError, match=r"threads_per_worker must be None \(the cores shared out\) or an integer"):
            distributed.Cluster(workers=1, threads_per_worker=threads)
    for limit in (-1, "lots", "-4GB", "nan GB", 2.5, True, [1]):
        with pytest.raises(ValueError, match=r"memory_limit must be \"auto\""):
            distributed.Cluster(workers=1, memory_limit=limit)
    for options in ({"threads_per_worker": 2}, {"memory_limit": "4GB"}):
        with pytest.raises(ValueError, match="set a local cluster's workers; a running cluster's are set where"):
            distributed.Cluster(scheduler="tcp://127.0.0.1:8786", **options)
    # The command line says the same, with exit status 1 and nothing written.
    path = write_floor(tmp_path, sensors=4, paths=64)
    r = cli("contributions", path, "-o", tmp_path / "out.npz", "--scheduler", "tls://127.0.0.1:8786", timeout=60)
    assert r.returncode == 1 and "scheme tls:// is not supported" in r.stderr, r.stderr
    assert not (tmp_path / "out.npz").exists()


def test_a_local_cluster_has_the_workers_asked_for_and_refuses_use_after_close(tmp_path):
    """Contributions used after close() raised IndexError or KeyError: 'workers'."""
    path = write_floor(tmp_path, sensors=4, paths=64)
    with distributed.Cluster(workers=1, threads_per_worker=1, timeout=30) as one:
        assert len(one.workers()) == 1
        with distributed.contributions(str(path), one) as freed:
            mask = np.ones(freed.E.shape[1], dtype=bool)
            expected = freed.evaluate(mask)
        kept = distributed.contributions(str(path), one)
        for call in (lambda: freed.evaluate(mask), lambda: freed.evaluate_batch(mask[np.newaxis]),
                     lambda: freed.evaluate_openings([]), lambda: freed.solve()):
            with pytest.raises(distributed.ClusterError, match="these contributions were closed .* compute them again"):
                call()
    for call in (lambda: kept.evaluate(mask), lambda: kept.evaluate_batch(mask[np.newaxis]),
                 lambda: kept.evaluate_openings([]), lambda: kept.solve()):
        with pytest.raises(distributed.ClusterError, match="this study's cluster was closed"):
            call()
    for call in (one.workers, one.check, lambda: distributed.contributions(str(path), one),
                 lambda: distributed.evaluate(str(path), [], one)):
        with pytest.raises(distributed.ClusterError, match="this study's cluster was closed"):
            call()
    # What the client holds stays usable.
    assert np.array_equal(kept.all_open, freed.all_open)
    kept.save(str(tmp_path / "kept"))
    assert (tmp_path / "kept.npz").exists()
    kept.close()
    one.close()  # a second close does nothing
    assert expected[0].shape == (4,)
    for bad in (0, 1025, 2.0, True, "2"):
        with pytest.raises(ValueError, match="workers must be an integer from 1 to 1024"):
            distributed.Cluster(workers=bad)


# ---- solve ------------------------------------------------------------------------------------


def write_solve_floor(tmp_path, **solver):
    """write_floor with goals (half the unobstructed light everywhere), opening limits and a short
    genetic run: every stage of the solver runs (exact re-ranking, edges off the grid, trade-offs,
    the check with real cutters)."""
    path = write_floor(tmp_path, sensors=18, paths=256, element_size=0.4)
    scene = json.loads(path.read_text())
    scene["goals"] = {"units": "normalized", "uniform": [{"sensors": "all", "level": 0.3}]}
    scene["solver"] = dict({"generations": 30, "population": 16, "seed": 3, "verify_paths": 64,
                            "constraints": {"min_width": 0.6, "min_height": 0.8, "sill_min": 0.6}}, **solver)
    path.write_text(json.dumps(scene))
    return path


def quietly(function, *args, **kwargs):
    """function(...) without its RuntimeWarnings (a solve's warnings, which its result holds)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        return function(*args, **kwargs)


def without_timings(result):
    """A solve result without what measures time (and the tracing's stage, listed when the solve
    traced the contributions itself, as timings_s["contributions"] is)."""
    result = json.loads(json.dumps(result))
    result.pop("timings_s")
    for generation in result["genetic"]["history"]:
        generation.pop("seconds")
    result["stages"] = [s for s in result["stages"] if s["name"] != "contributions"]
    for stage in result["stages"]:
        stage.pop("seconds")
    if "climate" in result:  # the hourly model's bytes over its shards: each stores its own sensors'
        assert result["climate"].pop("model_bytes") > 0
    return result


def test_solve_on_a_cluster_equals_one_process(tmp_path, cluster):
    path = write_solve_floor(tmp_path)
    one = quietly(fenestra.solve, fenestra.load_scene(str(path)))
    assert one["openings"] and one["tradeoffs"] and one["error"]["verified"] and one["edge_moves"] > 0
    many = quietly(distributed.solve, str(path), cluster, shards=3)
    assert without_timings(many) == without_timings(one)
    assert [s["name"] for s in many["stages"]] == [s["name"] for s in one["stages"]]  # the tracing's too
    # From contributions already on the cluster (the solver's paths: render's here), shards of 1 to 7 sensors.
    scene = fenestra.load_scene(str(path))
    with distributed.contributions(scene, cluster, shards=5) as study:
        again = quietly(study.solve)
    assert without_timings(again) == without_timings(one)


def test_a_worker_killed_mid_solve_leaves_the_answer_unchanged(tmp_path, cluster, monkeypatch):
    """The solver's state on a shard (exact values' references, region searches) is rebuilt on the
    worker that recomputes it, so the answer is the same bit for bit."""
    path = write_solve_floor(tmp_path)
    one = quietly(fenestra.solve, fenestra.load_scene(str(path)))
    cluster.client.wait_for_workers(2, timeout=60)
    asked = distributed.client._ShardedRecords._ask
    seen = {"calls": 0, "killed": [], "recomputed": 0}

    def ask(records, op, *args):
        seen["calls"] += 1
        # Twice: among the genetic stage's exact values, and in an edge search's tries.
        if (seen["calls"] == 20 and not seen["killed"]) or (op == "try" and len(seen["killed"]) == 1):
            cluster.client.wait_for_workers(2, timeout=60)
            holder = records._study.shards[0][2]
            seen["killed"].append(op)
            os.kill(worker_pids(cluster)[holder], signal.SIGKILL)
        result = asked(records, op, *args)
        seen["recomputed"] = records._study.recomputed_shards
        return result

    monkeypatch.setattr(distributed.client._ShardedRecords, "_ask", ask)
    many = quietly(distributed.solve, str(path), cluster, shards=2)
    assert len(seen["killed"]) == 2 and seen["killed"][1] == "try"
    assert seen["recomputed"] >= 2
    assert without_timings(many) == without_timings(one)
    cluster.client.wait_for_workers(2, timeout=60)


def test_a_thick_wall_solve_cuts_its_edge_search_on_the_shards(tmp_path, cluster, monkeypatch):
    """In a 0.3 m wall the edges below the element size are searched with real cutters: on a
    cluster those cuts are traced by the shards' workers, on a random stream of their own (not the
    final check's). The result is one process's, bit for bit."""
    path = write_solve_floor(tmp_path)
    scene = json.loads(path.read_text())
    scene["opening_domain"]["thickness"] = 0.3
    path.write_text(json.dumps(scene))
    one = quietly(fenestra.solve, fenestra.load_scene(str(path)))
    edges = [s for s in one["stages"] if s["name"] == "thick-wall edges"]
    assert edges and edges[0]["stopped_because"] == "done", one["stages"]
    cut = distributed.client._ShardedRecords.cut
    streams = []

    def counted(records, openings, paths, stream=0):
        streams.append(stream)
        return cut(records, openings, paths, stream)

    monkeypatch.setattr(distributed.client._ShardedRecords, "cut", counted)
    many = quietly(distributed.solve, str(path), cluster, shards=3)
    assert 1 in streams and 0 in streams, streams  # the search's cuts, and the check's
    assert without_timings(many) == without_timings(one)


def write_two_closed_rooms(tmp_path):
    """Two rooms 3 m apart in 0.3 m walls, room A (y 0..3) opening south and room B (y 6..9)
    north, six sensors each: a change of one room's openings does not reach the other's sensors,
    so the thick-wall stages' cuts keep their values (docs/solver.md, step 7)."""
    a = box_obj((0, 0, 0), (3, 3, 2.5), lambda f: "facade" if f == "south" else "grey")
    b = box_obj((0, 6, 0), (3, 9, 2.5), lambda f: "facade" if f == "north" else "grey")
    shifted = "\n".join("f " + " ".join(str(int(i) + 24) for i in line.split()[1:]) if line.startswith("f ") else line
                        for line in b.splitlines())
    (tmp_path / "rooms.obj").write_text(a + shifted + "\n")
    sensors = [[x, y, 0.8] for y in (1.0, 2.0) for x in (0.7, 1.5, 2.3)]
    sensors += [[x, y, 0.8] for y in (7.0, 8.0) for x in (0.7, 1.5, 2.3)]
    scene = {
        "fenestra": 1, "geometry": "rooms.obj",
        "materials": {"grey": {"reflectance": 0.5}, "facade": {"reflectance": 0.5}},
        "opening_domain": {"materials": ["facade"], "element_size": 0.5, "thickness": 0.3},
        "sensors": {"points": sensors, "normals": [0, 0, 1]},
        "sky": {"type": "cie_overcast", "resolution": [64, 32]},
        "render": {"paths_per_sensor": 256, "seed": 7},
        "goals": {"units": "lux", "uniform": [{"sensors": "all", "level": 300.0}]},
        "solver": {"generations": 30, "population": 16, "seed": 3, "verify_paths": 64,
                   "constraints": {"min_width": 0.6, "min_height": 0.8, "sill_min": 0.6}},
    }
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))
    return path


def test_cuts_that_keep_the_values_a_change_cannot_reach_are_one_processs_on_a_cluster(tmp_path, cluster):
    """A cut keeps its values at the sensors a change of openings cannot reach (their sky samples
    would be drawn anew): the cluster's shards name those sensors from their records, so the
    result is one process's, bit for bit, though the shards trace every cut whole."""
    path = write_two_closed_rooms(tmp_path)
    one = quietly(fenestra.solve, fenestra.load_scene(str(path)))
    shares = [one[k]["traced_share"] for k in ("thick_wall_merges", "thick_wall_joint_edges") if one[k]["run"]]
    assert shares and min(shares) < 1.0, (one["thick_wall_merges"], one["thick_wall_joint_edges"])
    many = quietly(distributed.solve, str(path), cluster, shards=2)
    assert without_timings(many) == without_timings(one)


def write_climate_room(tmp_path):
    """The climate goals' test room (sDA and ASE, least glazing) with a short search, trade-offs and
    the check with real cutters."""
    from test_climate_goals import SDA_ASE, climate_room

    path, scene = climate_room(tmp_path, SDA_ASE, paths=128)
    scene["solver"].update(generations=10, population=10, tradeoffs=True, verify_paths=64)
    path.write_text(json.dumps(scene))
    return path


def test_a_climate_solve_on_a_cluster_equals_one_process_with_a_worker_killed(tmp_path, monkeypatch):
    """Climate goals: the hourly model stays in the shards, which settle the search's states and
    answer in tallies; the years of openings (from the records, and traced with real cutters) come
    from the shards. A worker killed in the middle of the genetic search (its shards' states lost)
    is recomputed and brought back to the search's state, and the result is the same bit for bit."""
    path = write_climate_room(tmp_path)
    one = quietly(fenestra.solve, fenestra.load_scene(str(path)))
    climate = one["climate"]
    assert climate["goals"][0]["verified"] is not None and one["tradeoffs"], climate
    asked = distributed.client._ShardedRecords._ask
    seen = {"ops": set(), "killed": 0, "recomputed": 0}

    def ask(records, op, *args):
        seen["ops"].add(op)
        seen[op] = seen.get(op, 0) + 1
        if op == "climate_settle" and seen[op] == 4 and not seen["killed"]:
            seen["killed"] += 1
            os.kill(worker_pids(cluster)[records._study.shards[0][2]], signal.SIGKILL)
        result = asked(records, op, *args)
        seen["recomputed"] = records._study.recomputed_shards
        return result

    monkeypatch.setattr(distributed.client._ShardedRecords, "_ask", ask)
    # A cluster of its own: the killed worker's restart is not waited for (the shared one stays whole).
    with distributed.Cluster(workers=2, threads_per_worker=1, timeout=30) as cluster:
        many = quietly(distributed.solve, str(path), cluster, shards=3)
    assert {"climate_model", "climate_settle", "climate_flip_tallies", "climate_tally", "annual_parts",
            "exact"} <= seen["ops"], seen
    assert seen["killed"] == 1 and seen["recomputed"] >= 1
    assert without_timings(many) == without_timings(one)


def test_a_solve_under_a_sky_without_light_is_refused_before_any_tracing(tmp_path, cluster, monkeypatch):
    path = write_solve_floor(tmp_path)
    scene = json.loads(path.read_text())
    scene["sky"] = {"type": "preetham", "latitude": 78, "longitude": 15, "utc_offset": 1, "date": "2026-12-21",
                    "resolution": [64, 32]}
    path.write_text(json.dumps(scene))

    def traced(*args, **kwargs):
        raise AssertionError("traced contributions for a solve that cannot be met")

    monkeypatch.setattr(distributed.client, "_contributions", traced)
    with pytest.raises(ValueError, match="2026-12-21.*the goals cannot be met"):
        distributed.solve(str(path), cluster)


def test_a_solve_whose_client_would_not_fit_is_refused_before_any_tracing(tmp_path, cluster, monkeypatch):
    path = write_solve_floor(tmp_path)
    scene = fenestra.load_scene(str(path))
    held = distributed.check_client_fits(scene)
    # E, E_stderr, A, T and the flip effects at least: 8 bytes per sensor and element, four times.
    assert held >= 8 * (4 * scene.sensor_count * scene.element_count + scene.element_count ** 2)

    def traced(*args, **kwargs):
        raise AssertionError("traced contributions for a client that cannot hold them")

    monkeypatch.setattr(distributed.client, "_contributions", traced)
    with pytest.raises(ValueError, match=r"the client of a solve on a cluster holds about .* allowed by max_memory"):
        distributed.solve(str(path), cluster, max_memory=int(held) - 1)
    with pytest.raises(ValueError, match="max_memory expects"):
        distributed.solve(str(path), cluster, max_memory=-5)


def test_cli_solves_climate_goals_on_a_local_cluster_as_one_process(tmp_path):
    path = write_climate_room(tmp_path)
    runs = {}
    for name, extra in (("one", []), ("many", ["--workers", 2, "--threads", 1, "--shards", 2])):
        r = cli("solve", path, "-o", tmp_path / (name + ".json"), "--quiet", *extra)
        assert r.returncode == 0, r.stderr
        runs[name] = r
    one, many = (json.loads((tmp_path / n).read_text()) for n in ("one.json", "many.json"))
    assert one["climate"]["goals"][0]["achieved"] is not None
    assert without_timings(many) == without_timings(one)
    assert "climate goal sDA300/50% >= 50 %:" in runs["many"].stdout, runs["many"].stdout
    r = cli("solve", path, "-o", tmp_path / "said.json", "--workers", 2, "--threads", 1)
    assert r.returncode == 0, r.stderr
    said = re.search(r"estimated memory: about ([\d.]+) (MiB|GiB) per worker, [\d.]+ (MiB|GiB) in this process \(one "
                     r"process would hold [\d.]+ (MiB|GiB)\)", r.stderr)
    assert said, r.stderr
    # The summary is the one process's, but its seconds and the output's name.
    summary = lambda out: [line.split("; ")[0] if line.startswith("solve:") else line
                           for line in out.replace("many.json", "one.json").splitlines()]
    assert summary(runs["many"].stdout) == summary(runs["one"].stdout)


def test_cli_solve_on_a_local_cluster_writes_what_one_process_writes(tmp_path):
    path = write_solve_floor(tmp_path)
    runs = {}
    for name, extra in (("one", []), ("many", ["--workers", 2, "--threads", 1, "--shards", 3])):
        r = cli("solve", path, "-o", tmp_path / (name + ".json"), "--seed", 5, "--paths", 192, "--quiet", *extra)
        assert r.returncode == 0, r.stderr
        runs[name] = r
    one, many = (json.loads((tmp_path / n).read_text()) for n in ("one.json", "many.json"))
    assert one["sensors"][0]["predicted"] > 0
    assert without_timings(many) == without_timings(one)
    summary = lambda out: [line.split("; ")[0:2] if line.startswith("solve:") else line for line in out.splitlines()]
    assert summary(runs["many"].stdout.replace("many.json", "one.json")) == summary(runs["one"].stdout)  # but seconds


def test_cli_solve_ctrl_c_stops_the_solver_and_writes_nothing(tmp_path):
    path = write_solve_floor(tmp_path, generations=1000000)
    out = tmp_path / "out.json"
    p = subprocess.Popen([CLI, "solve", str(path), "-o", str(out), "--workers", "2"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + STARTUP_GUARD_S
    line = ""
    while "solving:" not in line:  # the contributions are on the cluster, the solver runs
        line = p.stderr.readline()
        assert line or p.poll() is None, "exited early"
        assert time.monotonic() < deadline
    time.sleep(1.0)
    start = time.monotonic()
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=120)
    assert p.returncode == 130, err
    assert "interrupted by SIGINT; no output written" in err
    assert time.monotonic() - start < 30
    assert not out.exists()


def test_record_queries_refuse_bad_arguments_and_bad_answers(tmp_path):
    """The shard side (fenestra._core.RecordQueries) names a bad mask or rectangle; the solver names a
    records object whose answers have the wrong shape, or passes its exception on."""
    from fenestra import _core

    path = write_solve_floor(tmp_path)
    scene = fenestra.load_scene(str(path))
    c = fenestra.contributions(scene)
    q = _core.RecordQueries(scene, c)
    n = scene.element_count
    with pytest.raises(ValueError, match=r"open mask must have shape \(%d,\)" % n):
        q.exact(np.ones(n + 1, dtype=np.uint8))
    for bad in ([[7, 0, 1, 0, 1]], [[-1, 0, 1, 0, 1]], [[0.5, 0, 1, 0, 1]], [[np.nan, 0, 1, 0, 1]]):
        with pytest.raises(ValueError, match="is not a panel of the opening domain"):
            q.evaluate(np.array(bad, dtype=float))
    for bad in ([[0, np.nan, 1, 0, 1]], [[0, 0, np.inf, 0, 1]], [[0, 0, 1, -np.inf, 1]]):
        with pytest.raises(ValueError, match="is not a finite number of meters"):
            q.evaluate(np.array(bad, dtype=float))
    with pytest.raises(ValueError, match=r"shape \(n, 5\)"):
        q.region_search(np.zeros((2, 4)))
    v, e = q.exact(np.ones(n, dtype=np.uint8))
    assert np.array_equal(v, c.evaluate(np.ones(n, dtype=bool))[0])

    class Short:
        def exact(self, open_mask):
            return np.zeros(3), np.zeros(3)

    with pytest.raises(RuntimeError, match="exact values: expected %d values" % scene.sensor_count):
        _core.solve_with_records(scene, c, Short())

    class Failing:
        def exact(self, open_mask):
            raise OSError("the cluster went away")

    with pytest.raises(OSError, match="the cluster went away"):
        _core.solve_with_records(scene, c, Failing())


def test_record_queries_refuse_bad_climate_arguments_and_bad_answers(tmp_path):
    """Climate goals' queries on a shard: states, slots, elements and goals of the wrong form, and
    records of another sky, are named; a records object whose shards answer in tallies of another
    model, or for another number of states, is named by the solver."""
    from fenestra import _core
    from test_climate_goals import SDA_ASE, climate_room

    path, _ = climate_room(tmp_path, SDA_ASE, paths=64)
    scene = fenestra.load_scene(str(path))
    c = fenestra.contributions(scene)
    q = _core.RecordQueries(scene, c)
    n, sensors = scene.element_count, scene.sensor_count
    about, excluded = np.zeros(n, dtype=np.uint8), np.zeros(n, dtype=np.uint8)
    goals = np.concatenate([np.full(sensors, np.nan), np.zeros(sensors), np.full(sensors, -np.inf),
                            np.full(sensors, np.inf)])
    with pytest.raises(ValueError, match="none was built"):
        q.climate_flip_tallies(0, np.zeros(1, np.int32))
    assert q.climate_model(about, excluded, goals) > 0
    width = (n + 7) // 8
    states = np.zeros((2, width), np.uint8)
    states[1, 0] = 0b101  # elements 0 and 2 open
    tallies = q.climate_settle(np.array([0, 1], np.int32), np.array([-1, 0], np.int32), states)
    assert len(tallies) == 2
    hours, sums, above_target, above_minimum = tallies[0]
    assert len(hours) == 2 and all(len(h) == sensors for h in hours)  # sDA and ASE, per goal sensor
    assert not np.array_equal(tallies[0][0][0], tallies[1][0][0]) or not np.array_equal(tallies[0][0][1],
                                                                                      tallies[1][0][1])
    flipped = q.climate_flip_tallies(0, np.array([0, 2], np.int32))
    assert len(flipped) == 2
    for args, message in (((np.array([0], np.int32), np.array([-1], np.int32), np.zeros((1, width + 1), np.uint8)),
                           "expected as many slots"),
                          ((np.array([3], np.int32), np.array([7], np.int32), np.zeros((1, width), np.uint8)),
                           "slot 7 holds no settled state"),
                          ((np.array([1, 1], np.int32), np.array([-1, -1], np.int32), np.zeros((2, width), np.uint8)),
                           "written twice")):
        with pytest.raises(ValueError, match=message):
            q.climate_settle(*args)
    with pytest.raises(ValueError, match="element %d is not one of the %d" % (n, n)):
        q.climate_flip_tallies(0, np.array([n], np.int32))
    with pytest.raises(ValueError, match="expected the target, weight, lower and upper of %d sensors" % sensors):
        q.climate_model(about, excluded, goals[:-1])
    with pytest.raises(ValueError, match="climate model state: expected %d elements" % n):
        q.climate_model(np.zeros(n + 2, np.uint8), excluded, goals)
    with pytest.raises(ValueError, match="values must be 0 or 1"):
        q.climate_tally(np.full(n, 2, np.uint8), goals)
    sources, sun, mean, stderr = q.annual_parts(np.zeros((0, 5)))
    assert sources.shape[0] == sun.shape[0] == len(mean) == len(stderr) == sensors

    (tmp_path / "other").mkdir()
    other_scene = fenestra.load_scene(str(write_solve_floor(tmp_path / "other")))
    other_scene.render.paths_per_sensor = 16
    with pytest.raises(ValueError, match="not a climate sky's"):
        _core.RecordQueries(other_scene, fenestra.contributions(other_scene)).climate_model(
            np.zeros(other_scene.element_count, np.uint8), np.zeros(other_scene.element_count, np.uint8),
            np.zeros(4 * other_scene.sensor_count))

    class Model:
        model_bytes = 1.0

        def __init__(self, settle):
            self.settle = settle

        def flip_tallies(self, slot, elements):
            return [q.climate_flip_tallies(slot, elements)]

        def close(self):
            pass

    class OtherModel:
        def climate_model(self, about, excluded, goals):
            q.climate_model(about, excluded, goals)
            return Model(lambda slots, bases, states: [q.climate_settle(slots, bases, states)])

        def climate_tally(self, open_mask, goals):
            hours, sums, target, minimum = q.climate_tally(open_mask, goals)
            return [(hours[:1], sums, target, minimum)]

    with pytest.raises(ValueError, match="climate tally: hours of another model"):
        _core.solve_with_records(scene, c, OtherModel())

    class FewerStates(OtherModel):
        def climate_model(self, about, excluded, goals):
            q.climate_model(about, excluded, goals)
            return Model(lambda slots, bases, states: [q.climate_settle(slots, bases, states)[:-1]])

        def climate_tally(self, open_mask, goals):
            return [q.climate_tally(open_mask, goals)]

    with pytest.raises(ValueError, match="answered for"):
        _core.solve_with_records(scene, c, FewerStates())


def test_a_stopped_worker_is_named_within_the_timeout(cluster):
    """A worker that does not answer (here stopped with SIGSTOP) is named, not waited for forever."""
    cluster.client.wait_for_workers(2, timeout=60)
    address, pid = sorted(worker_pids(cluster).items())[0]
    os.kill(pid, signal.SIGSTOP)
    try:
        start = time.monotonic()
        with pytest.raises(distributed.ClusterError, match="worker %s did not answer within 3 s" % address):
            distributed.Cluster(scheduler=cluster.address, timeout=3)
        assert time.monotonic() - start < 20
    finally:
        os.kill(pid, signal.SIGCONT)


# ---- faults of a running cluster end clearly -------------------------------------------------------


@pytest.fixture(scope="module")
def external_scheduler(tmp_path_factory):
    """A Dask scheduler started by hand (as on a real cluster, without a nanny to restart workers);
    its address. Each test starts its own workers with start_worker."""
    folder = tmp_path_factory.mktemp("scheduler")
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "addon"))
    scheduler = subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1",
                                  "--port", "0", "--no-dashboard", "--scheduler-file", str(folder / "s.json")],
                                 env=env, cwd=folder, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 60
        while not (folder / "s.json").exists() or not (folder / "s.json").read_text().strip():
            assert time.monotonic() < deadline and scheduler.poll() is None, "the scheduler did not start"
            time.sleep(0.1)
        yield json.loads((folder / "s.json").read_text())["address"]
    finally:
        scheduler.terminate()
        scheduler.wait(timeout=30)


def start_worker(address, folder):
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "addon"))
    return subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_worker", address, "--nthreads", "1",
                             "--no-dashboard", "--no-nanny"], env=env, cwd=folder,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def contributions_until(cluster, path, fault, cap=90):
    """distributed.contributions on a long study; `fault()` once its shards are being traced. The
    exception it ends with, and the seconds from the fault to the end; the test fails if it has not
    ended within `cap` seconds."""
    outcome = {}

    def run():
        try:
            distributed.contributions(str(path), cluster, shards=2)
        except BaseException as exc:
            outcome["error"] = exc
        outcome["end"] = time.monotonic()

    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    deadline = time.monotonic() + 60
    while not any(cluster.client.processing().values()):
        assert time.monotonic() < deadline and thread.is_alive(), outcome
        time.sleep(0.05)
    time.sleep(0.5)
    fault()
    at = time.monotonic()
    thread.join(cap)
    assert not thread.is_alive(), "still waiting %d s after the fault" % cap
    return outcome.get("error"), outcome["end"] - at


def test_a_worker_stopped_during_a_study_is_named_within_the_timeout(tmp_path, external_scheduler):
    """A SIGSTOPped worker ended the study after 69 s with Dask's "Timed out during handshake"."""
    path = write_floor(tmp_path, sensors=8, paths=1 << 17)
    worker = start_worker(external_scheduler, tmp_path)
    try:
        with distributed.Cluster(scheduler=external_scheduler, timeout=30) as cluster:  # time to start the worker
            (address,) = cluster.workers()
            cluster.timeout = 4.0  # how long a study waits on a worker not heard from
            error, seconds = contributions_until(cluster, path, lambda: os.kill(worker.pid, signal.SIGSTOP))
        assert isinstance(error, distributed.ClusterError), repr(error)
        assert re.search(r"worker %s has not been heard from for 4 s: it is stopped \(e.g. by SIGSTOP\), hung, or cut "
                         r"off from the scheduler at .*; resume or restart it" % re.escape(address), str(error)), error
        assert "handshake" not in str(error)
        assert seconds < 4.0 + 10.0  # the timeout, the scheduler's heartbeat and this client's polling
    finally:
        worker.kill()
        worker.wait(timeout=30)


def test_losing_the_only_worker_during_a_study_ends_with_a_message(tmp_path, external_scheduler):
    """The only worker killed during contributions left the client waiting in silence."""
    path = write_floor(tmp_path, sensors=8, paths=1 << 17)
    worker = start_worker(external_scheduler, tmp_path)
    try:
        with distributed.Cluster(scheduler=external_scheduler, timeout=30) as cluster:
            (address,) = cluster.workers()
            cluster.timeout = 4.0
            error, seconds = contributions_until(cluster, path, lambda: os.kill(worker.pid, signal.SIGKILL))
        assert isinstance(error, distributed.ClusterError), repr(error)
        assert re.search(r"the Dask cluster at %s has had no worker for 4 s \(%s left: killed, crashed or out of "
                         r"memory\): its work cannot go on; start workers with 'dask worker %s'"
                         % ((re.escape(external_scheduler), re.escape(address), re.escape(external_scheduler))),
                         str(error)), error
        assert seconds < 4.0 + 10.0
    finally:
        worker.kill()
        worker.wait(timeout=30)


def test_the_python_example_of_the_docs_runs_as_written(tmp_path):
    """docs/distributed.md's Python block, run as a script on a small scene.json: it must run to the
    end (its local workers, started with spawn, import the script: the main guard keeps them from
    running it)."""
    text = open(os.path.join(ROOT, "docs", "distributed.md"), encoding="utf-8").read()
    block = re.search(r"```python\n(.*?)```", text, re.S).group(1)
    assert 'if __name__ == "__main__":' in block
    (tmp_path / "example.py").write_text(block)
    write_solve_floor(tmp_path, generations=4, population=8)  # tmp_path/scene.json, as the example reads it
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "addon"))
    r = subprocess.run([sys.executable, "example.py"], cwd=tmp_path, env=env, capture_output=True, text=True,
                       timeout=240)
    assert r.returncode == 0, r.stderr[-3000:]
    assert (tmp_path / "contributions.npz").exists() and (tmp_path / "contributions.json").exists()


# ---- annual studies and skies -------------------------------------------------------------------


def write_annual_room(tmp_path):
    """The climate goals' test room with 128 paths per sensor, and an opening on its south wall."""
    from test_climate_goals import SDA_ASE, climate_room

    path, _ = climate_room(tmp_path, SDA_ASE, paths=128)
    openings = tmp_path / "openings.json"
    openings.write_text(json.dumps({"openings": [{"corners": [[0.5, 0, 0.9], [2.5, 0, 0.9], [2.5, 0, 2.1],
                                                              [0.5, 0, 2.1]]}]}))
    return path, openings


def without_seconds(result):
    out = dict(result)
    out["summary"] = {k: v for k, v in result["summary"].items() if k != "seconds"}
    return out


def assert_same_annual(a, b):
    assert a.keys() == b.keys()
    for name in a:
        if isinstance(a[name], np.ndarray):
            assert a[name].dtype == b[name].dtype and np.array_equal(a[name], b[name]), name
        else:
            assert without_seconds(a)[name] == without_seconds(b)[name], name


def test_annual_on_a_cluster_equals_one_process_bit_for_bit(tmp_path, cluster):
    """The records' study and the study with real cutters, in 2 and 3 shards, against one process:
    every hour of every sensor, the metrics and the files, but the study's seconds."""
    path, openings = write_annual_room(tmp_path)
    scene = fenestra.load_scene(str(path))
    ops = fenestra.read_openings(str(openings))
    one = fenestra.annual(scene, ops, output=str(tmp_path / "one"))
    one_cut = fenestra.annual(scene, ops, cutters=True, paths=32)
    assert one["illuminance"].max() > 1000 and one["summary"]["space"]["annual_sunlight_exposure"] >= 0
    for shards in (2, 3):
        many = distributed.annual(str(path), ops, cluster, shards=shards, output=str(tmp_path / "many"))
        assert_same_annual(many, one)
        assert_same_annual(distributed.annual(str(path), ops, cluster, shards=shards, cutters=True, paths=32), one_cut)
    a, b = np.load(tmp_path / "one.npz"), np.load(tmp_path / "many.npz")
    assert a.files == b.files and all(np.array_equal(a[n], b[n]) for n in a.files)
    ja, jb = (json.loads((tmp_path / n).read_text()) for n in ("one.json", "many.json"))
    assert {k for k in ja if ja[k] != jb[k]} <= {"seconds"}
    # The real cutters see the opening the records see, within their noise.
    assert not np.array_equal(one_cut["illuminance"], one["illuminance"])


def test_annual_on_a_cluster_refuses_bad_arguments_before_any_work(tmp_path, cluster, monkeypatch):
    path, openings = write_annual_room(tmp_path)
    ops = fenestra.read_openings(str(openings))
    from fenestra.distributed import annual_study as annual_module

    def traced(*args, **kwargs):
        raise AssertionError("work started")

    monkeypatch.setattr(annual_module, "_contributions", traced)
    off_wall = [{"corners": [[0.5, 1, 0.9], [2.5, 1, 0.9], [2.5, 1, 2.1], [0.5, 1, 2.1]]}]
    for kwargs, message in (({"openings": off_wall}, "opening 0"),
                            ({"paths": 16}, "paths belongs to annual\\(cutters=True\\)"),
                            ({"paths": -1, "cutters": True}, "paths must be a whole number"),
                            ({"cutters": "yes"}, "cutters"),
                            ({"output": str(tmp_path)}, "directory")):
        args = dict(openings=ops, **kwargs) if "openings" not in kwargs else kwargs
        with pytest.raises((ValueError, TypeError), match=message):  # as fenestra.annual raises them
            distributed.annual(str(path), cluster=cluster, **args)
    floor = write_floor(tmp_path, sensors=4, paths=64)
    with pytest.raises(ValueError, match="needs a scene whose sky is \"climate\""):
        distributed.annual(str(floor), ops, cluster)


def without_capture_date(exr):
    """An OpenEXR file's bytes without the value of its capDate attribute (the time it was written)."""
    data = (exr).read_bytes()
    at = data.index(b"capDate\0string\0")
    start = at + len(b"capDate\0string\0")
    length = int.from_bytes(data[start:start + 4], "little")
    assert 0 < length < 64
    return data[:start + 4] + data[start + 4 + length:]


def test_cli_annual_and_sky_on_a_local_cluster_write_what_one_process_writes(tmp_path):
    path, openings = write_annual_room(tmp_path)
    for name, extra in (("one", []), ("many", ["--workers", 2, "--threads", 1, "--shards", 3])):
        for kind, more in (("", []), ("_cut", ["--cutters", "--paths", 32])):
            r = cli("annual", path, "--openings", openings, "-o", tmp_path / (name + kind), "--quiet", *extra, *more)
            assert r.returncode == 0, r.stderr
            assert "wrote" in r.stdout
        r = cli("sky", path, "-o", tmp_path / (name + ".exr"), "--json", tmp_path / (name + "_sky.json"), "--quiet",
                *extra[:4])  # one worker builds the sky: no shards
        assert r.returncode == 0, r.stderr
        assert "horizontal illuminance" in r.stdout
    for kind in ("", "_cut"):
        a, b = np.load(tmp_path / ("one%s.npz" % kind)), np.load(tmp_path / ("many%s.npz" % kind))
        assert a.files == b.files and all(np.array_equal(a[n], b[n]) for n in a.files), kind
        ja, jb = (json.loads((tmp_path / (n + kind + ".json")).read_text()) for n in ("one", "many"))
        assert {k for k in ja if ja[k] != jb[k]} <= {"seconds"}, kind
    assert without_capture_date(tmp_path / "one.exr") == without_capture_date(tmp_path / "many.exr")
    one, many = (json.loads((tmp_path / n).read_text()) for n in ("one_sky.json", "many_sky.json"))
    # The worker reads the weather file by its absolute path; the time to build the map is its own.
    assert {k for k in one if one[k] != many[k]} <= {"build_seconds", "description"}
    assert one["horizontal_illuminance"] == many["horizontal_illuminance"] and one["suns"] == many["suns"]
