"""Helper of scripts/radiance_annual_reference.sh: the parts of the Radiance annual reference that
are bookkeeping, not light transport (which suns go where, the matrix products, the metrics).

    radiance_annual_reference.py prepare WORK            # after gendaymtx: writes WORK/{sky,suns1,sunsf}.rad
    radiance_annual_reference.py assemble WORK OUT ...   # after rcontrib: writes the reference to OUT

Plain /usr/bin/python3 with NumPy; no Fenestra import (the reference must not depend on the code it
checks). Units: Radiance radiance W/(sr m^2) x 179 lm/W = cd/m^2, irradiance x 179 = lux.
"""

import gzip
import json
import os
import re
import sys

import numpy as np

EFFICACY = 179.0               # lm/W, Radiance's WHTEFFICACY
SUN_ANGLE_DEG = 0.533          # the solar disc of gendaymtx -D and gendaylit
SKY_MF = 4                     # sky patches: Reinhart MF 4, 2305 + the ground
OCCUPIED = (8.0, 18.0)         # local standard time, [start, end), the LM-83 analysis period
TREGENZA_ROW = [30, 30, 24, 24, 18, 12, 6]


def luminance(rgb):
    """Radiance's photopic weighting of (R, G, B) (grey here: every channel is the same)."""
    rgb = np.asarray(rgb)
    return 0.265 * rgb[..., 0] + 0.670 * rgb[..., 1] + 0.065 * rgb[..., 2]


def reinhart_patches(mf):
    """Centres (unit vectors, +X east, +Y north, +Z up) and solid angles (sr) of the sky patches
    1..144 mf^2 + 1 in gendaymtx's order (rh_init): rings from the horizon up, each starting at
    north and going clockwise (east), the zenith cap last. Index 0 (the ground) is not included."""
    rows = 7 * mf
    alpha = np.radians(90.0 / (rows + 0.5))
    centres, omega = [], []
    for r in range(rows):
        n = mf * TREGENZA_ROW[r // mf]
        alt = (r + 0.5) * alpha
        dom = 2 * np.pi * (np.sin((r + 1) * alpha) - np.sin(r * alpha)) / n
        for j in range(n):
            az = j * 2 * np.pi / n
            centres.append((np.cos(alt) * np.sin(az), np.cos(alt) * np.cos(az), np.sin(alt)))
            omega.append(dom)
    centres.append((0.0, 0.0, 1.0))
    omega.append(2 * np.pi * (1 - np.cos(alpha / 2)))
    return np.array(centres), np.array(omega)


def read_matrix(path, ncomp=3):
    """A Radiance matrix file with a header (gendaymtx -of, rcontrib -faf): float32 values."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"\n\n") + 2 if data.startswith(b"#?RADIANCE") else 0
    header = data[:end].decode(errors="replace")
    if end and "FORMAT=float" not in header:
        raise SystemExit("%s: expected FORMAT=float" % path)
    return header, np.frombuffer(data[end:], dtype="<f4")


def read_suns(path):
    """gendaymtx -D output: [(id, radiance, direction)] in file order."""
    text = open(path).read()
    pattern = re.compile(r"void light solar(\d+)\n0\n0\n3 (\S+) \S+ \S+\n\nsolar\d+ source sun\d+\n"
                         r"0\n0\n4 (\S+) (\S+) (\S+) (\S+)")
    return [(int(m.group(1)), float(m.group(2)),
             np.array([float(m.group(k)) for k in (3, 4, 5)])) for m in pattern.finditer(text)]


def read_wea(path):
    rows = []
    for line in open(path):
        f = line.split()
        if len(f) >= 5 and f[0][0].isdigit():
            rows.append((int(f[0]), int(f[1]), float(f[2]), float(f[3]), float(f[4])))
    return rows


DAYS = [31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31]


def julian(month, day):
    return sum(DAYS[:month - 1]) + day


def hour_index_of_sun(sun_id):
    """gendaymtx's solar_minute(jd, hr) = 1440 (jd - 1) + round(60 hr) -> the row of the year."""
    return sun_id // 60


def prepare(work):
    # The sky of the daylight coefficients: one glow of unit radiance over both hemispheres; the
    # bins (reinhartb.cal, MF 4, shifted by one) make the lower hemisphere bin 0, the ground.
    with open(os.path.join(work, "sky.rad"), "w") as f:
        f.write("void glow skyglow\n0\n0\n4 1 1 1 0\n\n"
                "skyglow source skydome\n0\n0\n4 0 0 1 180\n\n"
                "skyglow source grounddome\n0\n0\n4 0 0 -1 180\n")
    suns = read_suns(os.path.join(work, "suns.rad"))
    # Every sun of gendaymtx -D at unit radiance (its hourly illuminance is applied afterwards).
    with open(os.path.join(work, "suns1.rad"), "w") as f, open(os.path.join(work, "suns1.mod"), "w") as m:
        for sid, _, d in suns:
            f.write("void light solar%d\n0\n0\n3 1 1 1\n\nsolar%d source sun%d\n0\n0\n4 %.6f %.6f %.6f %g\n\n"
                    % (sid, sid, sid, d[0], d[1], d[2], SUN_ANGLE_DEG))
            m.write("solar%d\n" % sid)
    # The sun's interreflected light: the same actual suns (unit radiance), only those that can
    # shine into the room: lit, and in front of the south wall (direction y < 0), the only side
    # with an opening. (Suns moved to sun-patch centres, as the 5-phase method does, are not
    # good enough here: for a sensor 0.25 m from a sunlit side wall, moving the sun by 0.9 degrees
    # changed its interreflected sunlight by 17 %.)
    lit = [(sid, rad, d) for sid, rad, d in suns if rad > 0 and d[1] < 0]
    with open(os.path.join(work, "sunsf.rad"), "w") as f, open(os.path.join(work, "sunsf.mod"), "w") as m:
        for sid, _, d in lit:
            f.write("void light solar%d\n0\n0\n3 1 1 1\n\nsolar%d source sun%d\n0\n0\n4 %.6f %.6f %.6f %g\n\n"
                    % (sid, sid, sid, d[0], d[1], d[2], SUN_ANGLE_DEG))
            m.write("solar%d\n" % sid)
    print("prepare: %d suns, %d with light in front of the south wall" % (len(suns), len(lit)))


def replicate_mean_and_se(stack):
    """stack: (R, ...) independent estimates -> mean, standard error of the mean."""
    r = stack.shape[0]
    return stack.mean(0), stack.std(0, ddof=1) / np.sqrt(r)


def save_npy_gz(path, array):
    with gzip.open(path, "wb", compresslevel=9) as f:
        np.save(f, array)


def assemble(work, out, sky_reps, sun_reps, n_sensors, settings_json):
    os.makedirs(out, exist_ok=True)
    settings = json.load(open(settings_json))
    sensors = np.loadtxt(os.path.join(work, "sensors.pts"))
    assert sensors.shape == (n_sensors, 6)
    wea = read_wea(os.path.join(work, "weather.wea"))
    n_hours = len(wea)
    month = np.array([w[0] for w in wea])
    day = np.array([w[1] for w in wea])
    clock = np.array([w[2] for w in wea])           # epw2wea: the middle of the EPW row's hour
    hour_ending = (clock + 0.5).astype(int)         # the EPW row's own hour label, 1..24
    assert np.allclose(clock, hour_ending - 0.5)
    occupied = (clock >= OCCUPIED[0]) & (clock < OCCUPIED[1])

    # Sky matrices (gendaymtx -m 4 -c 1 1 1): rows patches (0 = ground), columns hours.
    n_patch = 144 * SKY_MF ** 2 + 2
    _, s_sky = read_matrix(os.path.join(work, "sky_s.mtx"))
    s_sky = luminance(s_sky.reshape(n_patch, n_hours, 3))          # W/(sr m^2)
    _, s_sun = read_matrix(os.path.join(work, "sky_d.mtx"))
    s_sun = luminance(s_sun.reshape(n_patch, n_hours, 3))
    _, omega = reinhart_patches(SKY_MF)
    # The sun's direct normal illuminance per hour (lux), exactly as gendaymtx spread it over the
    # patches (AddDirect: sum of patch radiance x patch solid angle = dir_illum / 179).
    ev_patches = EFFICACY * (s_sun[1:].astype(np.float64) * omega[:, None]).sum(0)

    # The suns of gendaymtx -D (actual positions at the middle of each hour).
    suns = read_suns(os.path.join(work, "suns.rad"))
    sun_hour = np.array([hour_index_of_sun(sid) for sid, _, _ in suns])
    jd = np.array([julian(m, d) for m, d in zip(month, day)])
    assert np.all(jd[sun_hour] - 1 == np.array([sid // 1440 for sid, _, _ in suns]))
    sun_dir = np.zeros((n_hours, 3))
    sun_dir[sun_hour] = np.array([d for _, _, d in suns])
    has_sun = np.zeros(n_hours, bool)
    has_sun[sun_hour] = np.array([rad > 0 for _, rad, _ in suns])
    r_sun = np.radians(SUN_ANGLE_DEG / 2)
    ev_file = np.zeros(n_hours)
    ev_file[sun_hour] = np.array([rad for _, rad, _ in suns]) * EFFICACY * np.pi * r_sun ** 2
    # The sun's illuminance: from the matrix (float precision) where -D gives a sun; hours whose
    # mid-hour sun is below the horizon keep their light in the matrix but have no sun here.
    ev = np.where(has_sun, ev_patches, 0.0)
    rel = np.abs(ev - ev_file)[has_sun] / np.maximum(ev[has_sun], 1e-9)
    print("assemble: sun illuminance, matrix vs -D file (4 digits): max rel diff %.2e" % rel.max())
    lost = (~has_sun) & (ev_patches > 0)
    omega_sun = 2 * np.pi * (1 - np.cos(r_sun))      # Radiance's solid angle of a distant source

    # Daylight coefficients of the sky (rcontrib, R replicates): E_sky = 179 DC . S_sky.
    _, dc = read_matrix(os.path.join(work, "dc_sky.dat"))
    dc = luminance(dc.reshape(sky_reps, n_sensors, n_patch, 3)).astype(np.float64)
    s64 = s_sky.astype(np.float64)
    e_sky_sum = np.zeros((n_sensors, n_hours))
    e_sky_sq = np.zeros((n_sensors, n_hours))
    sky_rep_means = np.zeros((sky_reps, n_sensors))   # each estimate's occupied-hour mean
    for r in range(sky_reps):
        e = EFFICACY * dc[r] @ s64
        e_sky_sum += e
        e_sky_sq += e * e
        sky_rep_means[r] = e[:, occupied].mean(1)
    e_sky = e_sky_sum / sky_reps
    e_sky_se = np.sqrt(np.maximum(e_sky_sq / sky_reps - e_sky ** 2, 0) * sky_reps / (sky_reps - 1)
                       / sky_reps)

    # The sun seen directly (rcontrib -ab 0, every actual sun, unit radiance): C0 / omega x Ev.
    _, c0 = read_matrix(os.path.join(work, "sun_direct.dat"))
    c0 = luminance(c0.reshape(n_sensors, len(suns), 3)).astype(np.float64)
    e_direct = np.zeros((n_sensors, n_hours))
    e_direct[:, sun_hour] = c0 / omega_sun * ev[sun_hour]

    # The sun's interreflected light: the actual suns in front of the south wall, -ab N minus the
    # -ab 0 run of the same suns (the direct part of both is the same deterministic shadow-ray
    # sum, so it cancels and leaves the interreflections).
    mods = [int(l.strip()[5:]) for l in open(os.path.join(work, "sunsf.mod")) if l.strip()]
    _, cn = read_matrix(os.path.join(work, "sunsf_ab.dat"))
    cn = luminance(cn.reshape(sun_reps, n_sensors, len(mods), 3)).astype(np.float64)
    _, cz = read_matrix(os.path.join(work, "sunsf_ab0.dat"))
    cz = luminance(cz.reshape(n_sensors, len(mods), 3)).astype(np.float64)
    ind = cn - cz[None]                                    # (R, sensors, suns)
    ind_mean, ind_se = replicate_mean_and_se(ind)
    hours_front = np.array([hour_index_of_sun(sid) for sid in mods])
    assert np.all(has_sun[hours_front]) and np.all(sun_dir[hours_front, 1] < 0)
    assert int((has_sun & (sun_dir[:, 1] < 0)).sum()) == len(mods)
    scale = ev[hours_front] / omega_sun
    e_sunind = np.zeros((n_sensors, n_hours))
    e_sunind_se = np.zeros((n_sensors, n_hours))
    e_sunind[:, hours_front] = ind_mean * scale
    e_sunind_se[:, hours_front] = ind_se * scale
    occ_front = occupied[hours_front]
    sun_rep_means = (ind[:, :, occ_front] * scale[occ_front]).sum(2) / occupied.sum()
    # The -ab 0 run of these suns must equal the direct-sun run's columns for the same suns.
    assert np.allclose(cz / omega_sun * ev[hours_front], e_direct[:, hours_front], rtol=1e-5, atol=1e-3)

    total = e_sky + e_direct + e_sunind
    total_se = np.sqrt(e_sky_se ** 2 + e_sunind_se ** 2)

    # Metrics over the occupied hours (equal sensor areas: a regular grid).
    occ = total[:, occupied]
    occ_direct = e_direct[:, occupied]
    n_occ = int(occupied.sum())
    mean_lux = occ.mean(1)
    da300 = (occ >= 300.0).mean(1)
    sda = float((da300 >= 0.5).mean())
    ase_hours = (occ_direct > 1000.0).sum(1)
    ase = float((ase_hours > 250).mean())
    # Sensitivity of the metrics to the reference's noise: thresholds within 2 standard errors.
    occ_se = total_se[:, occupied]
    near_300 = (np.abs(occ - 300.0) < 2 * occ_se).sum(1)
    lit = occ > 50.0
    rel_se = occ_se[lit] / occ[lit]
    mean_rel_se = np.sqrt(sky_rep_means.var(0, ddof=1) / sky_reps
                          + sun_rep_means.var(0, ddof=1) / sun_reps) / mean_lux

    np.save(os.path.join(out, "sensors.npy"), sensors.astype(np.float32))
    save_npy_gz(os.path.join(out, "illuminance_total.npy.gz"), total.astype(np.float32))
    save_npy_gz(os.path.join(out, "illuminance_direct_sun.npy.gz"), e_direct.astype(np.float32))
    save_npy_gz(os.path.join(out, "illuminance_sky.npy.gz"), e_sky.astype(np.float32))
    save_npy_gz(os.path.join(out, "illuminance_total_stderr.npy.gz"), total_se.astype(np.float16))
    hours = {
        "units": {"clock_hours": "h, local standard time (UTC-6), the middle of the EPW row's hour",
                  "hour_ending": "the EPW row's hour label 1..24 (the row covers [h-1, h))",
                  "sun_normal_illuminance_lux": "lux, Perez 1990 direct efficacy x DNI (gendaymtx)",
                  "sun_direction": "unit vector toward the sun, +X east, +Y north, +Z up (gendaymtx -D)"},
        "month": month.tolist(), "day": day.tolist(), "hour_ending": hour_ending.tolist(),
        "clock_hours": clock.tolist(), "occupied": occupied.astype(int).tolist(),
        "direct_normal_irradiance_w_m2": [w[3] for w in wea],
        "diffuse_horizontal_irradiance_w_m2": [w[4] for w in wea],
        "sun_normal_illuminance_lux": [round(float(v), 3) for v in ev],
        "sun_direction": [[round(float(c), 6) for c in v] if h else None
                          for v, h in zip(sun_dir, has_sun)],
        "sun_lost_below_horizon": np.nonzero(lost)[0].tolist(),
    }
    with open(os.path.join(out, "hours.json"), "w") as f:
        json.dump(hours, f, separators=(",", ":"))
    metrics = {
        "units": {"mean_illuminance_lux": "lux, mean over the occupied hours",
                  "da300": "fraction of occupied hours with E >= 300 lux",
                  "sda300_50": "fraction of sensors (equal areas) with DA300 >= 0.5",
                  "ase_hours": "occupied hours with direct-sun E > 1000 lux",
                  "ase1000_250": "fraction of sensors with ase_hours > 250"},
        "occupied_period": "clock_hours in [8, 18) local standard time: EPW rows 9..18 (mid-hour 08:30..17:30), every day",
        "occupied_hours": n_occ,
        "sensor_count": n_sensors,
        "sensor_area_m2": 0.25,
        "mean_illuminance_lux": [round(float(v), 3) for v in mean_lux],
        "da300": [round(float(v), 6) for v in da300],
        "sda300_50": sda,
        "ase_hours": ase_hours.tolist(),
        "ase1000_250": ase,
        "space_mean_illuminance_lux": round(float(mean_lux.mean()), 3),
        "noise": {
            "relative_stderr_occupied_hours_above_50_lux": {
                "median": float(np.median(rel_se)), "p95": float(np.percentile(rel_se, 95)),
                "p99": float(np.percentile(rel_se, 99)), "max": float(rel_se.max())},
            "pooled_rms_relative_stderr_occupied_hours_above_50_lux": float(np.sqrt(np.mean(rel_se ** 2))),
            # The same coefficients serve every hour, so their noise does not average out over
            # the year: the mean's error comes from the independent estimates' own means.
            "relative_stderr_of_mean_illuminance_per_sensor_max": float(mean_rel_se.max()),
            "relative_stderr_of_mean_illuminance_per_sensor_median": float(np.median(mean_rel_se)),
            "occupied_hours_within_2_stderr_of_300_lux_per_sensor": near_300.tolist(),
        },
        "settings": settings,
    }
    with open(os.path.join(out, "metrics.json"), "w") as f:
        json.dump(metrics, f, indent=1)
    print("assemble: sDA300/50%% = %.4f, ASE1000,250h = %.4f, space mean %.1f lux, "
          "relative stderr median %.2e rms %.2e p99 %.2e max %.2e, of the sensors' means <= %.2e"
          % (sda, ase, mean_lux.mean(), np.median(rel_se), np.sqrt(np.mean(rel_se ** 2)),
             np.percentile(rel_se, 99), rel_se.max(), mean_rel_se.max()))
    print("assemble: %d hours lost their sun (mid-hour sun below the horizon)" % lost.sum())
    share = lambda a: float(a[:, occupied].sum() / total[:, occupied].sum())
    print("assemble: occupied-hour shares: sky %.3f, sun direct %.3f, sun interreflected %.3f"
          % (share(e_sky), share(e_direct), share(e_sunind)))


if __name__ == "__main__":
    cmd = sys.argv[1] if len(sys.argv) > 1 else ""
    if cmd == "prepare":
        prepare(sys.argv[2])
    elif cmd == "assemble":
        assemble(sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5]), int(sys.argv[6]),
                 sys.argv[7])
    else:
        raise SystemExit(__doc__)
