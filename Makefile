# is_graphs: the two commands are `make demo` (the main job) and `make test` (the whole suite).
# Both install what is missing (scripts/setup.sh), build the catkin workspace in .ws/ and run.
SHELL := /bin/bash
# Debian's ROS Python lives in /usr/bin/python3: keep it ahead of any pyenv or venv on PATH.
export PATH := /usr/bin:/bin:/usr/sbin:/sbin:$(PATH)
export ROS_HOME ?= $(CURDIR)/.ws/ros_home

.PHONY: all setup build demo map report test platforms screenshot bench-conversion buildings bags bags-short bench-bags bench bench-sgraph bench-matching bench-long evaluate clean format

all: build

setup:
	@bash scripts/setup.sh

build: setup
	@bash scripts/build.sh

demo: build  ## BIM=path/to/building.ifc to load another building
	@bash scripts/demo.sh

# The BIM as navigation maps for map_server (move_base, nav2): BIM=building.ifc (or .agraph.json),
# STOREY= one storey by name or index (default: every storey), MAP_DIR= (default .ws/maps),
# RESOLUTION= m per cell (0.05). Writes MAP_DIR/<file>_<storey>.yaml + .pgm (docs/navigation.md).
map: build
	@test -n "$(BIM)" || { echo "make map: give BIM=path/to/building.ifc [STOREY=name]" >&2; exit 1; }
	@.ws/devel/lib/is_graphs/bim_map "$(BIM)" -o "$${MAP_DIR:-.ws/maps}" \
	  $(if $(STOREY),--storey "$(STOREY)") $(if $(RESOLUTION),--resolution $(RESOLUTION))

# As built against as planned (issue 21): .ws/report/<name>/ deviations.csv, deviations.bcf,
# plan.png. SCENARIO=bags/X.yaml (default D4), or BAG=own.bag BIM=building.ifc [STOREY=..].
report: build
	@bash scripts/report.sh

test: build
	@bash scripts/test.sh

# The README's commands on Debian 11 (also with g++-9), 12 and 13, in debootstrap roots kept in
# ~/.cache/is_graphs/platforms: setup, build, the core gtests, D5_short made and localized; one
# table (docs/platforms.md). Needs root; 15-25 min per platform the first time. PLATFORMS="debian13".
platforms:
	@bash scripts/platforms.sh $(PLATFORMS)

# The README's pictures: rviz under Xvfb on the demo's bag -> docs/images/isgraph.png, and the
# trajectory plot -> docs/images/trajectory.png. SCENARIO=, RATE=1, SHOT_AT=130 (bag seconds).
screenshot: build
	@bash scripts/screenshot.sh

# Regenerates bim/*.ifc from bim/layouts/*.yaml.
buildings: setup
	@.venv/bin/python3 scripts/make_building.py --all

# Per-stage latency, real-time factor and peak memory of the whole pipeline (replay_pipeline)
# against building size and run length; makes a 540 s D6 bag in .ws/bench/bags (BENCH_LONG=0: not).
# BAGS_DIR=dir, BENCH_REPEATS=3. Results: .ws/bench/results.md, results.json.
bench: build
	@.venv/bin/python3 scripts/bench.py

# Conversion time and peak memory for the real IFC files and the project's buildings.
bench-conversion: setup
	@bash scripts/bench_conversion.sh

# Scenario bags from bags/*.yaml (up-to-date bags are kept; D1/D2 need ../shared/bim).
bags: build
	@bash scripts/make_bags.sh

bags-short: build
	@bash scripts/make_bags.sh '*_short'

# Bag generation time, real-time factor, size and peak memory: SCENARIO=bags/X.yaml
bench-bags: build
	@bash scripts/bench_bags.sh $(SCENARIO)

# S-Graph quality and speed on the full-length scenario bags present (make bags first).
bench-sgraph: build
	@bash scripts/bench_sgraph.sh '*' '!*_short'

# Matching time for S-Graphs of 3, 10, 20 rooms against A-Graphs of 10, 60, 200 rooms.
bench-matching: build
	@.ws/devel/lib/is_graphs/bench_matching

# An hour-long run (issue 22) without a bag: bench_long feeds the simulator's scans of
# bags/long/L1_large_hour.yaml (the D6 walk looped for 60 min) straight into the pipeline and
# prints per-10-minute p50/p99 of optimization, matching, merging, the pipeline's real-time
# factor and peak RSS (about 20-30 min). LONG_SCENARIO=, LONG_DURATION=s, LONG_WINDOW=s.
# The multi-storey hour (the tower, up two flights and back down, whole building):
# LONG_SCENARIO=bags/long/L2_tower_hour.yaml.
bench-long: build
	@nice .ws/devel/lib/is_graphs/bench_long $${LONG_SCENARIO:-bags/long/L1_large_hour.yaml} \
	  --root $(CURDIR) $${LONG_DURATION:+--duration $$LONG_DURATION} --window $${LONG_WINDOW:-600}

# Localization (replay_pipeline: the core the nodes run) on every full-length scenario bag
# present, against ground truth and the odometry / S-Graph baselines: .ws/evaluate/results.md,
# results.json and per-dataset plots. Missing bags are listed (make bags makes them).
evaluate: build
	@.venv/bin/python3 scripts/evaluate.py

format:
	@clang-format -i $$(git ls-files '*.h' '*.cpp')

clean:
	rm -rf .ws
