#!/usr/bin/env bash
# Makes the packaging venv (requirements/packaging.txt) at $1 from a Python 3.11 that is not
# Debian's (pyenv's), once: it is remade only when the pins change. Prints the venv's python.
set -euo pipefail
venv=$(realpath -m "$1")
pins=$(dirname "$0")/../requirements/packaging.txt
python=${FENESTRA_PACKAGING_PYTHON:-}
if [ -z "$python" ]; then
  for p in "$(command -v pyenv >/dev/null && pyenv root 2>/dev/null)"/versions/3.11*/bin/python3.11 \
           "$HOME"/.pyenv/versions/3.11*/bin/python3.11; do
    [ -x "$p" ] && python=$p
  done
fi
if [ -z "$python" ]; then
  echo "packaging-venv: no Python 3.11 besides Debian's found (pyenv's); set FENESTRA_PACKAGING_PYTHON" >&2
  exit 1
fi
if [ -x "$venv/bin/python" ] && cmp -s "$pins" "$venv/pins.txt"; then
  echo "$venv/bin/python"; exit 0
fi
rm -rf "$venv"
"$python" -m venv "$venv" >&2
"$venv/bin/pip" install -q --disable-pip-version-check -r "$pins" >&2
cp "$pins" "$venv/pins.txt"
echo "$venv/bin/python"
