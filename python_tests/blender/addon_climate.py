"""Climate goals in the add-on, headless (run by test_blender_climate.py):

    blender -b --factory-startup --python-exit-code 1 --python addon_climate.py -- OUT_DIR

The room of addon_study.py under a year of Chicago weather: the Climate Goals list exported as the
scene file's goals.climate / least_glazing / sensors.groups (a goal on a vertex group of the sensor
grid), the fields' ranges, bad setups refused naming the goal and the group with nothing changed,
and a solve on climate goals alone whose figures reach scene.fenestra.results.climate and the
Daylight Autonomy false colour exactly as result.json has them."""

import json
import os
import sys
import unittest

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import installed  # noqa: E402
import addon_study  # noqa: E402

OUT = sys.argv[sys.argv.index("--") + 1] if "--" in sys.argv else "/tmp/fenestra_climate_test"
addon_study.OUT = OUT


def room():
    """The room, its sensor grid with a vertex group "window" (the sensors within 2 m of the south
    wall), the climate sky; no climate goal yet. Returns the sensor object and the group's vertices."""
    addon_study.study()
    addon_study.climate()
    f = bpy.context.scene.fenestra
    f.solve.wall_thickness = 0.0
    sensors = bpy.data.objects["Fenestra Sensors"]
    near = [v.index for v in sensors.data.vertices if (sensors.matrix_world @ v.co).y < 2.0]
    group = sensors.vertex_groups.new(name="window")
    group.add(near, 1.0, 'REPLACE')
    return sensors, near


def add_goal(metric, **values):
    assert bpy.ops.fenestra.climate_goal_add() == {'FINISHED'}
    goals = bpy.context.scene.fenestra.goals
    goal = goals.climate[goals.climate_index]
    goal.metric = metric
    for key, value in values.items():
        setattr(goal, key, value)
    return goal


def exported():
    export = installed.blender("study.export")
    return export.build(bpy.context)


class Export(unittest.TestCase):
    def setUp(self):
        addon_study.reset()

    def test_climate_goals_are_written_as_the_spec_says(self):
        sensors, near = room()
        f = bpy.context.scene.fenestra
        add_goal('SDA')                                     # the defaults: sDA300/50% >= 55 %
        add_goal('ASE', sensor_group="window", ase_hours=200.0, ase_area=5.0)
        add_goal('EN17037', en17037_level='MEDIUM')
        add_goal('UDI', udi_lower=150.0, udi_upper=2500.0, udi_area=40.0, weight=2.0)
        add_goal('MEAN', sensor_group="window", mean_lux=400.0)
        f.goals.least_glazing = True
        f.goals.source = 'NONE'
        study = exported()
        scene = study.scene
        self.assertEqual(scene["goals"], {
            "climate": [
                {"metric": "sda", "sensors": "all", "illuminance_lux": 300.0, "time_fraction": 0.5,
                 "min_area_fraction": 0.55},
                {"metric": "ase", "sensors": "window", "illuminance_lux": 1000.0, "hours": 200.0,
                 "max_area_fraction": 0.05},
                {"metric": "en17037", "sensors": "all", "level": "medium"},
                {"metric": "udi", "sensors": "all", "lower_lux": 150.0, "upper_lux": 2500.0, "min_area_fraction": 0.4,
                 "weight": 2.0},
                {"metric": "mean", "sensors": "window", "illuminance_lux": 400.0},
            ],
            "least_glazing": True})
        self.assertNotIn("goals", scene["sensors"])      # Climate Goals Only: no goal per sensor
        self.assertEqual(scene["sensors"]["groups"], {"window": sorted(near)})
        # The sensor grid is the only sensor object: its vertices are the study's sensors in order.
        points = np.array(scene["sensors"]["points"])
        self.assertTrue(np.all(points[near, 1] < 2.0) and len(near) < len(points), (len(near), len(points)))
        # The native loader takes it as it stands.
        import fenestra
        path = study.write(os.path.join(OUT, "climate_export"))
        self.assertTrue(fenestra.load_scene(path).has_climate)

        # With a uniform goal too, both are written; the groups follow the objects' order.
        f.goals.source = 'UNIFORM'
        second = sensors.copy()
        second.data = sensors.data.copy()
        second.name = "More Sensors"
        second.location.x += 0.1
        bpy.context.collection.objects.link(second)
        study = exported()
        scene = study.scene
        self.assertEqual(scene["goals"]["uniform"], [{"sensors": "all", "level": 0.5}])
        self.assertEqual(len(scene["goals"]["climate"]), 5)
        self.assertEqual(sorted(name for name, _ in study.sensor_objects), ["Fenestra Sensors", "More Sensors"])
        first = study.sensor_objects[0][1]  # both objects have the group on the same vertices
        self.assertEqual(scene["sensors"]["groups"], {"window": sorted(near) + [first + i for i in sorted(near)]})

        # A goal on a sensor object (a room's grid): the group is all of that object's sensors.
        add_goal('SDA', sensor_group="More Sensors")
        study = exported()
        first = dict(study.sensor_objects)
        start = 0 if study.sensor_objects[0][0] == "More Sensors" else study.sensor_objects[0][1]
        self.assertEqual(study.scene["sensors"]["groups"]["More Sensors"],
                         list(range(start, start + first["More Sensors"])))
        self.assertEqual(study.scene["goals"]["climate"][-1]["sensors"], "More Sensors")

    def test_fields_stay_in_the_spec_ranges(self):
        room()
        goal = add_goal('SDA')
        goal.sda_area, goal.sda_time, goal.sda_lux = 250.0, 0.0, -3.0
        self.assertEqual((goal.sda_area, goal.sda_time, goal.sda_lux), (100.0, 1.0, 1.0))
        goal.ase_hours, goal.ase_lux = 1e5, 1e7
        self.assertEqual((goal.ase_hours, goal.ase_lux), (8760.0, 200000.0))
        goal.udi_upper = 3000.0
        goal.udi_lower = 5000.0  # crosses the upper: the upper moves along
        self.assertLess(goal.udi_lower, goal.udi_upper)
        goal.udi_upper = 50.0    # below the lower: the lower moves down
        self.assertLess(goal.udi_lower, goal.udi_upper)
        goal.weight = 0.0
        self.assertGreater(goal.weight, 0.0)
        # The defaults are the spec's.
        fresh = add_goal('UDI')
        self.assertEqual((fresh.udi_lower, fresh.udi_upper, fresh.udi_area), (100.0, 3000.0, 50.0))
        self.assertEqual((fresh.ase_lux, fresh.ase_hours, fresh.ase_area), (1000.0, 250.0, 10.0))
        self.assertEqual((fresh.sda_lux, fresh.sda_time, fresh.sda_area), (300.0, 50.0, 55.0))
        self.assertEqual(fresh.en17037_level, 'MINIMUM')

    def test_list_add_and_remove(self):
        room()
        goals = bpy.context.scene.fenestra.goals
        bpy.ops.fenestra.climate_goal_add()
        bpy.ops.fenestra.climate_goal_add()
        self.assertEqual([g.metric for g in goals.climate], ['SDA', 'ASE'])  # sDA, then ASE
        goals.climate_index = 0
        self.assertEqual(bpy.ops.fenestra.climate_goal_remove(), {'FINISHED'})
        self.assertEqual([g.metric for g in goals.climate], ['ASE'])
        bpy.ops.fenestra.climate_goal_remove()
        self.assertEqual(len(goals.climate), 0)
        FENESTRA_OT_climate_goal_remove = installed.blender("ui.climate_panel").FENESTRA_OT_climate_goal_remove
        self.assertFalse(FENESTRA_OT_climate_goal_remove.poll(bpy.context))

    def test_only_goals_and_groups_leave_the_contributions_reusable(self):
        study_fingerprint = installed.blender("com.study_fingerprint")
        room()
        add_goal('SDA')
        before = study_fingerprint.contributions_fingerprint(exported())
        add_goal('ASE', sensor_group="window")
        bpy.context.scene.fenestra.goals.least_glazing = True
        after = exported()
        self.assertIn("groups", after.scene["sensors"])
        self.assertEqual(study_fingerprint.contributions_fingerprint(after), before)


class Refused(unittest.TestCase):
    """Each refused by Solve Openings with a message naming the goal and the group; nothing changes."""

    def setUp(self):
        addon_study.reset()

    def assert_refused(self, words):
        before = addon_study.snapshot()
        folder = os.path.join(OUT, "study")
        files = sorted(os.listdir(folder)) if os.path.isdir(folder) else None
        with self.assertRaises(RuntimeError) as failure:  # bpy.ops raises on an ERROR report
            bpy.ops.fenestra.solve_openings()
        for word in words:
            self.assertIn(word, str(failure.exception))
        self.assertEqual(addon_study.snapshot(), before)
        self.assertEqual(sorted(os.listdir(folder)) if os.path.isdir(folder) else None, files)
        return str(failure.exception)

    def test_a_group_that_names_no_sensor(self):
        room()
        add_goal('SDA')
        add_goal('ASE', sensor_group="north")
        message = self.assert_refused(["Climate goal 2 (ASE1000,250 ≤ 10 %)", "Sensor Group 'north' holds no sensor",
                                       "'Fenestra Sensors'"])
        self.assertNotIn("sensors.groups", message)

    def test_an_empty_vertex_group(self):
        sensors, _ = room()
        sensors.vertex_groups.new(name="empty")
        add_goal('SDA', sensor_group="empty")
        self.assert_refused(["Climate goal 1 (sDA300/50% ≥ 55 %)", "Sensor Group 'empty' holds no sensor"])

    def test_a_vertex_group_named_all(self):
        sensors, near = room()
        sensors.vertex_groups.new(name="all").add(near, 1.0, 'REPLACE')
        add_goal('SDA', sensor_group="all")
        self.assert_refused(["Climate goal 1", "cannot be named 'all'"])

    def test_climate_goals_under_another_sky(self):
        room()
        add_goal('SDA')
        bpy.context.scene.fenestra.sky.type = 'CIE_OVERCAST'
        self.assert_refused(["Climate goal 1 (sDA300/50% ≥ 55 %) needs the Climate sky", "Sky > Climate"])

    def test_climate_goals_only_without_a_goal(self):
        room()
        bpy.context.scene.fenestra.goals.source = 'NONE'
        self.assert_refused(["No goals", "Climate Goals Only", "list of climate goals is empty"])


class Solved(unittest.TestCase):
    def setUp(self):
        addon_study.reset()

    def test_a_solve_on_climate_goals_alone(self):
        false_colour = installed.blender("com.false_colour")
        result_display = installed.blender("result.result_display")
        sensors, near = room()
        f = bpy.context.scene.fenestra
        f.goals.source = 'NONE'
        add_goal('SDA', sda_area=50.0)
        add_goal('ASE', sensor_group="window")
        f.goals.least_glazing = True
        s = f.solve
        s.quality, s.paths, s.generations, s.population = 'CUSTOM', 256, 30, 16
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        r = f.results
        self.assertTrue(r.valid and r.climate.valid)
        with open(os.path.join(OUT, "study", "result.json")) as fh:
            result = json.load(fh)
        climate = result["climate"]
        # The panel's figures are the result's.
        self.assertEqual([g.description for g in r.climate.goals], [g["description"] for g in climate["goals"]])
        self.assertEqual(r.climate.goals[0].description, "sDA300/50% >= 50 %")
        self.assertEqual(r.climate.goals[1].description, "ASE1000,250 <= 10 % (window)")
        for item, goal in zip(r.climate.goals, climate["goals"]):
            self.assertAlmostEqual(item.required, goal["required"], places=6)
            self.assertTrue(item.has_achieved)
            self.assertAlmostEqual(item.achieved, goal["achieved"], places=6)
            self.assertEqual(item.met, goal["met"])
            self.assertEqual(item.has_verified, goal["verified"] is not None)
            self.assertEqual(item.has_records, goal["records"] is not None)
            self.assertEqual(item.apart, bool(goal["apart"]))
            # The panel leads with the real cutters' figure where there is one.
            lead = goal["verified"] if goal["verified"] is not None else goal["achieved"]
            self.assertAlmostEqual(item.lead()[0], lead, places=6)
            self.assertEqual(item.lead()[2], "real cutters" if goal["verified"] is not None else "path records")
            self.assertEqual((item.unit, item.sense, item.sensors), (goal["unit"], goal["sense"], len(goal["sensors"])))
        self.assertEqual(r.climate.goals[1].sensors, len(near))
        # Each room the goals name (here the vertex group): its figures of the solved year, the result's.
        self.assertEqual([group["name"] for group in climate["rooms"]], ["window"])
        self.assertEqual([item.name for item in r.climate.rooms], ["window"])
        for item, group in zip(r.climate.rooms, climate["rooms"]):
            self.assertEqual(item.sensors, len(group["sensors"]))
            self.assertAlmostEqual(item.spatial_daylight_autonomy, group["space"]["spatial_daylight_autonomy"], places=6)
            self.assertAlmostEqual(item.annual_sunlight_exposure, group["space"]["annual_sunlight_exposure"], places=6)
            self.assertAlmostEqual(item.mean_illuminance, group["space"]["mean_illuminance_lux"], places=2)
        self.assertEqual(r.climate.all_met, climate["all_met"])
        self.assertEqual(r.climate.unmet.split("\n") if r.climate.unmet else [], climate["unmet"])
        self.assertTrue(r.climate.least_glazing)
        self.assertAlmostEqual(r.climate.glazing_area, climate["glazing_area_m2"], places=4)
        self.assertAlmostEqual(r.climate.domain_area, climate["domain_area_m2"], places=4)
        self.assertGreater(r.climate.glazing_area, 0.0)
        self.assertLessEqual(r.climate.glazing_area, r.climate.domain_area + 1e-6)
        # The space metrics of the solved openings' year, in the Annual Daylight figures.
        annual = f.annual
        self.assertTrue(annual.valid)
        self.assertAlmostEqual(annual.spatial_daylight_autonomy, climate["space"]["spatial_daylight_autonomy"], places=6)
        self.assertAlmostEqual(annual.mean_illuminance, climate["space"]["mean_illuminance_lux"], places=3)
        self.assertEqual(annual.openings, len(result["openings"]))
        self.assertEqual(len(annual.sensors), len(r.sensors))
        # Per sensor, and the false colour: DA of the solve in percent, 0 to 100.
        da = np.array(climate["per_sensor"]["daylight_autonomy"])
        stored = np.zeros(len(r.sensors))
        r.sensors.foreach_get("daylight_autonomy", stored)
        np.testing.assert_allclose(stored, da, atol=1e-6)
        self.assertEqual(f.display.false_colour, 'CLIMATE_DA')
        scale, shown = result_display.current(bpy.context)
        self.assertEqual((scale.quantity, scale.top, scale.units), ('CLIMATE_DA', 100.0, "%"))
        self.assertIn("Daylight autonomy DA300", scale.title)
        np.testing.assert_allclose(shown["Fenestra Sensors"], 100.0 * da, atol=1e-4)
        np.testing.assert_allclose(scale.colours(shown["Fenestra Sensors"]), false_colour.Scale("DA", 100.0).colours(100 * da),
                                   atol=1e-6)
        for quantity, key, factor in (('CLIMATE_MEAN', "mean_illuminance_lux", 1.0), ('CLIMATE_ASE_HOURS', "ase_hours", 1.0)):
            f.display.false_colour = quantity
            scale, shown = result_display.current(bpy.context)
            np.testing.assert_allclose(shown["Fenestra Sensors"], factor * np.array(climate["per_sensor"][key]), rtol=1e-5)
            self.assertGreaterEqual(scale.top, np.max(shown["Fenestra Sensors"]))
        FENESTRA_PT_climate_results = installed.blender("ui.climate_panel").FENESTRA_PT_climate_results
        self.assertTrue(FENESTRA_PT_climate_results.poll(bpy.context))

        # Each trade-off says whether its openings meet the climate goals (the core's figures).
        for item, entry in zip(r.tradeoffs, result["tradeoffs"]):
            self.assertIsNotNone(entry["climate"])
            self.assertEqual(len(entry["climate"]["achieved"]), len(climate["goals"]))
            self.assertEqual(item.climate_met, int(entry["climate"]["all_met"]))
        self.assertEqual(result["tradeoffs"][0]["climate"]["achieved"], [g["achieved"] for g in climate["goals"]])
        # Each trade-off's row says its glazing and each goal's figure, met or not.
        climate_results = installed.blender("result.climate_results")
        for item, entry in zip(r.tradeoffs, result["tradeoffs"]):
            self.assertEqual(item.climate_line.count(" met"), len(climate["goals"]), item.climate_line)
            # The panel's rows: a goal each, its check mark or cross from the core's verdict.
            rows = climate_results.tradeoff_rows(item.climate_line)
            self.assertEqual([met for _, met in rows], entry["climate"]["met"], rows)
            self.assertFalse(any(text.endswith("met") for text, _ in rows), rows)
            # Each row starts with the metric and its figure; the room's name follows.
            for (text, _), goal, achieved in zip(rows, climate["goals"], entry["climate"]["achieved"]):
                self.assertTrue(text.startswith("%s %.1f %%" % (climate_results.SHORT[goal["metric"]],
                                                                100 * achieved)), (text, goal))
        # A room named with ", " still gives one row per goal.
        line = climate_results.tradeoff_line(
            {"goals": [{"metric": "sda", "unit": "fraction", "description": "sDA300/50% >= 50 % (Room, north)"},
                       {"metric": "ase", "unit": "fraction", "description": "ASE1000,250 <= 10 % (Room, north)"}]},
            {"climate": {"achieved": [0.6, 0.2], "met": [True, False]}})
        self.assertEqual(climate_results.tradeoff_rows(line),
                         [("sDA 60.0 % (Room,north)", True), ("ASE 20.0 % (Room,north)", False)])
        # A trade-off shown: the climate goals' figures are its own, with no lux error table or
        # element count (its openings are rectangles); the rooms and the year go with the answer.
        # (A second trade-off, with other figures, is put in result.json when the solve found none.)
        if len(r.tradeoffs) < 2:
            other = json.loads(json.dumps(result["tradeoffs"][0]))
            other["climate"]["achieved"] = [0.5 * a for a in other["climate"]["achieved"]]
            other["climate"]["met"] = [False for _ in other["climate"]["achieved"]]
            other["climate"]["all_met"] = False
            result["tradeoffs"].append(other)
            with open(os.path.join(OUT, "study", "result.json"), "w") as fh:
                json.dump(result, fh)
            r.tradeoffs.add()
        f.display.false_colour = 'CLIMATE_DA'
        self.assertEqual(bpy.ops.fenestra.apply_tradeoff(index=1), {'FINISHED'})
        entry = result["tradeoffs"][1]["climate"]
        self.assertTrue(r.climate.valid and r.climate.tradeoff)
        self.assertEqual([round(g.lead()[0], 9) for g in r.climate.goals], [round(a, 9) for a in entry["achieved"]])
        self.assertEqual([g.lead()[1] for g in r.climate.goals], entry["met"])
        self.assertEqual((len(r.climate.rooms), r.open_elements), (0, -1))
        self.assertEqual(f.display.false_colour, 'CLIMATE_DA')
        self.assertEqual(bpy.ops.fenestra.apply_tradeoff(index=0), {'FINISHED'})
        self.assertTrue(r.climate.valid)
        self.assertFalse(r.climate.tradeoff)
        self.assertGreaterEqual(r.open_elements, 0)
        self.assertEqual(f.display.false_colour, 'CLIMATE_DA')

        # Saved and reloaded: the goals and the figures stay.
        path = os.path.join(OUT, "climate_solved.blend")
        bpy.ops.wm.save_as_mainfile(filepath=path)
        bpy.ops.wm.open_mainfile(filepath=path)
        f = bpy.context.scene.fenestra
        self.assertEqual([g.metric for g in f.goals.climate], ['SDA', 'ASE'])
        self.assertEqual(f.goals.climate[1].sensor_group, "window")
        self.assertTrue(f.results.climate.valid)
        self.assertEqual(len(f.results.climate.goals), 2)

        # Evaluate path-traces the cutters as they stand: the solve's climate figures are no longer theirs.
        self.assertEqual(bpy.ops.fenestra.evaluate_openings(), {'FINISHED'})
        self.assertFalse(f.results.climate.valid)
        self.assertEqual(f.display.false_colour, 'ACHIEVED')
        self.assertTrue(f.results.evaluated)

        # Clear Results forgets them.
        self.assertEqual(bpy.ops.fenestra.clear_results(), {'FINISHED'})
        self.assertFalse(f.results.climate.valid)
        self.assertEqual(len(f.results.climate.goals), 0)
        self.assertIsNone(result_display.current(bpy.context))


def floor(names):
    """Rooms side by side (addon_study's box, 0.3 m apart), each lit by its south wall, each with
    its own sensor grid named "<room> sensors". Returns the grids."""
    f = bpy.context.scene.fenestra
    f.sensor_height, f.sensor_spacing = 0.8, 1.0
    grids = []
    for i, name in enumerate(names):
        room = addon_study.box_room()
        room.name = name
        room.location.x = (addon_study.ROOM[0] + 0.3) * i
        bpy.context.view_layer.update()
        addon_study.mark_south_wall(room)
        addon_study.select_only(room)
        before = set(bpy.data.objects)
        assert bpy.ops.fenestra.add_sensor_grid() == {'FINISHED'}
        (grid,) = set(bpy.data.objects) - before
        grid.name = name + " sensors"
        grids.append(grid)
    addon_study.climate()
    f.solve.wall_thickness, f.solve.element_size = 0.0, 0.5
    s = f.solve
    s.quality, s.paths, s.generations, s.population, s.seed = 'CUSTOM', 256, 30, 16, 3
    s.study_directory = os.path.join(OUT, "study")
    return grids


class Floor(unittest.TestCase):
    """A floor of rooms, a sensor grid each, sDA and ASE goals per room and the least glazing: the
    export names each room's sensors, and the solve's Rooms figures are result.json's."""

    def setUp(self):
        addon_study.reset()

    def test_a_floor_of_rooms_solves_with_goals_per_room(self):
        names = ("West office", "Meeting", "East office")
        grids = floor(names)
        f = bpy.context.scene.fenestra
        f.goals.source = 'NONE'
        for grid in grids:
            add_goal('SDA', sda_area=50.0, sensor_group=grid.name)
            add_goal('ASE', sensor_group=grid.name)
        f.goals.least_glazing = True
        # Each goal's sensors are its room's grid, in the study's order of sensors.
        scene = exported().scene
        sensors = scene["sensors"]["points"]
        for grid in grids:
            points = [tuple(round(c, 4) for c in grid.matrix_world @ v.co) for v in grid.data.vertices]
            group = scene["sensors"]["groups"][grid.name]
            self.assertEqual(sorted(tuple(round(c, 4) for c in sensors[i]) for i in group), sorted(points))
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        r = f.results
        self.assertTrue(r.valid and r.climate.valid)
        with open(os.path.join(OUT, "study", "result.json")) as fh:
            climate = json.load(fh)["climate"]
        self.assertEqual([g["description"] for g in climate["goals"]],
                         [d % (name + " sensors") for name in names
                          for d in ("sDA300/50%% >= 50 %% (%s)", "ASE1000,250 <= 10 %% (%s)")])
        # One row of the Rooms box per grid, with the result's figures of that room.
        self.assertEqual([item.name for item in r.climate.rooms], [g.name for g in grids])
        self.assertEqual([room["name"] for room in climate["rooms"]], [g.name for g in grids])
        for item, room, grid in zip(r.climate.rooms, climate["rooms"], grids):
            self.assertEqual(item.sensors, len(grid.data.vertices))
            self.assertEqual(item.sensors, len(room["sensors"]))
            self.assertAlmostEqual(item.spatial_daylight_autonomy, room["space"]["spatial_daylight_autonomy"], places=6)
            self.assertAlmostEqual(item.annual_sunlight_exposure, room["space"]["annual_sunlight_exposure"], places=6)
            self.assertAlmostEqual(item.mean_illuminance, room["space"]["mean_illuminance_lux"], places=2)
        # The floor's figures are all its sensors'.
        self.assertEqual(len(r.sensors), sum(len(g.data.vertices) for g in grids))
        self.assertAlmostEqual(f.annual.spatial_daylight_autonomy, climate["space"]["spatial_daylight_autonomy"],
                               places=6)
        # Every room got an opening in its own south wall (each room's goals ask for light).
        cutters = addon_study.cutters()
        for i, name in enumerate(names):
            x0 = (addon_study.ROOM[0] + 0.3) * i
            mine = [c for c in cutters if x0 <= c.matrix_world.translation.x <= x0 + addon_study.ROOM[0]]
            self.assertTrue(mine, "no opening in %s's wall" % name)


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    addon_study.enable()
    result = unittest.main(argv=[sys.argv[0]], exit=False, verbosity=2).result
    sys.exit(0 if result.wasSuccessful() else 1)
