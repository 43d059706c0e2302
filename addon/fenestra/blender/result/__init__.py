"""A result put into the scene, and what the viewport shows of it: the cutters, Booleans and
achieved values of a solve (results, sensor_results, climate_results), an Annual Daylight run's
figures (annual_results, sensor_table), the quantity and scale shown in false colour
(result_display), the sky a result was solved under (sky_reference), Preview Sky's World
(sky_preview), the goals-versus-achieved plot (goal_plot)."""
