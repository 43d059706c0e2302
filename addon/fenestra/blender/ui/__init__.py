"""What the user clicks and reads in the sidebar's Fenestra tab: the operators (operators,
annual_operator, evaluate_openings, tradeoff_operators, result_operators, check_setup), the running
job's modal half and progress (job_operator, solve_progress) and what cancels it (solve_guard), the
panels (panels, result_panels, climate_panel, annual_panel), the Fenestra menu in the Object menu
(menu), the commands' keyboard shortcuts (shortcuts), the goals shown while they are painted
(goal_painting) and the automatic constraints the panels show greyed (constraint_defaults)."""
