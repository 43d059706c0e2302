"""Ground-truth validation of the opening solver (`make validate`).

For each ground-truth scene of examples/ (window_room, apartment, atrium, solid_wall_room; see
make_examples.py):

1. the scene's truth.json openings are path-traced with many paths (`evaluate`); the sensor
   values become lux goals, written with the scene into out/validate/<scene>/scene.json (with the
   "solver" settings used below, so `fenestra solve` can be run on it directly);
2. the solver designs openings for those goals (out/validate/<scene>/result.json);
3. the solution's openings are path-traced again, independently (other random numbers), and
   compared with the goals: relative RMS error sqrt(sum (v - g)^2 / sum g^2) and the worst
   sensor's relative error. The target is a relative RMS of at most 2 %.

The Monte Carlo noise of that comparison is reported beside it: the relative standard error of
(v - g), sqrt(sum (s_v^2 + s_g^2) / sum g^2), which is the relative RMS a perfect answer would
show, and the truth itself evaluated a second time with other random numbers, compared with the
goals the same way (the same quantity, measured).

The table goes to out/validate/table.md and into README.md between the validate markers; all
numbers to out/validate/results.json. Exits with status 1 if a scene misses the target.

    /usr/bin/python3 scripts/validate.py [--scenes window_room,apartment,atrium] [--quick]
"""

import argparse
import json
import os
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "addon"))
import fenestra  # noqa: E402

EXAMPLES = os.path.join(ROOT, "examples")
TARGET = 0.02  # relative RMS error of the solution against the goals
SEEDS = {"goals": 1001, "solution": 2002, "truth again": 3003}

# Per scene: paths per sensor of the goal and check evaluations, and the solver's settings.
SOLVER = {"paths": 16384, "population": 64, "generations": 500, "seed": 1, "elite": 8}
SCENES = {
    "window_room": {
        "paths": 262144,
        "solver": SOLVER,
    },
    "apartment": {
        "paths": 131072,
        "solver": SOLVER,
    },
    "atrium": {
        "paths": 524288,
        "solver": SOLVER,
    },
    # The studies the Blender examples write (examples/build_blend_examples.py).
    "room_study": {
        "paths": 131072,
        "solver": SOLVER,
    },
    "apartment_study": {
        "paths": 131072,
        "solver": SOLVER,
    },
    # Built by `make examples-blend` (its 189 000-triangle OBJ is not kept in the repository):
    # skipped when absent. Two skylights over the atrium's void.
    "museum_study": {
        "source": os.path.join(ROOT, "out", "examples", "museum_study"),
        "truth_cells": [(0, 6, 9, 6, 9), (0, 13, 17, 12, 17)],
        "paths": 131072,
        "solver": dict(SOLVER, paths=8192),
    },
    # 0.3 m walls (the south wall modelled by its inner face, the thickness given): the elements
    # are tubes through the wall, lined by their closed neighbours' reveals.
    "thick_walls_study": {
        "paths": 131072,
        "solver": SOLVER,
    },
    # A 0.3 m wall modelled as a solid (outer face and edge strips in the model; the thickness measured),
    # under a sun oblique to the wall.
    "solid_wall_room": {
        "paths": 131072,
        "solver": SOLVER,
    },
    # Truths whose edges lie between grid lines: shifted by half an element along the wall and up.
    "window_room_off_grid": {
        "source": os.path.join(EXAMPLES, "window_room"),
        "truth_shift": [0.175, 0.0, 0.175],
        "paths": 262144,
        "solver": SOLVER,
    },
    # In thick walls the edges are searched below the element size on a grid refined about the
    # openings, traced again (solver step 7).
    "thick_walls_off_grid": {
        "source": os.path.join(EXAMPLES, "thick_walls_study"),
        "truth_shift": [0.125, 0.0, 0.125],
        "paths": 131072,
        "solver": SOLVER,
    },
    # Curved domains, diced in their unrolled surface; the truths are parameter rectangles spanning
    # several facets.
    "curved_wall_room": {
        "paths": 131072,
        "solver": SOLVER,
    },
    "vault_room": {
        "paths": 131072,
        "solver": SOLVER,
    },
    # Window catalogues holding the truth's sizes among others (solver.constraints.catalogue): every
    # opening of the answer is one of them; the off-grid truth is a catalogue size, not a multiple
    # of the element.
    "window_room_off_grid_catalogue": {
        "source": os.path.join(EXAMPLES, "window_room"),
        "truth_shift": [0.175, 0.0, 0.175],
        "paths": 262144,
        "solver": dict(SOLVER, constraints={"catalogue": [[0.9, 1.2], [1.2, 1.5], [1.4, 1.4], [1.4, 1.75],
                                                          [1.8, 1.5], [1.8, 2.1]]}),
    },
    "apartment_catalogue": {
        "source": os.path.join(EXAMPLES, "apartment"),
        "paths": 131072,
        "solver": dict(SOLVER, constraints={"catalogue": [[0.9, 1.2], [1.2, 1.5], [1.6, 1.6], [2.0, 1.6],
                                                          [1.8, 2.1]]}),
    },
    "thick_walls_off_grid_catalogue": {
        "source": os.path.join(EXAMPLES, "thick_walls_study"),
        "truth_shift": [0.125, 0.0, 0.125],
        "paths": 131072,
        "solver": dict(SOLVER, constraints={"catalogue": [[1.2, 1.5], [1.5, 1.2], [2.0, 1.5], [2.4, 1.5]]}),
    },
}

SKY_NAMES = {
    "uniform": "uniform",
    "cie_overcast": "CIE overcast",
    "cie_clear": "CIE clear + sun",
    "preetham": "Preetham + sun",
    "envmap": "HDR map",
}

BEGIN, END = "<!-- validate:begin -->", "<!-- validate:end -->"


def relative_rms(values, goals):
    return float(np.sqrt(np.sum((values - goals) ** 2) / np.sum(goals ** 2)))


def max_relative(values, goals):
    return float(np.max(np.abs(values - goals) / goals))


def noise_level(stderr_a, stderr_b, goals):
    """Relative standard error of the difference of two independent estimates, over all sensors."""
    return float(np.sqrt(np.sum(stderr_a ** 2 + stderr_b ** 2) / np.sum(goals ** 2)))


def open_mask(scene, openings):
    """Elements whose centre lies in one of the openings (grid-aligned openings cover whole
    elements): by parameter rectangle where given, else by world corners."""
    openings = openings["openings"] if isinstance(openings, dict) else openings
    a = scene.element_size
    grid = np.asarray(scene.element_grid)
    centres = scene.element_corners.mean(axis=1)
    u, v = (grid[:, 2] + 0.5) * a, (grid[:, 1] + 0.5) * a
    mask = np.zeros(scene.element_count, bool)
    tolerance = 1e-4 * a
    for o in openings:
        if isinstance(o, dict) and "parameter_rectangle" in o:
            r = o["parameter_rectangle"]
            mask |= ((grid[:, 0] == o["panel"]) & (u > r["u0"] - tolerance) & (u < r["u1"] + tolerance)
                     & (v > r["v0"] - tolerance) & (v < r["v1"] + tolerance))
            continue
        rect = fenestra.openings_array([o])[0]
        lo, hi = rect.min(axis=0) - tolerance, rect.max(axis=0) + tolerance
        mask |= np.all((centres >= lo) & (centres <= hi), axis=1)
    return mask


def evaluate(scene, openings, paths, seed):
    scene.render.paths_per_sensor = paths
    scene.render.seed = seed
    start = time.perf_counter()
    values, stderr = fenestra.evaluate(scene, openings)
    return np.asarray(values), np.asarray(stderr), time.perf_counter() - start


def truth_from_cells(scene, cells):
    """Openings covering whole elements: (panel, first row, last row, first column, last column)."""
    grid, corners = np.asarray(scene.element_grid), np.asarray(scene.element_corners)

    def element(panel, row, col):
        k = np.flatnonzero((grid[:, 0] == panel) & (grid[:, 1] == row) & (grid[:, 2] == col))
        return corners[k[0]]
    return {"openings": [{"corners": [element(p, r0, c0)[0].tolist(), element(p, r0, c1)[1].tolist(),
                                      element(p, r1, c1)[2].tolist(), element(p, r1, c0)[3].tolist()]}
                         for p, r0, r1, c0, c1 in cells]}


def validate_scene(name, config, out_root, scale):
    source = config.get("source", os.path.join(EXAMPLES, name))
    out = os.path.join(out_root, name)
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(source, "scene.json")) as f:
        scene_dict = json.load(f)
    if "truth_cells" in config:
        truth = truth_from_cells(fenestra.load_scene(os.path.join(source, "scene.json")), config["truth_cells"])
        with open(os.path.join(out, "truth.json"), "w") as f:
            json.dump(truth, f, indent=1)
    else:
        with open(os.path.join(source, "truth.json")) as f:
            truth = json.load(f)
    if "truth_shift" in config:  # meters, world axes
        shift = np.asarray(config["truth_shift"], float)
        truth = {"openings": [{"corners": (np.asarray(o["corners"], float) + shift).tolist()}
                              for o in truth["openings"]]}
        with open(os.path.join(out, "truth.json"), "w") as f:
            json.dump(truth, f, indent=1)
    paths = max(1024, int(config["paths"] * scale))
    solver = dict(config["solver"])
    solver["paths"] = max(1024, int(solver["paths"] * scale))

    # 1. Goals: the truth path-traced.
    base = fenestra.scene_from_dict(scene_dict, source)
    goals, goals_stderr, goals_seconds = evaluate(base, truth, paths, SEEDS["goals"])
    derived = dict(scene_dict)
    derived["geometry"] = os.path.relpath(os.path.join(source, scene_dict["geometry"]), out)
    derived["sensors"] = dict(scene_dict["sensors"], goals=[float(g) for g in goals], goal_units="lux")
    derived.pop("goals", None)  # the example's own goals give way to the truth's light
    derived["solver"] = solver
    if derived["sky"].get("file"):
        derived["sky"] = dict(derived["sky"], file=os.path.relpath(os.path.join(source, derived["sky"]["file"]), out))
    derived_path = os.path.join(out, "scene.json")
    with open(derived_path, "w") as f:
        json.dump(derived, f, indent=2)

    # 2. The solver, on the derived scene file.
    scene = fenestra.load_scene(derived_path)
    start = time.perf_counter()
    result = fenestra.solve(scene)
    solve_seconds = time.perf_counter() - start
    with open(os.path.join(out, "result.json"), "w") as f:
        json.dump(result, f, indent=2)

    # 3. The solution path-traced independently, and the truth once more as the noise floor.
    values, stderr, check_seconds = evaluate(scene, result["openings"], paths, SEEDS["solution"])
    again, again_stderr, _ = evaluate(scene, truth, paths, SEEDS["truth again"])
    with open(os.path.join(out, "evaluation.json"), "w") as f:
        json.dump({"sensors": [{"goal": float(g), "goal_stderr": float(ge), "value": float(v), "stderr": float(s),
                                "truth_again": float(a), "truth_again_stderr": float(ae)}
                               for g, ge, v, s, a, ae in zip(goals, goals_stderr, values, stderr, again, again_stderr)]},
                  f, indent=2)

    truth_mask = open_mask(scene, truth)
    solution_mask = np.zeros(scene.element_count, bool)
    solution_mask[np.asarray(result["open_elements"], int)] = True
    row = {
        "scene": name,
        "sky": SKY_NAMES.get(scene_dict["sky"].get("type", "uniform"), scene_dict["sky"].get("type")),
        "sensors": int(scene.sensor_count),
        "elements": int(scene.element_count),
        "triangles": int(scene.triangle_count),
        "after_genetic": float(result["error"]["before_constraints"]["relative_rms"]),
        "after_constraints": float(result["error"]["relative_rms"]),
        "stages": {k: float(v) for k, v in result["timings_s"].items()},
        "element_size": float(scene.element_size),
        "paths": paths,
        # The constraints the scene sets (the automatic ones apply to every row alike).
        "solver": dict(result.get("settings", {}), constraints=solver.get("constraints"), **{
            k: v for k, v in solver.items() if k != "constraints"}),
        "openings_truth": len(truth["openings"]),
        "openings_solution": len(result["openings"]),
        "elements_truth": int(truth_mask.sum()),
        "elements_solution": int(solution_mask.sum()),
        "elements_shared": int((truth_mask & solution_mask).sum()),
        "relative_rms": relative_rms(values, goals),
        "max_relative": max_relative(values, goals),
        "solver_predicted_relative_rms": float(result["error"]["relative_rms"]),
        "solver_linear_relative_rms": float(result["error"]["linear"]["relative_rms"]),
        "noise": noise_level(stderr, goals_stderr, goals),
        # The solver's three predictions of its own solution, against the solution path-traced.
        "exact_vs_evaluate": relative_rms(np.array([x["predicted"] for x in result["sensors"]]), values),
        "linear_vs_evaluate": relative_rms(np.array([x["linear"] for x in result["sensors"]]), values),
        "compensated_vs_evaluate": relative_rms(np.array([x["compensated"] for x in result["sensors"]]), values),
        "evaluation_relative_stderr": float(np.sqrt(np.sum(stderr ** 2) / np.sum(goals ** 2))),
        "truth_again_relative_rms": relative_rms(again, goals),
        "seconds_goals": goals_seconds,
        "seconds_solve": solve_seconds,
        "seconds_contributions": float(result["timings_s"].get("contributions", float("nan"))),
        "seconds_check": check_seconds,
    }
    # Every opening within the scene's constraints (the automatic ones, or the catalogue), checked
    # again from the result's openings.
    row["constraint_violations"] = fenestra.constraint_violations(scene, result["openings"])
    row["constraints_met"] = bool(result["constraints_met"]) and not row["constraint_violations"]
    row["passed"] = (row["relative_rms"] <= TARGET and row["constraints_met"]) if config.get("target", True) else None
    return row


def percent(x):
    return "%.2f %%" % (100.0 * x)


def table(rows):
    lines = [
        "| scene | sky | sensors × elements | openings truth → solution | open elements truth → solution (shared) "
        "| relative RMS | worst sensor | solver's prediction | noise (1σ) | truth re-evaluated | solve / check |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append("| %s | %s | %d × %d (%.2f m) | %d → %d | %d → %d (%d) | **%s** %s | %s | %s | %s | %s | %.1f s / %.1f s |" % (
            r["scene"], r["sky"], r["sensors"], r["elements"], r["element_size"],
            r["openings_truth"], r["openings_solution"],
            r["elements_truth"], r["elements_solution"], r["elements_shared"],
            percent(r["relative_rms"]),
            "(no target: thick wall, truth off the grid)" if r["passed"] is None else "✓" if r["passed"]
            else "✗ (> 2 %)" if r["constraints_met"] else "✗ (constraints)",
            percent(r["max_relative"]), percent(r["solver_predicted_relative_rms"]),
            percent(r["noise"]), percent(r["truth_again_relative_rms"]),
            r["seconds_solve"], r["seconds_check"]))
    lines.append("")
    lines.append("The solver's predictions of its solution against that solution path-traced with real cutters "
                 "(relative RMS difference): the exact evaluation from the path records (what the solver reports), "
                 "the linear model E o (others-closed assumption), and the paper's compensated estimate (its Eq. 3).")
    lines.append("")
    lines.append("| scene | exact (path records) | linear model | compensated (Eq. 3) |")
    lines.append("|---|---|---|---|")
    for r in rows:
        lines.append("| %s | %s | %s | %s |" % (r["scene"], percent(r["exact_vs_evaluate"]),
                                             percent(r["linear_vs_evaluate"]), percent(r["compensated_vs_evaluate"])))
    lines.append("")
    lines.append("The solver's stages (seconds) and its own exact error against the goals after the genetic "
                 "algorithm and after the architectural refinement:")
    lines.append("")
    lines.append("| scene | triangles | contributions | linear start + coarse grids | genetic | constraints | "
                 "error after GA | after constraints |")
    lines.append("|---|---|---|---|---|---|---|---|")
    for r in rows:
        t = r["stages"]
        lines.append("| %s | %d | %.2f | %.2f | %.2f | %.2f | %s | %s |" % (
            r["scene"], r["triangles"], t.get("contributions", 0.0),
            t.get("linear start", 0.0) + t.get("coarse grids", 0.0), t.get("genetic", 0.0),
            t.get("constraints", 0.0), percent(r["after_genetic"]), percent(r["after_constraints"])))
    lines.append("")
    lines.append("Goals and checks: %s paths per sensor; solver settings: %s." % (
        ", ".join("%s %d" % (r["scene"], r["paths"]) for r in rows), _settings_by_scene(rows)))
    return "\n".join(lines) + "\n"


def _settings_by_scene(rows):
    """Each distinct solver setting once: the most common unlabelled, the others with their scenes."""
    groups = {}
    for r in rows:
        groups.setdefault(_settings_text(r["solver"]), []).append(r["scene"])
    common = max(groups, key=lambda text: len(groups[text]))
    parts = [common + (" (the other scenes)" if len(groups) > 1 else "")]
    parts += ["%s (%s)" % (text, ", ".join(scenes)) for text, scenes in groups.items() if text != common]
    return "; ".join(parts)


def _settings_text(s):
    shape = s.get("shape_weights", {})
    text = "paths %s, population %s, generations %s, seed %s, elite %s, coarse to fine %s" % (
        s.get("paths"), s.get("population"), s.get("generations"), s.get("seed"), s.get("elite"),
        "on" if s.get("coarse_to_fine", True) else "off")
    if shape:
        text += ", shape weights isolated %g, boundary %g, regions %g" % (
            shape.get("isolated"), shape.get("boundary"), shape.get("regions"))
    constraints = s.get("constraints")
    if constraints:
        text += ", constraints %s" % json.dumps(constraints, separators=(", ", ": "))
    return text


def update_readme(text):
    path = os.path.join(ROOT, "README.md")
    with open(path) as f:
        readme = f.read()
    begin, end = readme.find(BEGIN), readme.find(END)
    if begin < 0 or end < begin:
        print("README.md has no %s ... %s markers; table not inserted" % (BEGIN, END), file=sys.stderr)
        return
    readme = readme[:begin + len(BEGIN)] + "\n" + text + readme[end:]
    with open(path, "w") as f:
        f.write(readme)


def validate_annual(out_dir, scale):
    """The annual study of examples/annual_room against Radiance (python_tests/data/
    radiance_annual_room): the annual mean per sensor within 5 %, sDA and ASE within 5 points."""
    import gzip
    data = os.path.join(ROOT, "python_tests", "data", "radiance_annual_room")
    with open(os.path.join(data, "metrics.json")) as f:
        radiance = json.load(f)
    room = os.path.join(EXAMPLES, "annual_room")
    scene = fenestra.load_scene(os.path.join(room, "climate.json"))
    scene.render.paths_per_sensor = max(256, int(8192 * scale))
    with open(os.path.join(room, "window.json")) as f:
        window = json.load(f)
    start = time.time()
    year = fenestra.annual(scene, window, output=os.path.join(out_dir, "annual_room"))
    seconds = time.time() - start
    ours = np.array(year["summary"]["per_sensor"]["mean_illuminance_lux"])
    relative = ours / np.array(radiance["mean_illuminance_lux"]) - 1
    space = year["summary"]["space"]
    with gzip.open(os.path.join(data, "illuminance_direct_sun.npy.gz")) as f:
        direct_ratio = year["direct_sun"].sum() / np.load(f).sum()
    row = {"annual_mean_rms": float(np.sqrt(np.mean(relative ** 2))), "annual_mean_min": float(relative.min()),
           "annual_mean_max": float(relative.max()),
           "sda": space["spatial_daylight_autonomy"], "sda_radiance": radiance["sda300_50"],
           "ase": space["annual_sunlight_exposure"], "ase_radiance": radiance["ase1000_250"],
           "direct_sun_year_ratio": float(direct_ratio), "seconds": seconds,
           "paths_per_sensor": scene.render.paths_per_sensor}
    row["passed"] = bool(np.all(np.abs(relative) <= 0.05) and abs(row["sda"] - row["sda_radiance"]) <= 0.05
                         and abs(row["ase"] - row["ase_radiance"]) <= 0.05)
    print("== annual_room against Radiance: annual mean per sensor %+.1f .. %+.1f %% (rms %.1f %%), sDA %.0f %% "
          "(Radiance %.0f %%), ASE %.1f %% (Radiance %.1f %%), direct sun over the year x%.4f; %.1f s (%d paths)"
          % (100 * row["annual_mean_min"], 100 * row["annual_mean_max"], 100 * row["annual_mean_rms"],
             100 * row["sda"], 100 * row["sda_radiance"], 100 * row["ase"], 100 * row["ase_radiance"],
             row["direct_sun_year_ratio"], seconds, row["paths_per_sensor"]), flush=True)
    with open(os.path.join(out_dir, "annual_room.json"), "w") as f:
        json.dump(row, f, indent=2)
    return row


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scenes", default=",".join(SCENES), help="comma-separated scene names")
    parser.add_argument("--out", default=os.path.join(ROOT, "out", "validate"))
    parser.add_argument("--quick", action="store_true", help="1/16 of the paths (a smoke run; README untouched)")
    parser.add_argument("--no-annual", action="store_true", help="skip the annual study against Radiance")
    args = parser.parse_args()
    names = [n for n in args.scenes.split(",") if n]
    unknown = [n for n in names if n not in SCENES]
    if unknown:
        parser.error("unknown scene(s) %s (known: %s)" % (", ".join(unknown), ", ".join(SCENES)))
    scale = 1.0 / 16 if args.quick else 1.0
    os.makedirs(args.out, exist_ok=True)
    rows = []
    for name in names:
        source = SCENES[name].get("source", os.path.join(EXAMPLES, name))
        if not os.path.exists(os.path.join(source, "scene.json")):
            print("== %s: skipped, %s is not built (make examples-blend)" % (name, source), flush=True)
            continue
        print("== %s" % name, flush=True)
        row = validate_scene(name, SCENES[name], args.out, scale)
        print("   relative RMS %s (worst sensor %s), noise %s, truth re-evaluated %s; solver predicted %s; "
              "openings %d -> %d, elements %d -> %d (%d shared); solve %.1f s" % (
                  percent(row["relative_rms"]), percent(row["max_relative"]), percent(row["noise"]),
                  percent(row["truth_again_relative_rms"]), percent(row["solver_predicted_relative_rms"]),
                  row["openings_truth"], row["openings_solution"], row["elements_truth"],
                  row["elements_solution"], row["elements_shared"], row["seconds_solve"]), flush=True)
        rows.append(row)
    text = table(rows) if rows else ""
    with open(os.path.join(args.out, "table.md"), "w") as f:
        f.write(text)
    with open(os.path.join(args.out, "results.json"), "w") as f:
        json.dump(rows, f, indent=2)
    if not args.quick and names == list(SCENES):
        update_readme(text)
    print()
    print(text)
    failed = [r["scene"] for r in rows if r["passed"] is False]
    if not args.no_annual and not validate_annual(args.out, scale)["passed"]:
        failed.append("annual_room (against Radiance)")
    if failed:
        print("relative RMS above %s: %s" % (percent(TARGET), ", ".join(failed)), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
