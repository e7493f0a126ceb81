#!/usr/bin/env python3
"""The whole pipeline's cost against the size of the building and the length of the run (`make bench`).

Runs replay_pipeline (the core S-Graph, matcher and merger, synchronous, no ROS transport) on
  - building size: D1 FZK-Haus, D3 office, D7 symmetric, D6 large, each over its first SIZE_SECONDS s;
  - run length:    D6 large over the first 60, 120 and 180 s of bags/D6_large.bag, and the first
                   360 and 540 s of a 540 s D6 bag (bags/D6_large.yaml x3) that this script makes
                   in .ws/bench/bags/ when it is missing (about 1 min, 2.9 GB; BENCH_LONG=0 skips);
(a missing scenario bag is made first, as `make bags` would), each BENCH_REPEATS times (median of each number over the repeats), then bench_matching (matching
against synthetic A-Graphs of 10-200 rooms). Prints a Markdown table and writes it with the raw
runs to .ws/bench/results.md and results.json.

Environment: BAGS_DIR (default bags/), BENCH_REPEATS (default 3), BENCH_LONG (default 1),
BENCH_MATCHING (default 1), BENCH_OUT (default .ws/bench).
"""
import json
import os
import re
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = os.path.join(ROOT, ".ws", "devel", "lib", "is_graphs")
STAGES = ["preprocess", "plane_extraction", "association", "rooms", "optimization", "matching", "merging"]
SHOWN = ["plane_extraction", "association", "optimization", "matching", "merging"]
SIZE_SECONDS = 150
LONG_SCALE = 3  # the long bag: bags/D6_large.yaml with its 180 s scaled by this


def fail(message):
    sys.exit("bench: error: " + message)


def scenario_field(yaml_path, key):
    """A top-level scalar of a scenario YAML (as scripts/bench_sgraph.sh reads it)."""
    with open(yaml_path) as f:
        for line in f:
            m = re.match(r"^%s:\s*(.*?)\s*(#.*)?$" % key, line)
            if m:
                return m.group(1).strip('"')
    fail("%s has no '%s:'" % (yaml_path, key))


def building_stats(building, storey):
    """Rooms, wall-surfaces and floor area (sum of the room footprints) from agraph_info."""
    out = run([os.path.join(BIN, "agraph_info"), building, "--storey", storey], "agraph_info")
    rooms = int(re.search(r"^\s*rooms:\s+(\d+)", out, re.M).group(1))
    surfaces = int(re.search(r"^\s*wall surfaces:\s+(\d+)", out, re.M).group(1))
    area = sum(float(a) for a in re.findall(r"\s([0-9.]+) m\^2", out))
    return {"rooms": rooms, "wall_surfaces": surfaces, "area_m2": round(area, 1)}


def run(cmd, what):
    p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode != 0:
        fail("%s failed (exit %d): %s\n%s" % (what, p.returncode, " ".join(cmd), p.stdout[-2000:]))
    return p.stdout


def make_bag(yaml, bag, extra=()):
    """make_bag into BAG.tmp, renamed when complete (an interrupted run leaves no half bag)."""
    os.makedirs(os.path.dirname(bag), exist_ok=True)
    run([os.path.join(BIN, "make_bag"), yaml, "-o", bag + ".tmp", "--quiet", *extra], "make_bag")
    os.replace(bag + ".tmp", bag)


def make_long_bag(out_dir):
    bag = os.path.join(out_dir, "bags", "D6_large_x%d.bag" % LONG_SCALE)
    yaml = os.path.join(ROOT, "bags", "D6_large.yaml")
    if os.path.exists(bag) and os.path.getmtime(bag) > os.path.getmtime(yaml):
        return bag
    print("bench: making the long run's bag %s (D6_large.yaml, duration x%d; about 1 min, 2.9 GB)"
          % (os.path.relpath(bag, ROOT), LONG_SCALE), flush=True)
    start = time.monotonic()
    make_bag(yaml, bag, ["--duration-scale", str(LONG_SCALE)])
    print("bench: made it in %.0f s" % (time.monotonic() - start), flush=True)
    return bag


def make_bag_if_missing(scenario, bag):
    """The scenario's bag as `make bags` makes it (same YAML and seed: the same bytes), if absent."""
    if os.path.exists(bag):
        return
    yaml = os.path.join(ROOT, "bags", scenario + ".yaml")
    print("bench: making the missing bag %s from %s (about 15 s)" % (bag, os.path.relpath(yaml, ROOT)),
          flush=True)
    make_bag(yaml, bag)


def plan(bags_dir, out_dir, long_run):
    """(series, scenario, bag, seconds) in a fixed order; prints what is missing."""
    runs, missing = [], []
    for name in ["D1_fzk_haus", "D3_office", "D7_symmetric", "D6_large"]:
        runs.append(("size", name, os.path.join(bags_dir, name + ".bag"), SIZE_SECONDS))
    for seconds in [60, 120, 180]:
        runs.append(("length", "D6_large", os.path.join(bags_dir, "D6_large.bag"), seconds))
    present = []
    for r in runs:
        building = scenario_field(os.path.join(ROOT, "bags", r[1] + ".yaml"), "building")
        if not os.path.exists(os.path.join(ROOT, building)):
            missing.append("%s: building %s is absent (../shared/bim not available)" % (r[1], building))
        else:
            make_bag_if_missing(r[1], r[2])
            present.append(r)
    if long_run:
        long_bag = make_long_bag(out_dir)
        for seconds in [360, 540]:
            present.append(("length", "D6_large", long_bag, seconds))
    return present, sorted(set(missing))


def replay(scenario, bag, seconds, prefix):
    yaml = os.path.join(ROOT, "bags", scenario + ".yaml")
    cmd = [os.path.join(BIN, "replay_pipeline"), bag, "--building", scenario_field(yaml, "building"),
           "--storey", scenario_field(yaml, "storey"), "--duration", str(seconds), "--out-prefix", prefix]
    run(cmd, "replay_pipeline")
    with open(prefix + ".json") as f:
        return json.load(f)


def median_of(runs):
    """Each number the median over the repeats; counts and graph sizes are the same in every run."""
    def med(get):
        return statistics.median(get(r) for r in runs)
    first = runs[0]
    out = {k: first[k] for k in ["bag_seconds", "keyframes", "planes", "rooms", "localized",
                                 "seconds_to_localize"]}
    out["real_time_factor"] = med(lambda r: r["real_time_factor"])
    out["wall_seconds"] = med(lambda r: r["wall_seconds"])
    out["peak_rss_mib"] = med(lambda r: r["peak_rss_mib"])
    out["stages"] = {}
    for s in STAGES:
        st = [r["stages"][s] for r in runs]
        out["stages"][s] = {"count": st[0]["count"],
                            "median_ms": statistics.median(x["median_ms"] for x in st),
                            "p99_ms": statistics.median(x["p99_ms"] for x in st),
                            "max_ms": statistics.median(x["max_ms"] for x in st)}
    return out


def table(rows):
    head = ("| series | scenario | building: rooms / wall-surfaces / m² | run [s] | keyframes | planes | "
            + " | ".join(s.replace("_", " ") + " median / p99 [ms]" for s in SHOWN)
            + " | RTF | peak RSS [MiB] |")
    lines = [head, "|" + "---|" * (head.count("|") - 1)]
    for r in rows:
        m, b = r["result"], r["building"]
        cells = [r["series"], r["scenario"], "%d / %d / %.0f" % (b["rooms"], b["wall_surfaces"], b["area_m2"]),
                 "%.0f" % m["bag_seconds"], str(m["keyframes"]), str(m["planes"])]
        for s in SHOWN:
            st = m["stages"][s]
            cells.append("%.2f / %.2f" % (st["median_ms"], st["p99_ms"]) if st["count"] else "–")
        cells += ["%.0f×" % m["real_time_factor"], "%.0f" % m["peak_rss_mib"]]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main():
    # Debian's ROS Python ahead of a pyenv one (the IFC conversion); ROS logs and caches in .ws/.
    os.environ["PATH"] = "/usr/bin:/bin:" + os.environ.get("PATH", "")
    os.environ.setdefault("ROS_HOME", os.path.join(ROOT, ".ws", "ros_home"))
    repeats = int(os.environ.get("BENCH_REPEATS", "3"))
    bags_dir = os.path.abspath(os.environ.get("BAGS_DIR", os.path.join(ROOT, "bags")))
    out_dir = os.path.abspath(os.environ.get("BENCH_OUT", os.path.join(ROOT, ".ws", "bench")))
    for tool in ["replay_pipeline", "agraph_info", "make_bag", "bench_matching"]:
        if not os.access(os.path.join(BIN, tool), os.X_OK):
            fail("%s not found in %s: build first (make build)" % (tool, BIN))
    os.makedirs(os.path.join(out_dir, "runs"), exist_ok=True)
    start = time.monotonic()
    runs, missing = plan(bags_dir, out_dir, os.environ.get("BENCH_LONG", "1") != "0")
    for m in missing:
        print("bench: skipped " + m, flush=True)
    if not runs:
        fail("no bag to run: every scenario's building is absent")
    stats_cache, rows = {}, []
    for series, scenario, bag, seconds in runs:
        yaml = os.path.join(ROOT, "bags", scenario + ".yaml")
        key = (scenario_field(yaml, "building"), scenario_field(yaml, "storey"))
        if key not in stats_cache:
            stats_cache[key] = building_stats(*key)
        results = []
        for i in range(repeats):
            prefix = os.path.join(out_dir, "runs", "%s_%s_%ds_%d" % (series, scenario, seconds, i))
            print("bench: %s %s %d s, run %d/%d" % (series, scenario, seconds, i + 1, repeats), flush=True)
            results.append(replay(scenario, bag, seconds, prefix))
        rows.append({"series": series, "scenario": scenario, "bag": bag, "seconds": seconds,
                     "building": stats_cache[key], "result": median_of(results), "runs": results})
    matching = ""
    if os.environ.get("BENCH_MATCHING", "1") != "0":
        print("bench: bench_matching (synthetic A-Graphs of 10-200 rooms)", flush=True)
        matching = run([os.path.join(BIN, "bench_matching")], "bench_matching")
    elapsed = time.monotonic() - start
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, stdout=subprocess.PIPE,
                            text=True).stdout.strip()
    md = table(rows) + "\n\nMedian of %d runs each; commit %s; %d cores; make bench took %.0f s.\n" % (
        repeats, commit or "?", os.cpu_count(), elapsed)
    if missing:
        md += "\nSkipped:\n" + "".join("- %s\n" % m for m in missing)
    if matching:
        md += "\nbench_matching:\n\n```\n" + matching.strip() + "\n```\n"
    print("\n" + md)
    with open(os.path.join(out_dir, "results.md"), "w") as f:
        f.write(md)
    with open(os.path.join(out_dir, "results.json"), "w") as f:
        json.dump({"commit": commit, "repeats": repeats, "cores": os.cpu_count(), "seconds": elapsed,
                   "skipped": missing, "rows": rows, "bench_matching": matching}, f, indent=2)
    print("bench: results in %s/results.md and results.json" % os.path.relpath(out_dir, ROOT))


if __name__ == "__main__":
    main()
