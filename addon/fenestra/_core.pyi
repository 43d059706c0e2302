"""Type stubs for the native module fenestra._core (see native/python/module.cpp)."""

from typing import Dict, List, Optional, Tuple

import numpy as np
import numpy.typing as npt

class Cancelled(Exception): ...

class Progress:
    def __init__(self) -> None: ...
    @property
    def fraction(self) -> float: ...
    @property
    def status(self) -> str: ...
    @property
    def cancelled(self) -> bool: ...
    def cancel(self) -> None: ...

class RenderSettings:
    paths_per_sensor: int
    max_bounces: int
    seed: int
    threads: int

class Scene:
    @staticmethod
    def load(path: str) -> "Scene": ...
    @staticmethod
    def from_json(text: str, base_dir: str = ".", name: str = "<json>") -> "Scene": ...
    source: str
    render: RenderSettings
    @property
    def sensor_count(self) -> int: ...
    @property
    def solver_paths(self) -> int: ...  # solver.paths; 0: render.paths_per_sensor
    @property
    def has_climate_goals(self) -> bool: ...
    @property
    def climate_goal_sensors(self) -> List[int]: ...  # ascending: the climate goals' hourly model's rows
    @property
    def element_count(self) -> int: ...
    @property
    def triangle_count(self) -> int: ...
    @property
    def element_size(self) -> float: ...
    @property
    def site_origin(self) -> Tuple[float, float, float]: ...  # local frame's origin, input coordinates, meters
    @property
    def sensor_points(self) -> npt.NDArray[np.float64]: ...  # (sensors, 3), meters, input coordinates
    @property
    def goals(self) -> Optional[npt.NDArray[np.float64]]: ...
    @property
    def goal_units(self) -> str: ...
    @property
    def element_corners(self) -> npt.NDArray[np.float64]: ...  # (elements, 4, 3), meters
    @property
    def element_grid(self) -> npt.NDArray[np.int32]: ...  # (elements, 3): panel, row, column
    def elements_json(self) -> str: ...
    def constraints_json(self) -> str: ...  # the solver.constraints in force; "automatic": keys that took their automatic value

class Contributions:
    E: npt.NDArray[np.float64]  # (sensors, elements), lux for a sky in cd/m^2
    E_stderr: npt.NDArray[np.float64]
    A: npt.NDArray[np.float64]
    T: npt.NDArray[np.float64]  # (elements, elements)
    closed: npt.NDArray[np.float64]
    closed_stderr: npt.NDArray[np.float64]
    all_open: npt.NDArray[np.float64]
    all_open_stderr: npt.NDArray[np.float64]
    paths_per_sensor: int
    seconds: float
    events: int
    @property
    def dropped(self) -> dict[str, int]: ...  # {"non_finite", "truncated_conditions"}: what the tracer left out
    memory_bytes: int
    warnings: list[str]  # the setup checks' (fenestra.contributions sets them; save() writes them)
    def evaluate(self, open: npt.ArrayLike) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...  # bools or 0/1
    def evaluate_openings(self, scene: Scene, openings: npt.ArrayLike | str | dict | list, progress: Optional[Progress] = None,
                          sensors: Optional[Tuple[int, int]] = None  # a shard's block of the scene's sensors
                          ) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...
    @property
    def has_annual(self) -> bool: ...  # computed under a "climate" sky: annual studies are possible
    def annual(self, open: npt.ArrayLike, progress: Optional[Progress] = None) -> dict: ...  # arrays (lux) and "summary"
    def annual_openings(self, scene: Scene, openings: npt.ArrayLike | str, progress: Optional[Progress] = None
                        ) -> dict: ...
    def annual_parts(self, scene: Scene, openings: npt.ArrayLike | str) -> tuple: ...  # (sources, direct, mean, stderr)
    def save_annual(self, scene: Scene, openings: npt.ArrayLike | str, path: str) -> Tuple[str, str]: ...
    def save(self, scene: Scene, path: str) -> Tuple[str, str]: ...

def compute_contributions(scene: Scene, progress: Optional[Progress] = None,
                          sensors: Optional[Tuple[int, int]] = None  # (begin, end): a shard, T left empty
                          ) -> Contributions: ...
def evaluate(scene: Scene, openings: npt.ArrayLike, progress: Optional[Progress] = None,
             sensors: Optional[Tuple[int, int]] = None, paths_per_sensor: int = 0,
             stream: int = 0) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...  # stream: random numbers of their own
# Shards of a study (fenestra.distributed, docs/distributed.md).
def transport_entries(contributions: Contributions) -> Tuple[npt.NDArray[np.int32], npt.NDArray[np.int32],
                                                             npt.NDArray[np.float32], int]: ...  # from, to, value, sensors
def transport_matrix_from_entries(shards: list[tuple], elements: int, paths_per_sensor: int
                                  ) -> npt.NDArray[np.float64]: ...  # T, bit for bit one process's
def contributions_from_arrays(scene: Scene, paths_per_sensor: int, E: npt.ArrayLike, E_stderr: npt.ArrayLike,
                              A: npt.ArrayLike, T: npt.ArrayLike, closed: npt.ArrayLike, closed_stderr: npt.ArrayLike,
                              all_open: npt.ArrayLike, all_open_stderr: npt.ArrayLike, seconds: float = 0.0,
                              events: int = 0, dropped_non_finite: int = 0,
                              dropped_truncated_conditions: int = 0) -> Contributions: ...  # no path records
def keep_records_only(contributions: Contributions) -> None: ...  # frees E, E_stderr and A
def check_output_paths(outputs: list[str], inputs: list[str]) -> None: ...
def npz_json_pair(out: str) -> Tuple[str, str]: ...  # (OUT.npz, OUT.json); ValueError beside a device
def write_json_text(path: str, text: str) -> None: ...
def dropped_warning(dropped: dict[str, int]) -> str: ...  # "" when nothing was dropped
# The solver's queries of path records (solve/record_queries.h); rectangles are (n, 5) float64
# arrays [panel, u0, u1, v0, v1], meters in the panel's parameter domain.
class RegionSearch:
    @property
    def values(self) -> npt.NDArray[np.float64]: ...
    def try_region(self, rectangles: npt.ArrayLike) -> npt.NDArray[np.float64]: ...
    def accept(self) -> None: ...
class RecordQueries:
    def __init__(self, scene: Scene, contributions: Contributions,
                 sensors: Optional[Tuple[int, int]] = None) -> None: ...  # a shard's (begin, end)
    def exact(self, open: npt.ArrayLike) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...
    # (values, sampling errors) from one in four of the paths a change met: a screen before exact().
    def sampled(self, open: npt.ArrayLike) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...
    def evaluate(self, rectangles: npt.ArrayLike) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...
    def flip_effects(self, about: npt.ArrayLike) -> npt.NDArray[np.float64]: ...  # (sensors, elements)
    def region_search(self, rectangles: npt.ArrayLike) -> RegionSearch: ...
    # Positions (ascending) of these records' sensors that a change of openings from the rectangles
    # `before` to `after` (n, 5) can reach: those whose paths met an element near it.
    def sensors_reached(self, before: npt.ArrayLike, after: npt.ArrayLike) -> List[int]: ...
    @property
    def record_bytes(self) -> float: ...
    # Climate goals: rows are these records' sensors; columns (hour, occupied, daylight,
    # occupied_hours, daylight_hours); returns (total, direct, elements, flips, direct changes), lux.
    def hourly_model(self, about: npt.ArrayLike, rows: npt.ArrayLike, columns: tuple, flips: bool) -> tuple: ...
    # (sources (sensors, sources), direct (sensors, sun hours), mean, stderr): the region's year.
    def annual_parts(self, rectangles: npt.ArrayLike) -> tuple: ...
def solve_with_records(scene: Scene, contributions: Contributions, records: object,
                       progress: Optional[Progress] = None) -> str: ...  # JSON
def write_evaluation(scene: Scene, value: npt.ArrayLike, stderr: npt.ArrayLike, openings: int, path: str) -> None: ...
def annual_with_cutters(scene: Scene, openings: npt.ArrayLike | str, paths: int = 0,
                        progress: Optional[Progress] = None, output: str = "") -> dict: ...  # openings cut, no records
def annual_cut_coefficients(scene: Scene, openings: npt.ArrayLike | str, progress: Optional[Progress] = None,
                            sensors: Optional[Tuple[int, int]] = None, paths: int = 0
                            ) -> tuple: ...  # (sources, direct, mean, stderr, paths per sensor)
def annual_from_shards(scene: Scene, parts: tuple, paths_per_sensor: int, cutters: bool, dropped_non_finite: int = 0,
                       dropped_truncated_conditions: int = 0, warnings: list[str] = [], output: str = "",
                       seconds: float = 0.0) -> dict: ...  # the annual study of a sharded study's stacked parts
def check_openings(scene: Scene, openings: npt.ArrayLike | str) -> None: ...  # ValueError: an opening an annual study refuses
def constraint_violations(scene: Scene, openings: npt.ArrayLike | str) -> list[str]: ...  # empty: every constraint met
def write_image(path: str, image: npt.ArrayLike) -> None: ...
def read_openings(path: str) -> npt.NDArray[np.float64] | list[dict]: ...  # a list when any opening is by parameter_rectangle
def goal_error(goals: npt.ArrayLike, values: npt.ArrayLike, weights: npt.ArrayLike | None = None) -> dict: ...
def check_open_masks(masks: npt.ArrayLike, elements: int, batch: bool = False
                     ) -> npt.NDArray[np.uint8]: ...  # 0 and 1 only; ValueError naming the first other entry
def sky_map(scene: Scene) -> npt.NDArray[np.float32]: ...  # (height, width, 3), cd/m^2, top row = zenith
def check_image_path(path: str) -> None: ...  # ValueError unless an image can be written there
def write_sky_outputs(scene: Scene, path: str, map: npt.ArrayLike, summary: str, json_path: str = ""
                      ) -> str: ...  # as `fenestra sky` writes them; returns its lines about the sky
def sky_warnings(scene: Scene) -> list[str]: ...  # a weather file's warnings, a place far from its station
def sky_summary(scene: Scene) -> str: ...  # JSON: horizontal illuminances (lux), sun list
def write_sky(scene: Scene, path: str) -> None: ...
def check_setup(scene: Scene, command: str = "solve") -> list[dict]: ...  # "solve", "contributions", "evaluate"
def require_goals(scene: Scene) -> None: ...  # ValueError when no sensor has a goal and there is no climate goal
def rays_traced() -> int: ...  # rays traced by parallel computations since import

# Daylight models (docs/sky.md). Directions: +Z up, +Y north, +X east; azimuth clockwise from north.
def solar_position(utc_seconds: float, latitude_deg: float, longitude_deg: float, elevation_m: float = 0.0,
                   refraction: bool = True, pressure_hpa: float = 1010.0, temperature_c: float = 10.0
                   ) -> Tuple[float, float]: ...  # (zenith_deg, azimuth_deg)
def sun_direction(zenith_deg: float, azimuth_deg: float) -> npt.NDArray[np.float64]: ...
def utc_seconds(date: str, clock: str, utc_offset: Optional[float] = None, timezone: Optional[str] = None) -> float: ...
def sunrise_sunset(date: str, latitude_deg: float, longitude_deg: float, utc_offset: Optional[float] = None,
                   timezone: Optional[str] = None) -> dict: ...  # kind, sunrise/sunset/solar_noon local minutes
def preetham_radiance(turbidity: float, sun_direction: npt.ArrayLike, directions: npt.ArrayLike
                      ) -> npt.NDArray[np.float64]: ...  # (n, 3) linear sRGB, cd/m^2
def preetham_sun(turbidity: float, sun_zenith_deg: float) -> dict: ...  # radiance, solid_angle, normal_illuminance
def solve(scene: Scene, contributions: Optional[Contributions] = None, progress: Optional[Progress] = None) -> str: ...  # JSON
def automatic_constraints(full_height: bool = False) -> Dict[str, Tuple[float, str]]: ...  # key: (meters or count, why)
def catalogues() -> Dict[str, Dict[str, list[Tuple[float, float]]]]: ...  # built-in window catalogues, meters
def nnls(A: npt.ArrayLike, b: npt.ArrayLike, max_iterations: int = 0, tolerance: float = 0.0) -> Tuple[npt.NDArray[np.float64], float]: ...  # Lawson-Hanson: (x >= 0, ||A x - b||)
