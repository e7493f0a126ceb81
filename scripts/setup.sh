#!/usr/bin/env bash
# Installs what the project needs, idempotently and quickly when all is there:
#   Debian packages (scripts/apt-packages.txt) and a venv (.venv) with scripts/requirements.txt.
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"

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

stamp=.venv/.requirements.sha256
want=$(sha256sum scripts/requirements.txt | cut -d' ' -f1)
if [ ! -x .venv/bin/python3 ] || [ "$(cat "$stamp" 2>/dev/null)" != "$want" ]; then
  echo "setup: creating the Python venv .venv (system site packages + scripts/requirements.txt)"
  /usr/bin/python3 -m venv --system-site-packages .venv
  .venv/bin/python3 -m pip install -q --disable-pip-version-check -r scripts/requirements.txt
  echo "$want" > "$stamp"
fi
