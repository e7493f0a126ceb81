#!/usr/bin/env bash
# Installs what the project needs, idempotently and quickly when all is there:
#   Debian packages (scripts/apt-packages.txt) and a venv (.venv) with scripts/requirements.in.
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"

# The platforms setup knows (docs/platforms.md): Debian 11, 12 and 13 ship ROS 1 and every
# package of scripts/apt-packages.txt under the same names. Elsewhere (Ubuntu with ROS Noetic or
# ROS-O) the names differ: use rosdep (docs/platforms.md, "Your own workspace").
. /etc/os-release 2>/dev/null || true
case "${ID:-}:${VERSION_ID:-}" in
  debian:11 | debian:12 | debian:13) ;;
  *) echo "setup: warning: ${PRETTY_NAME:-this system} is not Debian 11, 12 or 13, the platforms" \
       "scripts/apt-packages.txt is written for; on Ubuntu with ROS 1 use" \
       "'rosdep install --from-paths src --ignore-src -y' instead" >&2 ;;
esac

mapfile -t packages < <(grep -v '^\s*#' scripts/apt-packages.txt | sed '/^\s*$/d')
missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if ((${#missing[@]})); then
  echo "setup: installing ${#missing[@]} Debian packages: ${missing[*]}"
  SUDO=""
  if [ "$(id -u)" != 0 ]; then
    command -v sudo >/dev/null || { echo "setup: error: need root or sudo to apt-get install" >&2; exit 1; }
    SUDO=sudo
  fi
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get update -qq
  unknown=()
  for p in "${missing[@]}"; do
    candidate=$(apt-cache policy "$p" 2>/dev/null | sed -n 's/^ *Candidate: *//p')
    [ -n "${candidate}" ] && [ "${candidate}" != "(none)" ] || unknown+=("$p")
  done
  if ((${#unknown[@]})); then
    echo "setup: error: ${PRETTY_NAME:-this system}'s package lists have no ${unknown[*]}" \
      "(scripts/apt-packages.txt; supported: Debian 11, 12, 13)" >&2
    exit 1
  fi
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# roslaunch resolves "localhost"; a bare system (a minimal container or chroot) may lack the entry.
if ! getent hosts localhost >/dev/null 2>&1; then
  if [ "$(id -u)" = 0 ]; then
    echo "setup: 'localhost' does not resolve (ROS needs it): adding '127.0.0.1 localhost' to /etc/hosts"
    echo "127.0.0.1 localhost" >> /etc/hosts
  else
    echo "setup: warning: 'localhost' does not resolve; roslaunch and rostest will fail" >&2
  fi
fi

# The venv: scripts/requirements.in, pinned by scripts/constraints/py3.X.txt for the Python of
# /usr/bin/python3 (3.9 to 3.13). On 3.8 (Ubuntu 20.04, Noetic) IfcOpenShell has no build: the
# venv gets the rest (requirements.in's markers) and IFC files are converted on another machine.
pyver=$(/usr/bin/python3 -c 'import sys; print("%d.%d" % sys.version_info[:2])')
constraints=scripts/constraints/py${pyver}.txt
case "$pyver" in
  3.9 | 3.10 | 3.11 | 3.12 | 3.13) ;;
  3.8)
    echo "setup: warning: /usr/bin/python3 is Python 3.8; supported: 3.9 to 3.13. IfcOpenShell" \
      "has no build for 3.8, so IFC conversion is unavailable here: convert on a machine with" \
      "Python 3.9-3.13 (scripts/ifc_to_agraph.py BUILDING.ifc -o OUT/BUILDING) and copy" \
      "OUT/BUILDING.agraph.json and OUT/BUILDING.obj here (bim:=.../BUILDING.agraph.json)." \
      "The venv gets the rest (evo, matplotlib, xmlschema). See docs/platforms.md." >&2
    ;;
  *)
    echo "setup: error: /usr/bin/python3 is Python $pyver; the project's Python packages support" \
      "Python 3.9 to 3.13 (3.8 without IFC conversion). See docs/platforms.md." >&2
    exit 1
    ;;
esac
stamp=.venv/.requirements.sha256
want=$({ echo "python $pyver"; cat scripts/requirements.in "$constraints"; } | sha256sum | cut -d' ' -f1)
if [ ! -x .venv/bin/python3 ] || [ "$(cat "$stamp" 2>/dev/null)" != "$want" ]; then
  # A venv of another Python (the system's was upgraded) is made anew, not installed over.
  clear=()
  venv_ver=$(sed -n 's/^version *= *\([0-9]*\.[0-9]*\).*/\1/p' .venv/pyvenv.cfg 2>/dev/null || true)
  if [ -n "$venv_ver" ] && [ "$venv_ver" != "$pyver" ]; then clear=(--clear); fi
  echo "setup: creating the Python venv .venv (Python $pyver: system site packages +" \
    "scripts/requirements.in, pinned by $constraints)"
  /usr/bin/python3 -m venv --system-site-packages "${clear[@]}" .venv
  .venv/bin/python3 -m pip install -q --disable-pip-version-check --only-binary=:all: \
    -r scripts/requirements.in -c "$constraints"
  echo "$want" > "$stamp"
fi
