#!/usr/bin/env bash
# `make platforms`: the README's commands on every supported Debian, as a new user runs them.
#
# For each platform, a minimal Debian root made with debootstrap from the machine's package
# registry (kept in $PLATFORMS_DIR/roots between runs; only apt, make, git, g++ and the CA
# certificates are added to it), a fresh clone of this repository's HEAD in it, and, as root in
# the chroot: `make setup`, `make build` (-Wall -Wextra: warnings counted), the core gtests, one
# short scenario bag made (make_bag) and localized (scripts/evaluate.py: replay_pipeline + evo).
# Prints one table (also $PLATFORMS_DIR/results.md): platform, compiler, Ceres, Embree, PCL,
# Python, build, warnings, gtests, bag sha256, time to localize, x-y APE.
#
#   scripts/platforms.sh [debian11 debian11-gcc9 debian12 debian13]   (default: all four)
#   PLATFORMS_DIR=~/.cache/is_graphs/platforms  PLATFORMS_SCENARIO=bags/D5_rotated_short.yaml
#   PLATFORMS_FROM=head (a clone of HEAD) | worktree (the working tree, uncommitted files too)
#
# Needs root (debootstrap, chroot, mount) and about 4 GB per root; 15-25 minutes per platform
# on 2 cores the first time. Too long for CI: run it before a change to build files, the apt list
# or the Python requirements lands.
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
repo="$(pwd)"
dir="$(realpath -m "${PLATFORMS_DIR:-${HOME}/.cache/is_graphs/platforms}")"
scenario="${PLATFORMS_SCENARIO:-bags/D5_rotated_short.yaml}"
from="${PLATFORMS_FROM:-head}"
mirror="${PLATFORMS_MIRROR:-$(sed -n 's/^URIs: *//p' /etc/apt/sources.list.d/debian.sources 2>/dev/null | head -n1)}"
mirror="${mirror:-http://deb.debian.org/debian}"
platforms=("$@")
((${#platforms[@]})) || platforms=(debian11 debian11-gcc9 debian12 debian13)

die() { echo "platforms: error: $*" >&2; exit 1; }
[ "$(id -u)" = 0 ] || die "needs root (debootstrap, chroot and mount)"
[ -f "${scenario}" ] || die "no scenario ${scenario}"
if ! command -v debootstrap >/dev/null; then
  echo "platforms: installing debootstrap"
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq debootstrap >/dev/null
fi

suite_of() {
  case "$1" in
    debian11*) echo bullseye ;; debian12*) echo bookworm ;; debian13*) echo trixie ;;
    *) die "unknown platform '$1' (debian11, debian11-gcc9, debian12, debian13)" ;;
  esac
}

mounted=()
cleanup() {
  local m
  for m in "${mounted[@]}"; do umount -R -l "$m" 2>/dev/null || true; done
  mounted=()
}
trap cleanup EXIT

# A minimal root with apt, make, git, g++ (and the registry's configuration), made once.
make_root() {
  local suite=$1 root=$2
  [ -f "${root}/.is_graphs_root" ] && return 0
  echo "platforms: ${suite}: debootstrap into ${root} (once)"
  rm -rf "${root}"
  mkdir -p "$(dirname "${root}")"
  debootstrap --variant=minbase "${suite}" "${root}" "${mirror}" > "${root}.debootstrap.log" 2>&1 \
    || die "debootstrap ${suite} failed, see ${root}.debootstrap.log"
  printf 'deb %s %s main\ndeb %s %s-updates main\n' "${mirror}" "${suite}" "${mirror}" "${suite}" \
    > "${root}/etc/apt/sources.list"
  # The machine's registry settings, pip's and the CA certificates it needs.
  cp /etc/apt/apt.conf.d/99artifact-registry "${root}/etc/apt/apt.conf.d/" 2>/dev/null || true
  cp -r /etc/apt/auth.conf.d/. "${root}/etc/apt/auth.conf.d/" 2>/dev/null || true
  [ -f /etc/pip.conf ] && cp /etc/pip.conf "${root}/etc/pip.conf"
  mkdir -p "${root}/usr/local/share/ca-certificates"
  cp -r /usr/local/share/ca-certificates/. "${root}/usr/local/share/ca-certificates/" 2>/dev/null || true
  in_root "${root}" "apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq \
    --no-install-recommends make git g++ ca-certificates >/dev/null && update-ca-certificates >/dev/null" \
    || die "${suite}: installing make, git, g++ failed"
  touch "${root}/.is_graphs_root"
}

mount_root() {
  local root=$1
  cp /etc/resolv.conf "${root}/etc/resolv.conf"
  mountpoint -q "${root}/proc" || { mount -t proc proc "${root}/proc"; mounted+=("${root}/proc"); }
  mountpoint -q "${root}/sys" || { mount -t sysfs sysfs "${root}/sys"; mounted+=("${root}/sys"); }
  if ! mountpoint -q "${root}/dev"; then
    mount --rbind /dev "${root}/dev" && mount --make-rslave "${root}/dev"
    mounted+=("${root}/dev")
  fi
}

in_root() {  # ROOT COMMAND: as root in the chroot, with a clean environment
  chroot "$1" /usr/bin/env -i HOME=/root PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    LANG=C.UTF-8 TERM=dumb /bin/bash -c "$2"
}

copy_source() {  # DEST
  rm -rf "$1"
  if [ "${from}" = worktree ]; then
    mkdir -p "$1"
    git ls-files -z -co --exclude-standard | tar --null -T - -cf - | tar -xf - -C "$1"
    (cd "$1" && git init -q && git add -A && git -c user.name=p -c user.email=p@p commit -qm worktree)
  else
    git clone -q "file://${repo}" "$1"
  fi
}

results="${dir}/results.md"
mkdir -p "${dir}"
rows=()
status=0
for platform in "${platforms[@]}"; do
  suite=$(suite_of "${platform}")
  root="${dir}/roots/${suite}"
  make_root "${suite}" "${root}"
  mount_root "${root}"
  work="/root/is_graphs-${platform}"
  copy_source "${root}${work}"
  log="${dir}/${platform}.log"
  echo "platforms: ${platform}: make setup, make build, test_core, ${scenario} (log: ${log})"
  start=$(date +%s)
  compiler_env=""
  if [ "${platform}" = debian11-gcc9 ]; then
    in_root "${root}" "dpkg -s g++-9 >/dev/null 2>&1 || DEBIAN_FRONTEND=noninteractive apt-get install -y -qq g++-9 >/dev/null"
    compiler_env="export CC=gcc-9 CXX=g++-9;"
  fi
  set +e
  in_root "${root}" "${compiler_env} cd ${work} && bash scripts/platform_check.sh ${scenario}" > "${log}" 2>&1
  rc=$?
  set -e
  [ "${rc}" = 0 ] || status=1
  minutes=$(( ($(date +%s) - start + 59) / 60 ))
  row=$(grep '^platform-row: ' "${log}" | tail -n1 | sed 's/^platform-row: //')
  [ -n "${row}" ] || row="| ? | ? | ? | ? | ? | failed (rc ${rc}), see ${log} | | | | | |"
  rows+=("| ${platform} ${row} ${minutes} min |")
  echo "platforms: ${platform}: rc ${rc}, ${minutes} min"
  cleanup
done

{
  echo "| platform | compiler | Ceres | Embree | PCL | Python | build | warnings | core gtests | bag sha256 (first 12) | localized after | x-y APE RMSE | time |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  printf '%s\n' "${rows[@]}"
} > "${results}"
cat "${results}"
exit "${status}"
