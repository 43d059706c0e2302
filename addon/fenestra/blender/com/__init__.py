"""The add-on's plain logic: no Blender module imported, directly or through another module, and no
Blender data touched: plain values (paths, dicts, arrays, strings) in and out, so each module loads and
is tested in plain Python. The names the add-on gives Blender's data (names), the study's error
(study_error), the solve and annual jobs run on a worker thread (solve_job, annual_job), the study
folder and its fingerprints (study_folder, study_fingerprint), the contributions kept between solves
(contributions_cache), the native module as the add-on sees it (native) and its messages in the
user's words (native_messages, user_messages), false colour's scale (false_colour), an opening's
cutter as a solid (cutter)."""
