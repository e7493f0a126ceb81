#!/usr/bin/env python3
"""As-built against as-planned report (issue 21, docs/deviations.md).

From replay_pipeline's --deviations JSON (each IFC wall's status under the final merge, and each
door or opening PRESENT / CLOSED / NOT_SEEN), writes into OUT: deviations.csv (walls, then doors),
deviations.bcf (BCF 2.1: a topic per wall not AS_PLANNED and per door CLOSED, bcf_writer.py) and
plan.png (the storey, walls coloured by status, doors marked by status, the robot's path). With --scenario (a bags/
YAML), compares against the simulator's known deviations (scene.deviations) and writes
truth.json; prints a summary either way.

  deviation_report.py DEVIATIONS.json OUT [--scenario bags/X.yaml] [--title NAME] [--path TUM]
"""
import argparse
import csv
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import bcf_writer  # noqa: E402
import deviation_truth  # noqa: E402

COLOURS = {"AS_PLANNED": "#2ca02c", "MOVED": "#ff7f0e", "NOT_BUILT": "#d62ad6",
           "EXTRA": "#1f5fff", "NOT_SEEN": "#b0b0b0"}
DOOR_COLOURS = {"PRESENT": "#2ca02c", "CLOSED": "#d62728", "NOT_SEEN": "#b0b0b0"}
# A door's row: wall_id the wall it is in, length_m its width, start its position (end empty).
CSV_FIELDS = ["guid", "wall_id", "name", "status", "offset_m", "angle_deg", "sigma_m",
              "length_m", "start_x", "start_y", "end_x", "end_y", "rays_through",
              "element", "doorway_id", "walked_through", "blocked_views"]


def key(w):
    """A wall's key for the user: its IFC GlobalId, else its A-Graph id (EXTRA: none)."""
    if w["guid"]:
        return w["guid"]
    return "wall#%d" % w["wall_id"] if w["wall_id"] >= 0 else ""


def door_items(doors, walls):
    """The doors as report items: "element" door / opening, start-end the opening's span along
    its wall (bcf_writer and the snapshots draw them like walls)."""
    along = {}
    for w in walls:
        dx, dy = w["end"][0] - w["start"][0], w["end"][1] - w["start"][1]
        n = math.hypot(dx, dy)
        if w["wall_id"] >= 0 and n > 0:
            along[w["wall_id"]] = (dx / n, dy / n)
    items = []
    for d in doors:
        tx, ty = along.get(d["wall_id"], (1.0, 0.0))
        (x, y), h = d["position"], 0.5 * d["width_m"]
        items.append(dict(d, element="opening" if d.get("kind") == "opening" else "door",
                          start=[x - h * tx, y - h * ty], end=[x + h * tx, y + h * ty],
                          length_m=d["width_m"], offset_m=0.0, angle_deg=0.0, sigma_m=0.0))
    return items


def write_csv(walls, doors, path):
    with open(path, "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(CSV_FIELDS)
        for w in walls:
            out.writerow([w["guid"], w["wall_id"], w["name"], w["status"],
                          "%.4f" % w["offset_m"], "%.3f" % w["angle_deg"], "%.4f" % w["sigma_m"],
                          "%.3f" % w["length_m"], "%.3f" % w["start"][0], "%.3f" % w["start"][1],
                          "%.3f" % w["end"][0], "%.3f" % w["end"][1], w["rays_through"],
                          "wall", "", "", ""])
        for d in doors:
            out.writerow([d["guid"], d["wall_id"], d["name"], d["status"], "", "", "",
                          "%.3f" % d["width_m"], "%.3f" % d["position"][0],
                          "%.3f" % d["position"][1], "", "", d["rays_through"], d["element"],
                          d["doorway_id"], d["walked_through"], d["blocked_views"]])


def draw(ax, walls, path, focus=None, doors=()):
    """The storey: every wall by status (MOVED drawn at where it was built), the doors by
    status (a filled square CLOSED, a circle else), the path."""
    for w in walls:
        (x0, y0), (x1, y1) = w["start"], w["end"]
        colour = COLOURS[w["status"]]
        width = 5 if w is focus else 2.5
        ax.plot([x0, x1], [y0, y1], color=colour, lw=width, solid_capstyle="butt", zorder=2)
        if w["status"] == "MOVED":  # the built position, dashed
            bx0, by0, bx1, by1 = bcf_writer.built_segment(w)
            ax.plot([bx0, bx1], [by0, by1], color=colour, lw=1.2, ls="--", zorder=3)
    for d in doors:
        closed = d["status"] == "CLOSED"
        ax.plot([d["position"][0]], [d["position"][1]], marker="s" if closed else "o",
                ms=9 if d is focus else 6, mfc=DOOR_COLOURS[d["status"]] if closed else "none",
                mec=DOOR_COLOURS[d["status"]], mew=1.5, ls="none", zorder=4)
    if path:
        ax.plot([p[1] for p in path], [p[2] for p in path], color="k", lw=0.8, alpha=0.6,
                zorder=1)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m] (bim)")
    ax.set_ylabel("y [m]")


def plan_png(walls, doors, path, title, out):
    fig, ax = plt.subplots(figsize=(10, 7), dpi=100)
    draw(ax, walls, path, doors=doors)
    for w in walls:
        if w["status"] in ("MOVED", "NOT_BUILT", "EXTRA"):
            mx = 0.5 * (w["start"][0] + w["end"][0])
            my = 0.5 * (w["start"][1] + w["end"][1])
            label = w["name"] or w["status"]
            if w["status"] == "MOVED":
                label += " %+.0f cm %+.1f°" % (100 * w["offset_m"], w["angle_deg"])
            ax.annotate(label, (mx, my), fontsize=7, ha="center", va="bottom")
    for d in doors:
        if d["status"] == "CLOSED":
            ax.annotate((d["name"] or "door") + " CLOSED", tuple(d["position"]), fontsize=7,
                        ha="center", va="top", color=DOOR_COLOURS["CLOSED"])
    handles = [plt.Line2D([], [], color=c, lw=3, label=s) for s, c in COLOURS.items()]
    handles += [plt.Line2D([], [], color=c, marker="s" if s == "CLOSED" else "o", ls="none",
                           mfc=c if s == "CLOSED" else "none", label="door " + s)
                for s, c in DOOR_COLOURS.items()]
    handles.append(plt.Line2D([], [], color="k", lw=0.8, label="robot path"))
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8)
    ax.set_title(title)
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)


def snapshot_png(walls, doors, path, focus, out):
    """A top view around one wall or door: the BCF topic's snapshot."""
    fig, ax = plt.subplots(figsize=(4, 4), dpi=80)
    draw(ax, walls, path, focus, doors)
    (x0, y0), (x1, y1) = focus["start"], focus["end"]
    cx, cy, r = 0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.5 * math.hypot(x1 - x0, y1 - y0) + 1.5
    ax.set_xlim(cx - r, cx + r)
    ax.set_ylim(cy - r, cy + r)
    ax.set_title(bcf_writer.topic_title(focus), fontsize=8)
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)


def summary(walls, doors=()):
    counts = {}
    for w in walls:
        counts[w["status"]] = counts.get(w["status"], 0) + 1
    lines = ["deviations: " + ", ".join("%s %d" % (s, counts.get(s, 0)) for s in COLOURS)]
    if doors:
        lines.append("doors and openings: " + ", ".join(
            "%s %d" % (s, sum(1 for d in doors if d["status"] == s)) for s in DOOR_COLOURS))
    for w in walls:
        if w["status"] == "MOVED":
            lines.append("  MOVED     %-24s %-12s offset %+6.1f cm (σ %.1f cm)  turned %+5.1f°" % (
                key(w), w["name"], 100 * w["offset_m"], 100 * w["sigma_m"], w["angle_deg"]))
        elif w["status"] == "NOT_BUILT":
            lines.append("  NOT_BUILT %-24s %-12s (%d sight lines through it)" % (
                key(w), w["name"], w["rays_through"]))
        elif w["status"] == "EXTRA":
            lines.append("  EXTRA     %.1f m from (%.2f, %.2f) to (%.2f, %.2f)" % (
                w["length_m"], w["start"][0], w["start"][1], w["end"][0], w["end"][1]))
    for d in doors:
        if d["status"] == "CLOSED":
            lines.append("  CLOSED    %-24s %-12s at (%.2f, %.2f) (%d views saw it covered)" % (
                d["guid"] or "doorway#%d" % d["doorway_id"], d["name"], d["position"][0],
                d["position"][1], d["blocked_views"]))
    return "\n".join(lines)


def read_tum_txy(path):
    """A TUM file's rows as [t, x, y] (comment lines skipped)."""
    with open(path) as f:
        return [[float(v) for v in line.split()[:3]] for line in f
                if line.strip() and not line.startswith("#")]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("deviations")
    ap.add_argument("out")
    ap.add_argument("--scenario", help="bags/X.yaml: compare with its known deviations")
    ap.add_argument("--title", default="")
    ap.add_argument("--path", help="a TUM file of the robot's poses in the bim frame (the "
                    "plan's path; default: the S-Graph's keyframes under the final merge)")
    ap.add_argument("--truth-path", help="with --scenario: a TUM file of the robot's true poses "
                    "in the bim frame; added walls never in view are counted apart")
    args = ap.parse_args(argv)
    with open(args.deviations) as f:
        data = json.load(f)
    walls, path = data["walls"], data.get("path", [])
    if args.path:
        path = read_tum_txy(args.path)
    unnamed = [w["wall_id"] for w in walls if w["wall_id"] >= 0 and not w["guid"]]
    if unnamed:
        print("deviation_report: warning: %d walls have no IFC GlobalId (A-Graph ids %s): "
              "reported by A-Graph id, without a BCF component" % (len(unnamed), unnamed[:5]),
              file=sys.stderr)
    os.makedirs(args.out, exist_ok=True)
    title = args.title or data.get("building", "")
    doors = door_items(data.get("doorways", []), walls)
    write_csv(walls, doors, os.path.join(args.out, "deviations.csv"))
    plan_png(walls, doors, path, "%s: as built vs as planned" % title,
             os.path.join(args.out, "plan.png"))
    bcf_writer.write_bcf(walls + doors, path, title, os.path.join(args.out, "deviations.bcf"),
                         lambda w, out: snapshot_png(walls, doors, path, w, out))
    print(summary(walls, doors))
    if args.scenario:
        truth_path = deviation_truth.thin_path(read_tum_txy(args.truth_path)) \
            if args.truth_path else None
        truth = deviation_truth.compare(walls, args.scenario, doors, truth_path)
        with open(os.path.join(args.out, "truth.json"), "w") as f:
            json.dump(truth, f, indent=2)
        print(deviation_truth.format_summary(truth))
    return 0


if __name__ == "__main__":
    sys.exit(main())
