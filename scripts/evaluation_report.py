"""results.md and results.json of `make evaluate` (scripts/evaluate.py) from its per-dataset
numbers."""
import json
import os
import subprocess

DASH = "–"


def _xy_yaw(numbers):
    if not numbers:
        return DASH, DASH
    return (f"{numbers['ape_xy_rmse_m']:.3f} / {numbers['ape_xy_max_m']:.3f}",
            f"{numbers['yaw_rmse_deg']:.2f} / {numbers['yaw_max_deg']:.2f}")


def _z(numbers):
    if not numbers or "ape_z_rmse_m" not in numbers:
        return DASH
    return f"{numbers['ape_z_rmse_m']:.3f} / {numbers['ape_z_max_m']:.3f}"


def _rmse(numbers):
    if not numbers:
        return DASH
    return f"{numbers['ape_xy_rmse_m']:.3f} m, {numbers['yaw_rmse_deg']:.2f}°"


def _commit(repo):
    try:
        head = subprocess.run(["git", "-C", repo, "rev-parse", "--short", "HEAD"],
                              capture_output=True, text=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", repo, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True).stdout.strip()
        return head + (" (with uncommitted changes)" if dirty else "")
    except OSError:
        return "unknown"


def table_one(results):
    lines = ["| dataset | iS-Graphs (ours), after localization | S-Graph alone, online | "
             "S-Graph alone, final keyframes | odometry |", "|---|---|---|---|---|"]
    for name, r in results.items():
        ours = _rmse(r.get("isgraphs")) if r["localized"] else "not localized"
        lines.append(f"| {name} | {ours} | {_rmse(r.get('sgraph_online'))} | "
                     f"{_rmse(r.get('sgraph'))} | {_rmse(r.get('odometry'))} |")
    return lines


def details(results):
    lines = ["| dataset | localized | first UNIQUE [s] | walked to first UNIQUE [m] | first pose "
             "in B | UNIQUE matches / wrong | x-y APE RMSE / max [m] | z APE RMSE / max [m] | "
             "yaw RMSE / max [°] | map cloud RMSE / median [m] (points used) | replay [s] (RTF, "
             "peak MiB) |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for name, r in results.items():
        loc = "yes" if r["localized"] else "**no**"
        if r["localized"] and not r["localized_at_end"]:
            loc += " (lost at the end)"
        first = (f"{r['first_unique_s']:.1f} | {r['first_unique_m']:.1f}"
                 if "first_unique_s" in r else f"{DASH} | {DASH}")
        pose = (f"{r['seconds_to_localize']:.1f} s, {r['distance_to_localize']:.1f} m"
                if r["localized"] else DASH)
        xy, yaw = _xy_yaw(r.get("isgraphs"))
        c = r.get("map_cloud_error")
        cloud = (f"{c['rmse_m']:.3f} / {c['median_m']:.3f} ({100 * c['used_share']:.0f} % of "
                 f"{c['points']})" if c else DASH)
        run = f"{r['replay_seconds']:.0f} ({r['real_time_factor']:.0f}×, {r['peak_rss_mib']:.0f})"
        wrong = f"{r['wrong_matches']}"
        if r.get("localizer_storey", None) == "":  # the whole building loaded (issue 22)
            wrong += f" (whole building; {r.get('wrong_storey_matches', 0)} on another storey)"
        lines.append(f"| {name} | {loc} | {first} | {pose} | {r['unique_matches']} / "
                     f"{wrong} | {xy} | {_z(r.get('isgraphs'))} | {yaw} | {cloud} | "
                 f"{run} |")
    return lines


def storeys(results):
    """Issue 22: per storey walked, for the runs with the whole building loaded."""
    lines = ["| dataset | storey | arrived [s] | localized on it after [s] | walked [m] |",
             "|---|---|---|---|---|"]
    for name, r in results.items():
        if r.get("localizer_storey", None) != "":
            continue
        for s in r.get("storeys", []):
            after = s["localized_after_s"]
            cells = ("never", DASH) if after is None else (f"{after:.1f}",
                                                          f"{s['localized_after_m']:.1f}")
            lines.append(f"| {name} | {s['storey']} | {s['arrived_s']:.1f} | {cells[0]} | "
                         f"{cells[1]} |")
    return lines if len(lines) > 2 else []


BASELINES = (("sgraph_online", "S-Graph online"), ("sgraph", "S-Graph final keyframes"),
             ("odometry", "odometry"))


def baselines(results):
    header = [f"{label}{when}" for when in ("", ", after localization") for _, label in BASELINES]
    lines = ["| dataset | " + " | ".join(header) + " |", "|---" * (len(header) + 1) + "|"]
    for name, r in results.items():
        cells = []
        for suffix in ("", "_after_localization"):
            for key, _ in BASELINES:
                xy, yaw = _xy_yaw(r.get(key + suffix))
                cells.append(DASH if xy == DASH else f"{xy}; {yaw}")
        lines.append(f"| {name} | " + " | ".join(cells) + " |")
    return lines


def write_reports(results, missing, out_dir):
    repo = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
    os.makedirs(out_dir, exist_ok=True)
    commit = _commit(repo)
    with open(os.path.join(out_dir, "results.json"), "w") as f:
        json.dump({"commit": commit, "missing_bags": missing, "datasets": results}, f, indent=2,
                  sort_keys=True)
    notes = [f"- {name}: {r['note']}" for name, r in results.items() if r.get("note")]
    notes += [f"- {name}: bag missing, not evaluated (`make bags`)" for name in missing]
    md = [f"# make evaluate (code {commit})", "",
          "APE without alignment (evo) against `ground_truth/pose`: x-y RMSE, yaw RMSE. "
          "iS-Graphs: the pose in the BIM frame from the first one (after the first merged "
          "UNIQUE match) on, at every odometry reading. The baselines over the whole bag, put "
          "in the BIM frame with the true start pose: S-Graph online (its map <- odom at that "
          "moment times the odometry, at every reading: what sgraph_node's tf gives), S-Graph "
          "final keyframes (its optimized keyframe poses at the end of the bag, smoothed with "
          "everything seen later: not causal), raw odometry.", ""] + table_one(results) + [
          "", "## Per dataset", "",
          "Wrong = UNIQUE matches whose B_x_M is > 0.5 m (anywhere on the map) or > 5° from the "
          "truth (the S-Graph's keyframes aligned to ground truth in x, y, yaw, at that "
          "revision). Map cloud: the keyframe clouds (10 cm voxels) put in the BIM frame with "
          "the final merged B_x_M; a point is used when it projects onto an A-Graph "
          "wall-surface (10 cm inside its extent: no floor or ceiling) within 0.3 m of it.", ""]
    md += details(results)
    per_storey = storeys(results)
    if per_storey:
        md += ["", "## Per storey (whole building loaded)", "",
               "From the robot's arrival on a storey (the truth's height, first on the storey it "
               "starts on) to its first pose in B within 0.5 m (x-y) and 1 m (z) of the truth "
               "there; 0 when it came up or down the stairs already localized."] + [""] + per_storey
    md += ["", "## Baselines (x-y RMSE / max [m]; yaw RMSE / max [°])", ""] + baselines(results)
    if notes:
        md += ["", "## Notes", ""] + notes
    md += ["", "Plots: `<dataset>/trajectory.png` (over the BIM plan, the pose coloured by its "
           "error), `<dataset>/error.png` (error over time, every method)."]
    path = os.path.join(out_dir, "results.md")
    with open(path, "w") as f:
        f.write("\n".join(md) + "\n")
    return path
