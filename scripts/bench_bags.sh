#!/usr/bin/env bash
# Times the generation of one bag and reports what it costs:
#
#   scripts/bench_bags.sh [SCENARIO.yaml] [--duration-scale S] [--compression none|lz4|bz2]
#
# Prints wall-clock seconds, the real-time factor (bag duration / generation time; the target
# is >= 10 on the 2-core reference machine), MB of bag per minute of data, and peak RSS.
# Default scenario: bags/D3_office.yaml. MAKE_BAG selects the binary as in make_bags.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
make_bag="${MAKE_BAG:-$(pwd)/.ws/devel/lib/is_graphs/make_bag}"
scenario="bags/D3_office.yaml"
if [ $# -gt 0 ] && [[ "$1" != -* ]]; then scenario="$1"; shift; fi
[ -x "${make_bag}" ] || { echo "bench_bags: ${make_bag} not found (set MAKE_BAG)" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "bench_bags: /usr/bin/time is missing (apt install time)" >&2; exit 2; }
work="$(mktemp -d)"
trap 'rm -rf "${work}"' EXIT
# Warm the IFC conversion cache so that only the simulation is timed.
"${make_bag}" "${scenario}" -o "${work}/warm.bag" --quiet --duration-scale 0.01 "$@" >/dev/null
rm -f "${work}/warm.bag"
/usr/bin/time -v -o "${work}/time.txt" "${make_bag}" "${scenario}" -o "${work}/bench.bag" --quiet "$@"
seconds="$(sed -n 's/.*Elapsed (wall clock) time (h:mm:ss or m:ss): //p' "${work}/time.txt" |
  awk -F: '{ if (NF == 3) print $1 * 3600 + $2 * 60 + $3; else print $1 * 60 + $2 }')"
rss_kb="$(sed -n 's/.*Maximum resident set size (kbytes): //p' "${work}/time.txt")"
cpu="$(sed -n 's/.*Percent of CPU this job got: //p' "${work}/time.txt")"
duration="$(PATH=/usr/bin:$PATH python3 -c "import rosbag,sys; b=rosbag.Bag(sys.argv[1]); print(b.get_end_time()-b.get_start_time())" "${work}/bench.bag")"
bytes="$(stat -c %s "${work}/bench.bag")"
awk -v s="${seconds}" -v d="${duration}" -v b="${bytes}" -v r="${rss_kb}" -v c="${cpu}" -v n="${scenario}" 'BEGIN {
  printf "scenario:           %s\n", n
  printf "bag duration:       %.1f s\n", d
  printf "generation time:    %.2f s (CPU %s)\n", s, c
  printf "real-time factor:   %.1f x (target >= 10)\n", d / s
  printf "bag size:           %.1f MB (%.1f MB per minute)\n", b / 1e6, b / 1e6 / (d / 60)
  printf "peak RSS:           %.1f MB\n", r / 1024
}'
