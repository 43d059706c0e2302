#!/usr/bin/env bash
# Installs the Debian packages Fenestra builds and tests with; does nothing when all are present.
set -euo pipefail

packages=(
  cmake g++ make pkg-config
  libembree-dev pybind11-dev libeigen3-dev libopenimageio-dev libtbb-dev
  nlohmann-json3-dev libtinyobjloader-dev libgtest-dev libbenchmark-dev
  libhowardhinnant-date-dev
  python3-dev python3-numpy python3-scipy python3-pytest python3-astropy python3-matplotlib
  python3-distributed
  blender xvfb xdotool
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "Installing: ${missing[*]}"
if [ "$(id -u)" -ne 0 ]; then
  echo "error: missing Debian packages (${missing[*]}); run as root or install them with apt-get" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
