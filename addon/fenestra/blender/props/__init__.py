"""The add-on's settings and figures in Blender's data: `scene.fenestra` and `object.fenestra`
(properties), with their parts: the display settings (display_settings), climate goals and a solve's
climate figures (climate_goal_properties), an Annual Daylight run's figures (annual_properties), and
the goal fields' bounds (goal_bounds). Their names and paths are what scripts use (docs/blender.md)."""
