#!/bin/sh
# Regenerates the Radiance annual reference of examples/annual_room under the Chicago weather
# (python_tests/data/radiance_annual_room/) and the gendaylit Perez skies
# (python_tests/data/gendaylit_perez/). See python_tests/data/radiance_annual_room/README.md.
#
#   scripts/radiance_annual_reference.sh RADIANCE_PREFIX [WORK_DIR]
#
# RADIANCE_PREFIX holds bin/ (epw2wea gendaymtx gendaylit oconv rcontrib rtrace getinfo) and lib/
# (reinhartb.cal, perezlum.cal, rayinit.cal). WORK_DIR (default /tmp/radiance_annual_work) keeps
# the large intermediate files. Environment: NPROC (default: all cores), SKY_REPS, SUN_REPS,
# SKY_AD, SUN_AD, AB (the defaults are what the stored reference used), OUT and OUT_PEREZ (the
# output folders), STAGE=perez to run only
# the gendaylit part, STAGE=sun to redo the sun's interreflections and the assembly.
set -eu

RAD=${1:?usage: $0 RADIANCE_PREFIX [WORK_DIR]}
WORK=${2:-/tmp/radiance_annual_work}
HERE=$(cd "$(dirname "$0")/.." && pwd)
PY=/usr/bin/python3
OUT=${OUT:-$HERE/python_tests/data/radiance_annual_room}
OUT_PEREZ=${OUT_PEREZ:-$HERE/python_tests/data/gendaylit_perez}
EPW=$HERE/examples/weather/USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw
ROOM=$HERE/examples/annual_room

export PATH="$RAD/bin:$PATH"
export RAYPATH=".:$RAD/lib"
NPROC=${NPROC:-$(nproc)}
SKY_REPS=${SKY_REPS:-32}     # independent estimates per sensor, sky daylight coefficients
SUN_REPS=${SUN_REPS:-2}      # independent estimates per sensor, the sun's interreflections
SKY_AD=${SKY_AD:-16384}      # hemisphere samples per estimate (first bounce)
SUN_AD=${SUN_AD:-4096}
AB=${AB:-20}                 # ambient bounces (Russian roulette below -lw, no depth cap: -lr 0)
STAGE=${STAGE:-all}

# Sampling: no irradiance cache, stratified hemisphere sampling at every bounce, Russian roulette
# for rays below the weight -lw (unbiased). The sun's runs test 577 sources at every hit, so their
# paths are cut shorter (-lw 1e-4: several times less variance for the same time than 1e-6;
# rcontrib's coefficients carry the roulette's weights, so its results do not depend on -lw).
AMB="-ab $AB -aa 0 -lw 1e-6 -lr 0"
AMB_SUN="-ab $AB -aa 0 -lw 1e-4 -lr 0"
# Light sources: every source tested with one shadow ray to its centre (no culling, no jitter).
DIR="-dc 1 -dt 0 -ds 0 -dj 0 -dr 0 -dp 0"

mkdir -p "$WORK" "$OUT" "$OUT_PEREZ"
cd "$WORK"
rtrace -version > radiance_version.txt
cat radiance_version.txt

repeat() {  # repeat FILE N: the file's lines N times over (independent estimates)
  i=0; while [ $i -lt "$2" ]; do cat "$1"; i=$((i + 1)); done
}

NS=0
if [ "$STAGE" = all ]; then
  start=$(date +%s)
  cp "$ROOM/room.rad" "$ROOM/sensors.pts" .
  NS=$(wc -l < sensors.pts)

  # 1. Weather: EPW -> .wea (DNI, DHI in W/m^2; time = the middle of the EPW row's hour).
  epw2wea "$EPW" weather.wea

  # 2. Skies: MF 4 sky matrix without the sun (sky + ground; the ground is lit by sky and sun),
  #    the sun alone spread over its patches (used only for its illuminance), and the actual suns.
  gendaymtx -m 4 -c 1 1 1 -s -of weather.wea > sky_s.mtx 2> gendaymtx.log
  gendaymtx -m 4 -c 1 1 1 -d -of weather.wea > sky_d.mtx 2>> gendaymtx.log
  gendaymtx -n -D suns.rad -M suns.mod weather.wea 2>> gendaymtx.log
  $PY "$HERE/scripts/radiance_annual_reference.py" prepare "$WORK"
  oconv room.rad sky.rad > sky.oct
  oconv room.rad suns1.rad > suns1.oct

  # 3. Sky daylight coefficients, SKY_REPS independent estimates per sensor.
  repeat sensors.pts "$SKY_REPS" > sensors_sky.pts
  t0=$(date +%s)
  rcontrib -n "$NPROC" -h -I+ $AMB -ad "$SKY_AD" -faf \
    -f reinhartb.cal -p MF=4 -bn 'Nrbins+1' -b 'rbin+1' -m skyglow sky.oct \
    < sensors_sky.pts > dc_sky.dat
  t1=$(date +%s); echo "sky coefficients: $((t1 - t0)) s"

  # 4. The sun seen directly: every actual sun (unit radiance), no interreflection.
  rcontrib -n "$NPROC" -h -I+ -ab 0 $DIR -faf -M suns1.mod suns1.oct < sensors.pts > sun_direct.dat
  t2=$(date +%s); echo "direct sun: $((t2 - t1)) s"
  echo "$start $t0 $t1 $t2" > times.txt
fi

if [ "$STAGE" = all ] || [ "$STAGE" = sun ]; then
  # (STAGE=sun redoes step 5 and the assembly in an existing WORK_DIR.)
  read start t0 t1 t2 < times.txt
  NS=$(wc -l < sensors.pts)
  $PY "$HERE/scripts/radiance_annual_reference.py" prepare "$WORK"
  oconv room.rad sunsf.rad > sunsf.oct
  t2b=$(date +%s)
  # 5. The sun's interreflected light: the actual suns that can shine through the window (unit
  #    radiance), all bounces (SUN_REPS estimates) and the direct part alone (subtracted).
  repeat sensors.pts "$SUN_REPS" > sensors_sun.pts
  rcontrib -n "$NPROC" -h -I+ $AMB_SUN -ad "$SUN_AD" $DIR -faf -M sunsf.mod sunsf.oct \
    < sensors_sun.pts > sunsf_ab.dat
  rcontrib -n "$NPROC" -h -I+ -ab 0 $DIR -faf -M sunsf.mod sunsf.oct < sensors.pts > sunsf_ab0.dat
  t3=$(date +%s); echo "sun interreflections: $((t3 - t2b)) s"

  cat > settings.json <<EOF
{"radiance": "$(cat radiance_version.txt)",
 "sky": "gendaymtx -m 4 -c 1 1 1 -s (MF 4, 2305 sky patches + ground, reflectance 0.2)",
 "sky_coefficients": "rcontrib -I+ $AMB -ad $SKY_AD, $SKY_REPS estimates per sensor",
 "sun_direct": "rcontrib -I+ -ab 0 $DIR, every gendaymtx -D sun",
 "sun_interreflected": "rcontrib -I+ $AMB_SUN -ad $SUN_AD $DIR minus -ab 0, the actual suns in front of the south wall, $SUN_REPS estimates per sensor",
 "seconds": {"sky_coefficients": $((t1 - t0)), "sun_direct": $((t2 - t1)), "sun_interreflected": $((t3 - t2b)), "total_rcontrib": $((t1 - t0 + t2 - t1 + t3 - t2b))},
 "threads": $NPROC}
EOF
  $PY "$HERE/scripts/radiance_annual_reference.py" assemble "$WORK" "$OUT" "$SKY_REPS" "$SUN_REPS" "$NS" settings.json
fi

# 6. Perez skies of gendaylit -W for a few Chicago hours, sampled on a grid of directions.
if [ "$STAGE" = all ] || [ "$STAGE" = perez ]; then
  $PY "$HERE/scripts/radiance_gendaylit_perez.py" "$EPW" "$OUT_PEREZ/hours.json"
fi
