"""The Blender add-on end to end, inside Blender (run by test_blender_addon.py):

    blender -b --factory-startup --python-exit-code 1 --python addon_study.py -- OUT_DIR

The add-on must be on Blender's add-on path (BLENDER_USER_SCRIPTS/addons/fenestra)."""

import json
import os
import shutil
import sys
import unittest

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import installed  # noqa: E402

OUT = sys.argv[sys.argv.index("--") + 1] if "--" in sys.argv else "/tmp/fenestra_addon_test"
ROOM = (4.0, 4.0, 2.7)
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CHICAGO = os.path.join(ROOT, "examples", "weather", "USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw")


def enable():
    installed.enable()
    assert hasattr(bpy.types.Scene, "fenestra"), "the add-on did not register"


def disable():
    installed.disable()


def reset():
    bpy.ops.wm.read_homefile(use_empty=True)
    enable()


def box_room():
    """A closed 4 x 4 x 2.7 m box; face 2 is the south wall (y = 0)."""
    x, y, z = ROOM
    verts = [(0, 0, 0), (x, 0, 0), (x, y, 0), (0, y, 0), (0, 0, z), (x, 0, z), (x, y, z), (0, y, z)]
    faces = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    mesh = bpy.data.meshes.new("Room")
    mesh.from_pydata(verts, [], faces)
    room = bpy.data.objects.new("Room", mesh)
    bpy.context.collection.objects.link(room)
    material = bpy.data.materials.new("Plaster")
    material.use_nodes = True
    material.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.6, 0.6, 0.6, 1)
    material.node_tree.nodes["Principled BSDF"].inputs["Roughness"].default_value = 1.0
    mesh.materials.append(material)
    return room


def select_only(obj):
    for o in bpy.context.view_layer.objects:
        o.select_set(False)
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj


def mark_south_wall(room):
    select_only(room)
    bpy.ops.object.mode_set(mode='EDIT')
    bpy.ops.mesh.select_all(action='DESELECT')
    bpy.ops.object.mode_set(mode='OBJECT')
    room.data.polygons[2].select = True
    bpy.ops.object.mode_set(mode='EDIT')
    assert bpy.ops.fenestra.mark_domain() == {'FINISHED'}
    bpy.ops.object.mode_set(mode='OBJECT')


def study(sensors=True, domain=True):
    """The whole setup, through the add-on's operators and settings."""
    room = box_room()
    if domain:
        mark_south_wall(room)
    f = bpy.context.scene.fenestra
    f.sensor_height, f.sensor_spacing = 0.8, 1.0
    if sensors:
        select_only(room)
        assert bpy.ops.fenestra.add_sensor_grid() == {'FINISHED'}
    f.goals.source, f.goals.units, f.goals.level = 'UNIFORM', 'NORMALIZED', 0.5
    f.sky.type, f.sky.horizontal_illuminance = 'UNIFORM', 10000.0
    s = f.solve
    s.element_size, s.wall_thickness = 0.5, 0.2
    s.quality, s.paths, s.generations, s.population, s.seed = 'CUSTOM', 512, 40, 16, 3
    s.study_directory = os.path.join(OUT, "study")
    return room


def cutters():
    return [o for o in bpy.data.objects if o.fenestra.is_opening]


def snapshot():
    """What a failed solve must leave alone."""
    return (sorted(o.name for o in bpy.data.objects), sorted(c.name for c in bpy.data.collections),
            sorted((o.name, m.name) for o in bpy.data.objects for m in o.modifiers),
            bpy.context.scene.fenestra.results.valid, len(bpy.data.meshes))


class Registration(unittest.TestCase):
    def test_register_unregister_twice(self):
        for _ in range(2):
            enable()
            self.assertTrue(hasattr(bpy.types.Scene, "fenestra"))
            self.assertTrue(hasattr(bpy.ops.fenestra, "solve_openings"))
            self.assertIn("FENESTRA_PT_main", dir(bpy.types))
            # The Fenestra menu in the Object menu (F3 finds its commands), gone with the add-on.
            self.assertIn("FENESTRA_MT_study", dir(bpy.types))
            disable()
            self.assertFalse(hasattr(bpy.types.Scene, "fenestra"))
            self.assertNotIn("FENESTRA_MT_study", dir(bpy.types))
        enable()

    def test_the_progress_bar_tells_what_it_is(self):
        """Its tooltip is its description (a read-only property's says "Disabled: This property is
        for internal use only"); dragging it changes nothing."""
        wm = bpy.context.window_manager
        prop = wm.bl_rna.properties["fenestra_solve_progress"]
        self.assertFalse(prop.is_readonly)
        self.assertTrue(prop.description.startswith("How much of the solve's current stage is done"))
        wm.fenestra_solve_progress = 50.0
        self.assertEqual(wm.fenestra_solve_progress, 0.0)  # no solve runs


class Solve(unittest.TestCase):
    def setUp(self):
        reset()

    def test_solve_cuts_openings_in_the_south_wall(self):
        room = study()
        self.assertEqual(bpy.context.scene.fenestra.domain_faces, 1)
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        found = cutters()
        self.assertGreaterEqual(len(found), 1)
        self.assertEqual(len(found), bpy.context.scene.fenestra.results.openings)
        for obj in found:
            self.assertEqual(obj.display_type, 'WIRE')
            corners = np.array([obj.matrix_world @ v.co for v in obj.data.vertices])
            lo, hi = corners.min(axis=0), corners.max(axis=0)
            self.assertTrue(np.all(hi - lo > 0), (lo, hi))
            # Through the south wall plane y = 0, away from the sensors (y > 0) by the thickness.
            self.assertLess(lo[1], -0.2 + 1e-6)
            self.assertGreater(hi[1], 0.0)
            self.assertLess(hi[1], 0.1)
            self.assertTrue(-1e-6 <= lo[0] and hi[0] <= ROOM[0] + 1e-6, (lo, hi))
            self.assertTrue(-1e-6 <= lo[2] and hi[2] <= ROOM[2] + 1e-6, (lo, hi))
        self.assertIn("Fenestra Openings", [m.name for m in room.modifiers])
        r = bpy.context.scene.fenestra.results
        self.assertTrue(r.valid)
        self.assertLess(r.relative_rms, 1.0)
        sensors = bpy.data.objects["Fenestra Sensors"]
        achieved = sensors.data.attributes["fenestra_achieved"]
        values = np.zeros(len(achieved.data))
        achieved.data.foreach_get("value", values)
        self.assertTrue(np.all(values > 0))
        self.assertEqual(len(r.sensors), len(values))
        # The study folder re-runs with the command line.
        scene_json = json.load(open(os.path.join(OUT, "study", "scene.json")))
        self.assertEqual(scene_json["opening_domain"]["groups"], ["Room.domain"])
        self.assertTrue(os.path.exists(os.path.join(OUT, "study", "result.json")))

        # Solving again replaces the results; the domain is read uncut.
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        self.assertEqual(len(cutters()), bpy.context.scene.fenestra.results.openings)
        self.assertEqual(len(bpy.data.collections["Fenestra Openings"].objects), len(cutters()))
        self.assertEqual([m.name for m in room.modifiers].count("Fenestra Openings"), 1)
        self.assertEqual(json.load(open(os.path.join(OUT, "study", "scene.json")))["opening_domain"]["groups"],
                         ["Room.domain"])

    def test_too_few_paths_for_the_elements_warns_in_the_results(self):
        study()
        solve = bpy.context.scene.fenestra.solve
        solve.element_size, solve.quality = 0.1, 'CUSTOM'
        solve.paths, solve.generations, solve.population = 64, 10, 16
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        r = bpy.context.scene.fenestra.results
        self.assertIn("direct samples for", r.warnings)
        self.assertGreaterEqual(r.verified_rms, 0.0)
        # Enough paths for 0.25 m elements: no warning left from the solve before.
        solve.element_size, solve.paths = 0.25, 2048
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        self.assertNotIn("direct samples for", bpy.context.scene.fenestra.results.warnings)

    def test_constraints_reach_the_study_when_set(self):
        native = installed.blender("com.native")
        study()
        path = os.path.join(OUT, "study", "scene.json")
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        self.assertNotIn("constraints", json.load(open(path))["solver"])  # none set: none written
        bpy.context.scene.fenestra.solve.constraints.max_openings = 1
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        solver = json.load(open(path))["solver"]
        if native.accepts_constraints():
            self.assertEqual(solver["constraints"], {"max_openings": 1})
            self.assertLessEqual(bpy.context.scene.fenestra.results.openings, 1)
        else:
            self.assertNotIn("constraints", solver)

    def test_automatic_constraints_show_greyed_and_choices_reach_the_study(self):
        import fenestra
        constraint_defaults = installed.blender("ui.constraint_defaults")
        properties = installed.blender("props.properties")
        study()
        c = bpy.context.scene.fenestra.solve.constraints
        # Every key left at 0 shows the solver's own automatic value.
        shown = constraint_defaults.automatic_values(c)
        automatic = fenestra.automatic_constraints()
        self.assertEqual(set(shown), set(automatic))
        self.assertEqual(shown["min_width"], "auto %g m" % automatic["min_width"][0])
        # With climate goals, openings of at least 1 m2; sills and heads aligned where cheap.
        self.assertEqual(constraint_defaults.automatic_values(c, climate=True)["min_area"], "auto 1 m\u00b2")
        self.assertEqual(constraint_defaults.aligned_by_default(c), ("align_sills", "align_heads"))
        c.align_heads = True  # chosen: a rule, not a default
        self.assertEqual(constraint_defaults.aligned_by_default(c), ())
        c.align_heads = False
        c.min_width = 0.8  # set: no longer automatic
        self.assertNotIn("min_width", constraint_defaults.automatic_values(c))
        c.full_height = True
        self.assertNotIn("sill_min", constraint_defaults.automatic_values(c))
        self.assertEqual(constraint_defaults.aligned_by_default(c), ())
        c.catalogue = 'residential'
        self.assertNotIn("min_height", constraint_defaults.automatic_values(c))
        c.automatic = False
        self.assertEqual(constraint_defaults.automatic_values(c), {})
        # The add-on's catalogues are the solver's.
        names = {k for k, _, _ in properties.CATALOGUES if k != 'NONE'}
        self.assertEqual(names, set(fenestra.catalogues()))
        path = os.path.join(OUT, "study", "scene.json")
        c.min_width = 0.0
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        self.assertEqual(json.load(open(path))["solver"]["constraints"],
                         {"automatic": False, "full_height": True, "catalogue": "residential"})
        sizes = fenestra.catalogues()["residential"]["walls"]
        result = json.load(open(os.path.join(OUT, "study", "result.json")))
        self.assertTrue(result["openings"] and result["constraints_met"])
        for o in result["openings"]:
            self.assertTrue(any(abs(o["width"] - w) < 1e-3 and abs(o["height"] - h) < 1e-3 for w, h in sizes), o)
        self.assertEqual(len(cutters()), len(result["openings"]))

    def test_facade_composition_reaches_the_study_and_bad_sill_heights_are_refused(self):
        study()
        c = bpy.context.scene.fenestra.solve.constraints
        c.align_sills, c.same_type_in_row, c.sill_heights = True, True, " 0.9 m, 1.2;"
        path = os.path.join(OUT, "study", "scene.json")
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        self.assertEqual(json.load(open(path))["solver"]["constraints"],
                         {"align_sills": True, "same_type_in_row": True, "sill_heights": [0.9, 1.2]})
        result = json.load(open(os.path.join(OUT, "study", "result.json")))
        self.assertTrue(result["openings"] and result["constraints_met"], result["constraint_violations"])
        self.assertEqual([s["rule"] for s in result["composition"]][:1], ["align_sills"])
        sills = {round(min(p[2] for p in o["corners"]), 3) for o in result["openings"]}
        self.assertEqual(len(sills), 1, sills)  # aligned
        before = os.path.getmtime(path)
        c.sill_heights = "0.9, high"
        with self.assertRaises(RuntimeError) as caught:  # the operator's error report
            bpy.ops.fenestra.solve_openings()
        self.assertIn("Sill Heights: 'high' is not a height", str(caught.exception))
        self.assertEqual(os.path.getmtime(path), before)  # the study is not rewritten

    def test_a_tradeoff_replaces_the_cutters_without_solving_again(self):
        study()
        c = bpy.context.scene.fenestra.solve.constraints
        c.automatic, c.max_width = False, 1.0  # several openings to light the room
        bpy.context.scene.fenestra.goals.level = 0.9
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        r = bpy.context.scene.fenestra.results
        result = json.load(open(os.path.join(OUT, "study", "result.json")))
        entries = result["tradeoffs"]
        self.assertGreater(len(entries), 1, result["openings"])
        self.assertEqual([t.openings for t in r.tradeoffs], [e["openings_count"] for e in entries])
        last = len(entries) - 1
        self.assertEqual(bpy.ops.fenestra.apply_tradeoff(index=last), {'FINISHED'})
        self.assertEqual(len(cutters()), entries[last]["openings_count"])
        self.assertEqual(r.tradeoff_shown, last)
        self.assertAlmostEqual(r.relative_rms, entries[last]["error"]["relative_rms"], places=6)
        self.assertLess(r.verified_rms, 0.0)  # the check was of the answer, not of this one
        achieved = [s.achieved for s in r.sensors]
        self.assertTrue(np.allclose(achieved, entries[last]["predicted"], rtol=1e-5))
        # Back to the answer.
        self.assertEqual(bpy.ops.fenestra.apply_tradeoff(index=0), {'FINISHED'})
        self.assertEqual(len(cutters()), len(result["openings"]))
        self.assertEqual(len(r.tradeoffs), len(entries))

    def test_settings_survive_save_and_reload(self):
        study()
        f = bpy.context.scene.fenestra
        f.sky.type, f.sky.latitude, f.solve.constraints.max_openings = 'PREETHAM', 37.98, 3
        f.goals.use_min, f.goals.min = True, 0.25
        path = os.path.join(OUT, "settings.blend")
        bpy.ops.wm.save_as_mainfile(filepath=path)
        bpy.ops.wm.read_homefile(use_empty=True)
        bpy.ops.wm.open_mainfile(filepath=path)
        f = bpy.context.scene.fenestra
        self.assertEqual(f.sky.type, 'PREETHAM')
        self.assertAlmostEqual(f.sky.latitude, 37.98, places=4)
        self.assertEqual(f.solve.constraints.max_openings, 3)
        self.assertEqual((f.solve.quality, f.solve.paths, f.solve.element_size), ('CUSTOM', 512, 0.5))
        self.assertTrue(f.goals.use_min)
        self.assertTrue(bpy.data.objects["Fenestra Sensors"].fenestra.is_sensor)
        flags = np.zeros(6, bool)
        bpy.data.objects["Room"].data.attributes["fenestra_domain"].data.foreach_get("value", flags)
        self.assertEqual(flags.tolist(), [False, False, True, False, False, False])


def climate(weather=CHICAGO):
    """The study's sky: a year of Chicago weather, 08:00-18:00."""
    sky = bpy.context.scene.fenestra.sky
    sky.type, sky.weather_file = 'CLIMATE', weather
    return sky


def annual_folder():
    return os.path.join(OUT, "study", "annual")


class ClimateDaylight(unittest.TestCase):
    """The climate sky exported, Annual Daylight on a room with one window, bad weather files refused."""

    def setUp(self):
        reset()

    def test_climate_sky_is_exported(self):
        export = installed.blender("study.export")
        study()
        sky = climate()
        sky.occupied_start, sky.occupied_end, sky.patches, sky.ground_reflectance = 7.5, 17.0, '2', 0.3
        sky.use_sun_position, sky.north_offset = False, np.radians(30.0)
        # A path relative to the .blend file's folder ('//') is written absolute: the study folder may move.
        bpy.ops.wm.save_as_mainfile(filepath=os.path.join(OUT, "climate.blend"))
        sky = climate(bpy.path.relpath(CHICAGO))
        self.assertTrue(sky.weather_file.startswith("//"), sky.weather_file)
        written = export.build(bpy.context).scene["sky"]
        self.assertAlmostEqual(written.pop("north_offset_deg"), 30.0, places=4)
        self.assertAlmostEqual(written.pop("ground_reflectance"), 0.3, places=6)
        self.assertEqual(written, {"type": "climate", "weather": os.path.abspath(CHICAGO), "patches": 2,
                                   "occupied": ["07:30", "17:00"]})
        # The native loader takes it (the sky matrix of the year and the cumulative sky are built).
        import fenestra
        study_ = export.build(bpy.context)
        path = study_.write(os.path.join(OUT, "climate_study"))
        self.assertTrue(fenestra.load_scene(path).has_climate)

    def test_annual_daylight_of_a_room_with_one_window(self):
        import fenestra
        result_display = installed.blender("result.result_display")
        study()
        climate()
        f = bpy.context.scene.fenestra
        f.solve.constraints.max_openings, f.solve.constraints.max_width = 1, 1.5
        f.solve.wall_thickness = 0.0  # the box's single-face wall: any edge counts (a thick wall: below)
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})  # under the occupied hours' mean sky
        self.assertEqual(len(cutters()), 1)
        self.assertEqual(bpy.ops.fenestra.annual_daylight(), {'FINISHED'})
        a = f.annual
        self.assertTrue(a.valid)
        self.assertTrue(a.reused)  # the solve's contributions: only the openings are new
        self.assertEqual((a.hours, a.occupied_hours, a.occupied_period, a.openings), (8760, 3650, "08:00-18:00", 1))
        self.assertEqual(a.weather, os.path.basename(CHICAGO))
        # The figures are the native core's summary, written to annual/annual.json.
        summary = json.load(open(os.path.join(annual_folder(), "annual.json")))
        space = summary["space"]
        self.assertAlmostEqual(a.spatial_daylight_autonomy, space["spatial_daylight_autonomy"], places=6)
        self.assertAlmostEqual(a.daylight_autonomy, space["daylight_autonomy"], places=6)
        self.assertAlmostEqual(a.mean_illuminance, space["mean_illuminance_lux"], places=2)
        self.assertAlmostEqual(a.annual_sunlight_exposure, space["annual_sunlight_exposure"], places=6)
        self.assertEqual(a.ase_passes, space["ase_passes"])
        self.assertEqual([(x.level, x.passed) for x in a.sda_levels],
                         [(as_stored(x["level"]), x["passed"]) for x in space["sda_levels"]])
        self.assertEqual(len(a.udi), 4)
        self.assertAlmostEqual(sum(b.space_fraction for b in a.udi), 1.0, places=5)
        self.assertEqual(a.en17037_level, space["en17037"]["level_reached"] or "")
        self.assertGreater(a.mean_illuminance, 50.0)  # a room with a window in Chicago
        # The run re-runs without Blender: its study, openings and outputs side by side.
        folder = annual_folder()
        self.assertEqual(sorted(os.listdir(folder)),
                         ["annual.json", "annual.npz", "openings.json", "scene.json", "scene.obj"])
        self.assertEqual(json.load(open(os.path.join(folder, "scene.json")))["sky"]["type"], "climate")
        self.assertEqual(len(json.load(open(os.path.join(folder, "openings.json")))["openings"]), 1)
        with np.load(os.path.join(folder, "annual.npz")) as arrays:
            self.assertEqual(arrays["illuminance"].shape, (len(a.sensors), 8760))
        # Per sensor, by object and vertex, and in false colour (DA in percent by default).
        sensors = bpy.data.objects["Fenestra Sensors"]
        self.assertEqual(len(a.sensors), len(sensors.data.vertices))
        self.assertEqual(f.display.false_colour, 'ANNUAL')
        scale, shown = result_display.current(bpy.context)
        da = np.array(summary["per_sensor"]["daylight_autonomy"]) * 100.0
        self.assertTrue(np.allclose(shown["Fenestra Sensors"], da, atol=1e-4))
        self.assertEqual(scale.top, 100.0)
        self.assertIn("Daylight autonomy", scale.title)
        colours = scale.colours(shown["Fenestra Sensors"])
        self.assertEqual(colours.shape, (len(da), 4))
        self.assertGreater(len(np.unique(np.round(colours, 3), axis=0)), 1)  # near and far from the window
        f.display.annual_metric = 'MEAN'
        scale, shown = result_display.current(bpy.context)
        self.assertTrue(np.allclose(shown["Fenestra Sensors"], summary["per_sensor"]["mean_illuminance_lux"], rtol=1e-5))
        self.assertEqual(scale.units, "lx")
        f.display.annual_metric = 'ASE_HOURS'
        self.assertTrue(np.allclose(result_display.current(bpy.context)[1]["Fenestra Sensors"],
                                    summary["per_sensor"]["ase_hours"]))
        # Moving the window and running again reuses the light paths; the figures follow the window.
        before = [s.mean_illuminance for s in a.sensors]
        window = cutters()[0]
        window.location.x += 0.8 if window.location.x < ROOM[0] / 2 else -0.8
        self.assertEqual(bpy.ops.fenestra.annual_daylight(), {'FINISHED'})
        self.assertTrue(a.reused)
        self.assertFalse(np.allclose(before, [s.mean_illuminance for s in a.sensors]))
        # Clear Results forgets the run with the openings it was of.
        self.assertEqual(bpy.ops.fenestra.clear_results(), {'FINISHED'})
        self.assertFalse(a.valid)
        self.assertEqual(len(a.sensors), 0)

    def test_a_thick_walls_openings_off_the_element_grid_are_traced_really_cut(self):
        """The path records cannot count an edge between the element grid's lines of a thick wall:
        the year is traced with the openings cut instead of refused, and the panel says so."""
        study()  # a 0.2 m wall
        climate()
        f = bpy.context.scene.fenestra
        f.solve.constraints.max_openings = 1
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})  # its edges moved off the grid
        self.assertEqual(bpy.ops.fenestra.annual_daylight(), {'FINISHED'})
        a = f.annual
        self.assertTrue(a.valid)
        self.assertFalse(a.reused)  # traced anew, the openings cut
        self.assertTrue(a.note.startswith("Traced with the openings really cut"), a.note)
        self.assertGreater(a.mean_illuminance, 50.0)
        self.assertEqual(len(json.load(open(os.path.join(annual_folder(), "openings.json")))["openings"]), 1)
        f.solve.edges_on_grid = True
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        self.assertIs(json.load(open(os.path.join(OUT, "study", "scene.json")))["solver"]["refine_edges"], False)
        self.assertEqual(bpy.ops.fenestra.annual_daylight(), {'FINISHED'})
        self.assertTrue(f.annual.valid and f.annual.reused)
        self.assertEqual(f.annual.note, "")  # the records' year, as they count these openings

    def test_bad_weather_files_are_refused_and_nothing_is_written(self):
        study()
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})  # a study folder to keep
        shutil.rmtree(annual_folder(), ignore_errors=True)  # an earlier test's run
        scene_json = os.path.join(OUT, "study", "scene.json")
        before_study = open(scene_json).read()
        other = os.path.join(OUT, "notes.txt")
        open(other, "w").write("not weather")
        for weather, words in ((os.path.join(OUT, "missing.epw"), ["Weather file 'missing.epw' not found", "Sky > Weather File"]),
                               (other, ["'notes.txt' is not a weather file", ".epw"]),
                               ("", ["Choose a weather file"])):
            climate(weather)
            shown = snapshot()
            for operator in (bpy.ops.fenestra.annual_daylight, bpy.ops.fenestra.solve_openings):
                with self.assertRaises(RuntimeError) as failure:
                    operator()
                for word in words:
                    self.assertIn(word, str(failure.exception))
                self.assertEqual(snapshot(), shown)
            self.assertFalse(os.path.exists(annual_folder()))
            self.assertEqual(os.listdir(os.path.join(OUT, "study")).count("annual"), 0)
            self.assertEqual(open(scene_json).read(), before_study)
            self.assertFalse(bpy.context.scene.fenestra.annual.valid)
        # The occupied period must lie within a day.
        sky = climate()
        sky.occupied_start, sky.occupied_end = 19.0, 7.0
        with self.assertRaises(RuntimeError) as failure:
            bpy.ops.fenestra.annual_daylight()
        self.assertIn("Occupied hours: the start (19:00) must be before the end (07:00)", str(failure.exception))
        self.assertFalse(os.path.exists(annual_folder()))
        # Another sky: the operator is not available, and says why.
        bpy.context.scene.fenestra.sky.type = 'UNIFORM'
        FENESTRA_OT_annual_daylight = installed.blender("ui.annual_operator").FENESTRA_OT_annual_daylight
        self.assertFalse(FENESTRA_OT_annual_daylight.poll(bpy.context))


def as_stored(value):
    """A float as Blender's single-precision property holds it."""
    return float(np.float32(value))


class BadSetups(unittest.TestCase):
    """Each fails with an ERROR report naming the problem and leaves the file as it was."""

    def setUp(self):
        reset()

    def assert_refused(self, words):
        before = snapshot()
        with self.assertRaises(RuntimeError) as failure:  # bpy.ops raises on an ERROR report
            bpy.ops.fenestra.solve_openings()
        message = str(failure.exception)
        for word in words:
            self.assertIn(word, message)
        self.assertEqual(snapshot(), before)

    def test_no_domain(self):
        study(domain=False)
        self.assert_refused(["No opening domain"])

    def test_no_sensors(self):
        study(sensors=False)
        self.assert_refused(["No sensors"])

    def test_sensor_without_vertices(self):
        study()
        empty = bpy.data.objects.new("Empty Sensors", bpy.data.meshes.new("Empty Sensors"))
        empty.fenestra.is_sensor = True
        bpy.context.collection.objects.link(empty)
        self.assert_refused(["Empty Sensors", "no vertices"])

    def test_no_goals(self):
        study()
        bpy.context.scene.fenestra.goals.source = 'ATTRIBUTE'
        sensors = bpy.data.objects["Fenestra Sensors"].data
        sensors.color_attributes.remove(sensors.color_attributes["fenestra_goal"])
        self.assert_refused(["No goals", "fenestra_goal"])

    def test_element_size_larger_than_the_wall(self):
        study()
        bpy.context.scene.fenestra.solve.element_size = 50.0
        self.assert_refused(["Element Size 50 m is too large", "the domain faces of 'Room'"])

    def test_element_size_too_small(self):
        study()
        bpy.context.scene.fenestra.solve.element_size = 0.001
        self.assert_refused(["too small"])

    def test_refused_by_the_cost_model_memory(self):
        # docs/cost.md: refused before the worker thread starts, naming the figure and the setting
        study()
        solve = bpy.context.scene.fenestra.solve
        solve.quality, solve.paths = 'CUSTOM', 2 ** 24
        self.assert_refused(["paths per sensor", "needs", "fewer paths"])

    def test_refused_by_the_cost_model_time(self):
        study()
        solve = bpy.context.scene.fenestra.solve
        solve.quality, solve.generations = 'CUSTOM', 10 ** 7
        self.assert_refused(["genetic algorithm", "fewer Generations"])

    def test_bad_setup_after_a_solve_keeps_the_result(self):
        study()
        self.assertEqual(bpy.ops.fenestra.solve_openings(), {'FINISHED'})
        bpy.context.scene.fenestra.solve.element_size = 50.0
        self.assert_refused(["Element Size"])
        self.assertTrue(bpy.context.scene.fenestra.results.valid)


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    enable()
    result = unittest.main(argv=[sys.argv[0]], exit=False, verbosity=2).result
    sys.exit(0 if result.wasSuccessful() else 1)
