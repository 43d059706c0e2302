"""Perez all-weather skies of Radiance's gendaylit -W for representative Chicago hours, sampled on a
grid of directions: python_tests/data/gendaylit_perez/hours.json.

    radiance_gendaylit_perez.py EPW OUT_JSON     # gendaylit, oconv, rtrace on PATH; RAYPATH set

Reads the EPW's direct normal and diffuse horizontal irradiance (columns 15, 16, W/m^2), calls
`gendaylit MONTH DAY HOUR -a LAT -o LON -m MER -W DNI DHI` for every hour with light at the middle of
the EPW row's hour (HOUR = hour_ending - 0.5, local standard time, as epw2wea and gendaymtx read
the file), picks representative hours from gendaylit's own epsilon, delta and solar altitude, and
for each renders the printed sky with rtrace (-ab 0, rays from the origin) in a fixed grid of
directions and near the sun. Plain /usr/bin/python3 with NumPy; no Fenestra import.
"""

import json
import math
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

EFFICACY = 179.0
HALF_SUN_DEG = 0.2665
GROUND_REFLECTANCE = 0.2   # gendaylit's default (-g)
# gendaylit's 145 integration points (defangle_theta / defangle_phi in gendaylit.c): zenith angle
# and azimuth from the sun's vertical, degrees, at Tregenza's patch centres.
TREG_THETA = [84] * 30 + [72] * 30 + [60] * 24 + [48] * 24 + [36] * 18 + [24] * 12 + [12] * 6 + [0]
TREG_PHI = ([12 * j for j in range(30)] * 2 + [15 * j for j in range(24)] * 2
            + [20 * j for j in range(18)] + [30 * j for j in range(12)] + [60 * j for j in range(6)] + [0])
# (name, which clearness bins, target altitude in degrees, what to maximise among the closest)
SELECTION = [
    ("clear, high sun", "clear", 70.0),
    ("clear, mid sun", "clear", 40.0),
    ("clear, low sun", "clear", 8.0),
    ("clear, winter noon", "clear_winter", 27.0),
    ("fairly clear (bins 6-7), mid sun", "fair", 45.0),
    ("intermediate (bins 4-5), high sun", "intermediate", 65.0),
    ("intermediate (bins 4-5), low sun", "intermediate", 12.0),
    ("thin overcast (bins 2-3), mid sun", "thin", 40.0),
    ("overcast (bin 1), high sun", "overcast", 65.0),
    ("overcast (bin 1), low sun", "overcast", 10.0),
    ("brightest overcast (largest delta, bins 1-2)", "bright", None),
    ("sun near the horizon (below 3 degrees), clear or intermediate", "horizon", 1.5),
]
BIN_EDGES = [1.065, 1.23, 1.5, 1.95, 2.8, 4.5, 6.2]


def clearness_bin(eps):
    return 1 + sum(eps >= e for e in BIN_EDGES)


def read_epw(path):
    lines = open(path).read().splitlines()
    loc = lines[0].split(",")
    lat, lon, tz, elev = float(loc[6]), float(loc[7]), float(loc[8]), float(loc[9])
    rows = []
    for line in lines[8:]:
        f = line.split(",")
        if len(f) < 20:
            continue
        rows.append({"month": int(f[1]), "day": int(f[2]), "hour_ending": int(f[3]),
                     "dni_w_m2": float(f[14]), "dhi_w_m2": float(f[15])})
    return (lat, lon, tz, elev), rows


def gendaylit(row, place):
    lat, lon, tz, _ = place
    clock = row["hour_ending"] - 0.5
    args = ["gendaylit", str(row["month"]), str(row["day"]), "%.3f" % clock,
            "-a", "%g" % lat, "-o", "%g" % -lon, "-m", "%g" % (-15 * tz),
            "-W", "%g" % row["dni_w_m2"], "%g" % row["dhi_w_m2"]]
    p = subprocess.run(args, capture_output=True, text=True)
    return args, p.stdout, p.stderr


def parse(text):
    out = {}
    m = re.search(r"# Local solar time: (\S+)", text)
    out["local_solar_time_h"] = float(m.group(1)) if m else None
    m = re.search(r"# Solar altitude and azimuth: (\S+) (\S+)", text)
    if m:
        out["solar_altitude_deg"], out["solar_azimuth_deg"] = float(m.group(1)), float(m.group(2))
    m = re.search(r"# epsilon, delta, atmospheric precipitable water content : (\S+) (\S+) (\S+)", text)
    if m:
        out["epsilon"], out["delta"], out["precipitable_water_cm"] = (float(m.group(k)) for k in (1, 2, 3))
    m = re.search(r"void light solar\n0\n0\n3 (\S+) \S+ \S+\n\nsolar source sun\n0\n0\n4 (\S+) (\S+) (\S+) (\S+)", text)
    if m:
        out["sun_radiance"] = float(m.group(1))
        out["sun_direction"] = [float(m.group(k)) for k in (2, 3, 4)]
    m = re.search(r"void brightfunc skyfunc\n2 skybright perezlum.cal\n0\n10 (.*)", text)
    if m:
        out["skyfunc_args"] = [float(v) for v in m.group(1).split()]
    return out


def direction(alt_deg, az_deg):
    """Unit vector, +X east, +Y north, +Z up; azimuth from north, clockwise (east = 90)."""
    a, z = math.radians(alt_deg), math.radians(az_deg)
    return [math.cos(a) * math.sin(z), math.cos(a) * math.cos(z), math.sin(a)]


GRID_ALT = [0.5, 2, 4, 6, 9, 12, 15, 20, 25, 30, 40, 50, 60, 70, 80, 90]
GRID_AZ = list(range(0, 360, 15))


def grid_directions():
    dirs = []
    for alt in GRID_ALT:
        for az in (GRID_AZ if alt < 90 else [0]):
            dirs.append((alt, az))
    return dirs


def near_sun_directions(sun):
    """Directions at angular distance g from the sun, 8 around it, kept above the horizon."""
    s = np.array(sun, float)
    up = np.array([0.0, 0.0, 1.0])
    u = np.cross(up, s)
    if np.linalg.norm(u) < 1e-9:
        u = np.array([1.0, 0.0, 0.0])
    u /= np.linalg.norm(u)
    v = np.cross(s, u)
    out = []
    for g in (1, 2, 5, 10, 20, 40, 90, 135, 180):
        for k in range(8 if g < 180 else 1):
            t = 2 * math.pi * k / 8
            d = math.cos(math.radians(g)) * s + math.sin(math.radians(g)) * (math.cos(t) * u + math.sin(t) * v)
            if d[2] > 0.01:
                out.append((g, k * 45, d / np.linalg.norm(d)))
    return out


def perez_shape(coef, d, sun):
    """The printed Perez function of perezlum.cal's intersky, without its normalisation A1."""
    a, b, c, dd, e = coef
    cz = max(d[2], 0.01)
    cg = float(np.clip(np.dot(d, sun), -1, 1))
    return (1 + a * math.exp(b / cz)) * (1 + c * math.exp(dd * math.acos(cg)) + e * cg * cg)


def render(sky_text, dirs, work):
    """What Radiance renders: rtrace -ab 0 from the origin toward each direction, radiance."""
    rad = os.path.join(work, "sky.rad")
    with open(rad, "w") as f:
        f.write(sky_text)
        f.write("\nskyfunc glow skyglow\n0\n0\n4 1 1 1 0\n\nskyglow source skydome\n0\n0\n4 0 0 1 180\n"
                "\nskyglow source grounddome\n0\n0\n4 0 0 -1 180\n")
    oct_path = os.path.join(work, "sky.oct")
    with open(oct_path, "wb") as f:
        subprocess.run(["oconv", rad], stdout=f, check=True)
    rays = "".join("0 0 0 %.9f %.9f %.9f\n" % tuple(d) for d in dirs)
    p = subprocess.run(["rtrace", "-h", "-ab", "0", "-ov", "-faf", oct_path],
                       input=rays.encode(), capture_output=True, check=True)
    rgb = np.frombuffer(p.stdout, "<f4").reshape(-1, 3)
    return (0.265 * rgb[:, 0] + 0.670 * rgb[:, 1] + 0.065 * rgb[:, 2]).astype(float)


def main(epw, out_path):
    place, rows = read_epw(epw)
    lat, lon, tz, elev = place
    candidates = []
    for i, row in enumerate(rows):
        if row["dhi_w_m2"] <= 0:
            continue
        args, text, err = gendaylit(row, place)
        h = parse(text)
        if "epsilon" not in h or "skyfunc_args" not in h or h["solar_altitude_deg"] <= 0:
            continue
        if "error sky" in err or "printing error" in err:
            continue
        h["bin"] = clearness_bin(h["epsilon"])
        candidates.append((i, h))
    groups = {
        "clear": lambda h, r: h["bin"] == 8,
        "clear_winter": lambda h, r: h["bin"] == 8 and r["month"] in (12, 1) and 11 <= r["hour_ending"] <= 14,
        "fair": lambda h, r: h["bin"] in (6, 7),
        "intermediate": lambda h, r: h["bin"] in (4, 5),
        "thin": lambda h, r: h["bin"] in (2, 3),
        "overcast": lambda h, r: h["bin"] == 1,
        "bright": lambda h, r: h["bin"] in (1, 2),
        "horizon": lambda h, r: h["bin"] >= 4 and h["solar_altitude_deg"] < 3,
    }
    chosen, used = [], set()
    for name, group, target in SELECTION:
        pool = [(i, h) for i, h in candidates if groups[group](h, rows[i]) and i not in used]
        if not pool:
            print("gendaylit_perez: no hour for %s" % name)
            continue
        if target is None:
            i, h = max(pool, key=lambda ih: (ih[1]["delta"], -ih[0]))
        else:
            # Closest altitude, then the strongest direct normal irradiance, then the earliest.
            i, h = min(pool, key=lambda ih: (round(abs(ih[1]["solar_altitude_deg"] - target), 1),
                                             -rows[ih[0]]["dni_w_m2"], ih[0]))
        used.add(i)
        chosen.append((name, i))

    grid = grid_directions()
    grid_vec = [direction(a, z) for a, z in grid]
    omega_sun = 2 * math.pi * (1 - math.cos(math.radians(HALF_SUN_DEG)))
    hours = []
    with tempfile.TemporaryDirectory() as work:
        for name, i in chosen:
            row = rows[i]
            args, text, err = gendaylit(row, place)
            h = parse(text)
            A = h["skyfunc_args"]
            sun = np.array(A[7:10])
            near = near_sun_directions(sun)
            dirs = grid_vec + [list(d) for _, _, d in near]
            lum = EFFICACY * render(text, dirs, work)
            coef = A[2:7]
            perez = [EFFICACY * A[0] * perez_shape(coef, np.array(d), sun) for d in dirs]
            # gendaylit's normalisation sum over its 145 points (integ_lv), with the printed
            # coefficients: diffuse horizontal illuminance = 179 A1 x sum (to A1's 4 digits).
            zen = math.acos(float(np.clip(sun[2], -1, 1)))
            s145 = 0.0
            for th, ph in zip(TREG_THETA, TREG_PHI):
                t, p = math.radians(th), math.radians(ph)
                cg = min(1.0, math.cos(zen) * math.cos(t) + math.sin(zen) * math.sin(t) * math.cos(p))
                s145 += ((1 + coef[0] * math.exp(coef[1] / math.cos(t)))
                         * (1 + coef[2] * math.exp(coef[3] * math.acos(cg)) + coef[4] * cg * cg)
                         * math.cos(t))
            s145 *= 2 * math.pi / 145
            n_grid = len(grid_vec)
            hours.append({
                "label": name,
                "epw_row": i + 1,
                "month": row["month"], "day": row["day"], "hour_ending": row["hour_ending"],
                "clock_hours": row["hour_ending"] - 0.5,
                "direct_normal_irradiance_w_m2": row["dni_w_m2"],
                "diffuse_horizontal_irradiance_w_m2": row["dhi_w_m2"],
                "command": " ".join(args),
                "gendaylit_header": {k: h[k] for k in ("local_solar_time_h", "solar_altitude_deg",
                                                       "solar_azimuth_deg", "epsilon", "delta",
                                                       "precipitable_water_cm")},
                "clearness_bin": clearness_bin(h["epsilon"]),
                "sun_direction": h["sun_direction"],
                "sun_radiance_w_sr_m2": h["sun_radiance"],
                "direct_normal_illuminance_lux": EFFICACY * h["sun_radiance"] * omega_sun,
                "skyfunc_args": A,
                "perez_coefficients_abcde": coef,
                "diffuse_normalization_A1": A[0],
                "zenith_luminance_cd_m2": EFFICACY * A[0] * perez_shape(coef, np.array([0, 0, 1.0]), sun),
                "ground_luminance_cd_m2": EFFICACY * A[1],
                "diffuse_horizontal_illuminance_lux_145": EFFICACY * A[0] * s145,
                "grid_luminance_cd_m2": [round(v, 4) for v in lum[:n_grid]],
                "grid_perez_luminance_cd_m2": [round(v, 4) for v in perez[:n_grid]],
                "near_sun": [{"gamma_deg": g, "around_deg": k, "direction": [round(c, 6) for c in d],
                              "luminance_cd_m2": round(float(lv), 4), "perez_luminance_cd_m2": round(float(pv), 4)}
                             for (g, k, d), lv, pv in zip(near, lum[n_grid:], perez[n_grid:])],
                "stderr": err.strip() or None,
            })
            print("gendaylit_perez: %-48s %2d/%2d %5.2fh eps %6.3f delta %.3f alt %5.1f"
                  % (name, row["month"], row["day"], row["hour_ending"] - 0.5, h["epsilon"], h["delta"],
                     h["solar_altitude_deg"]))
    version = subprocess.run(["rtrace", "-version"], capture_output=True, text=True).stdout.strip()
    doc = {
        "description": "Perez all-weather skies of Radiance's gendaylit -W (Perez, Seals & Michalsky 1993 "
                       "with the Perez et al. 1990 efficacies) for representative Chicago O'Hare TMY3 hours, "
                       "sampled in a grid of directions and near the sun. See "
                       "python_tests/data/radiance_annual_room/README.md.",
        "radiance": version,
        "place": {"latitude": lat, "longitude_east": lon, "utc_offset_h": tz, "elevation_m": elev,
                  "gendaylit_args": "-a %g -o %g -m %g (longitude and meridian west positive)"
                                    % (lat, -lon, -15 * tz)},
        "units": {
            "clock_hours": "local standard time (UTC-6), the middle of the EPW row's hour (hour_ending - 0.5)",
            "luminance": "cd/m^2 = 179 x Radiance radiance",
            "grid_luminance_cd_m2": "what Radiance renders: rtrace -ab 0 of the gendaylit sky as a glow; "
                                    "perezlum.cal's skybright, which blends the sky toward the ground "
                                    "brightness near the horizon (weights (Dz+1.01)^10 and (Dz+1.01)^-10)",
            "grid_perez_luminance_cd_m2": "perezlum.cal's intersky: 179 A1 (1 + a e^(b/max(cos theta, 0.01)))"
                                          " (1 + c e^(d gamma) + e cos^2 gamma), no horizon blend",
            "direct_normal_illuminance_lux": "179 x sun radiance (printed, 4 digits) x 2 pi (1 - cos 0.2665 deg)",
            "diffuse_horizontal_illuminance_lux_145": "179 x A1 (printed, 4 digits) x gendaylit's 145-point "
                                                      "normalisation sum (integ_lv) of the printed coefficients",
            "solar_azimuth_deg": "gendaylit's header: degrees from south, west positive",
            "direction": "unit vector, +X east, +Y north, +Z up",
        },
        "precipitable_water": "gendaylit's default 2 cm (no dew point is passed); ground reflectance 0.2",
        "grid": [{"altitude_deg": a, "azimuth_deg_from_north_clockwise": z,
                  "direction": [round(c, 9) for c in v]} for (a, z), v in zip(grid, grid_vec)],
        "hours": hours,
    }
    with open(out_path, "w") as f:
        json.dump(doc, f, indent=1)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    main(sys.argv[1], sys.argv[2])
