"""A native error message as the panel shows it: written for the scene file and the command line,
it names the study's file (here a staging folder, deleted with the failed solve), settings by their
scene-file keys and a command-line option Blender does not have. No bpy here."""

# Scene-file keys the cost model names -> where they are set in the panel.
SETTINGS = (
    ("opening_domain.element_size or solver.element_size", "Solve > Element Size"),
    ("solver.paths, render.paths_per_sensor, --paths", "Solve > Quality"),
)
COMMAND_LINE_ONLY = ", or raise the limit with --max-memory (max_memory= in Python)"


def for_the_panel(message, scene_path):
    """`message` without the study file's name and the command-line advice, settings named as in
    the panel."""
    for prefix in ("scene '%s': " % scene_path, "loading scene '%s': " % scene_path):
        if message.startswith(prefix):
            message = message[len(prefix):]
    message = message.replace(COMMAND_LINE_ONLY, "")
    for key, place in SETTINGS:
        message = message.replace(key, place)
    return message
