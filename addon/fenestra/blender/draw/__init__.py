"""What the add-on draws in the 3D View: the opening domain highlighted (overlay), the sensors in
false colour (false_colour_overlay) with its colour bar (legend), goal and achieved values beside
sensors (sensor_labels, and Inspect Sensors: sensor_hover); shared drawing helpers (viewport_drawing,
toward_viewer)."""
