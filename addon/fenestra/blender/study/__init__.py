"""The scene read as a study (it reads Blender's data and changes nothing): the scene file and OBJ
(export, with climate_goals, materials, sky, weather_file, visibility), the checks before a solve
(setup_checks), and the openings read back from their cutters (opening_cutters)."""
