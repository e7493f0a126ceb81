"""The simulator's known deviations (a bags/ scenario's scene.deviations) against a report.

move_wall (offset along the wall's first surface normal), rotate_wall (angle_deg about its
centre), remove_wall (NOT_BUILT), add_wall (EXTRA), close_doorway (the door CLOSED). Measures: every deviation >= 5 cm or >= 2 deg
found with the right status; offset and angle RMSE over the MOVED walls; walls on the plan
reported MOVED; NOT_BUILT claimed for a wall that was built; added walls >= 1 m found (EXTRA
within 0.3 m of them; given the robot's true path, only those in view: at least 1 m of them
had a clear sight line within 20 m through no wall as built, outside the openings) and EXTRA
reports no added wall explains; closed doors reported CLOSED,
doors reported CLOSED that are open, closed doors reported PRESENT.
"""
import math

import yaml


def _truth(scenario_path):
    with open(scenario_path) as f:
        scene = (yaml.safe_load(f) or {}).get("scene") or {}
    walls, extras, closed = {}, [], set()
    for d in scene.get("deviations") or []:
        kind = d.get("type")
        if kind == "close_doorway":
            closed.add(str(d["doorway"]))
        elif kind in ("move_wall", "rotate_wall", "remove_wall"):
            t = walls.setdefault(str(d["wall"]), {"status": "MOVED", "offset_m": 0.0,
                                                  "angle_deg": 0.0})
            if kind == "move_wall":
                t["offset_m"] += float(d["offset"])
            elif kind == "rotate_wall":
                t["angle_deg"] += float(d["angle_deg"])
            else:
                t["status"] = "NOT_BUILT"
        elif kind == "add_wall":
            extras.append({"start": [float(v) for v in d["start"]],
                           "end": [float(v) for v in d["end"]]})
    return walls, extras, closed


def _explains(added, w, tolerance=0.3):
    """Whether the EXTRA report w lies along the added wall (within tolerance, inside it)."""
    (ax, ay), (bx, by) = added["start"], added["end"]
    length = math.hypot(bx - ax, by - ay)
    tx, ty = (bx - ax) / length, (by - ay) / length
    mx = 0.5 * (w["start"][0] + w["end"][0])
    my = 0.5 * (w["start"][1] + w["end"][1])
    along = (mx - ax) * tx + (my - ay) * ty
    across = abs(-(mx - ax) * ty + (my - ay) * tx)
    return across <= tolerance and -tolerance <= along <= length + tolerance


def _cross(ax, ay, bx, by):
    return ax * by - ay * bx


def _blocks(p, q, s, e, gaps):
    """Whether the segment s-e (a wall's mid-line) blocks the sight line p-q: they cross
    strictly inside both, and not within a gap (an opening: centre, half-width) of s-e."""
    rx, ry = q[0] - p[0], q[1] - p[1]
    wx, wy = e[0] - s[0], e[1] - s[1]
    den = _cross(rx, ry, wx, wy)
    if abs(den) < 1e-12:
        return False
    t = _cross(s[0] - p[0], s[1] - p[1], wx, wy) / den
    u = _cross(s[0] - p[0], s[1] - p[1], rx, ry) / den
    if not (1e-6 < t < 1.0 - 1e-6 and 0.0 <= u <= 1.0):
        return False
    x, y = s[0] + u * wx, s[1] + u * wy
    return not any(math.hypot(x - c[0], y - c[1]) <= half for c, half in gaps)


def _as_built(walls, truth, extras, doors):
    """The walls as built (planned mid-lines moved, turned, removed as the scenario says; the
    added walls) with their openings: [(start, end, gaps)]."""
    gaps = {}
    for d in doors:
        gaps.setdefault(d.get("wall_id"), []).append((d["position"], 0.5 * d["width_m"]))
    out = []
    for w in walls:
        if w["wall_id"] < 0:
            continue
        t = truth.get(w["name"]) or truth.get(str(w["wall_id"])) or {}
        if t.get("status") == "NOT_BUILT":
            continue
        (sx, sy), (ex, ey) = w["start"], w["end"]
        nx, ny = w.get("normal", [0.0, 0.0])
        off = t.get("offset_m", 0.0)
        a = math.radians(t.get("angle_deg", 0.0))
        cx, cy = 0.5 * (sx + ex) + off * nx, 0.5 * (sy + ey) + off * ny
        hx, hy = 0.5 * (ex - sx), 0.5 * (ey - sy)
        hx, hy = hx * math.cos(a) - hy * math.sin(a), hx * math.sin(a) + hy * math.cos(a)
        openings = [((c[0] + off * nx, c[1] + off * ny), half)
                    for c, half in gaps.get(w["wall_id"], [])]
        out.append(((cx - hx, cy - hy), (cx + hx, cy + hy), openings))
    out += [(tuple(e["start"]), tuple(e["end"]), []) for e in extras]
    return out


def in_view(added, built, path, max_range=20.0, step=0.25, min_length=1.0):
    """Whether at least min_length of the added wall had a clear sight line (through no other
    wall as built, within max_range) from a pose of the robot's path: a wall never in view
    cannot be found by any method, and is counted apart."""
    (ax, ay), (bx, by) = added["start"], added["end"]
    length = math.hypot(bx - ax, by - ay)
    n = max(1, int(length / step))
    others = [b for b in built if not (b[0] == tuple(added["start"]) and
                                       b[1] == tuple(added["end"]))]
    seen = 0
    for i in range(n + 1):
        q = (ax + (bx - ax) * i / n, ay + (by - ay) * i / n)
        for p in path:
            if math.hypot(q[0] - p[0], q[1] - p[1]) > max_range:
                continue
            if not any(_blocks(p, q, s, e, gaps) for s, e, gaps in others):
                seen += 1
                break
    return seen * length / (n + 1) >= min_length


def thin_path(path, spacing=0.5):
    """The path's (x, y) every `spacing` m (rows of t, x, y, ...)."""
    out = []
    for row in path:
        xy = (float(row[1]), float(row[2]))
        if not out or math.hypot(xy[0] - out[-1][0], xy[1] - out[-1][1]) >= spacing:
            out.append(xy)
    return out


def _doors(doors, closed):
    """Doors (report items) against the closed ones (names or A-Graph ids)."""
    def is_closed(d):
        return d["name"] in closed or str(d["doorway_id"]) in closed
    rows = [{"doorway": d["name"], "guid": d["guid"],
             "truth": "CLOSED" if is_closed(d) else "PRESENT", "reported": d["status"]}
            for d in doors]
    return {"doors": rows,
            "closed_doors": len(closed),
            "closed_found": sum(1 for d in doors if is_closed(d) and d["status"] == "CLOSED"),
            "closed_reported_present": [d["name"] for d in doors
                                        if is_closed(d) and d["status"] == "PRESENT"],
            "false_closed": [d["name"] for d in doors
                             if not is_closed(d) and d["status"] == "CLOSED"],
            "doors_present": sum(1 for d in doors if d["status"] == "PRESENT"),
            "doors_not_seen": sum(1 for d in doors if d["status"] == "NOT_SEEN")}


def compare(walls, scenario_path, doors=(), truth_path=None):
    """The report against the scenario's truth; with truth_path (the robot's true (x, y) in the
    bim frame), added walls never in view are counted apart (extra_not_in_view)."""
    truth, extras, closed = _truth(scenario_path)
    rows, off_err, ang_err = [], [], []
    missed, false_moved, false_not_built = [], [], []
    for w in walls:
        if w["wall_id"] < 0:
            continue
        t = truth.get(w["name"]) or truth.get(str(w["wall_id"])) or {
            "status": "AS_PLANNED", "offset_m": 0.0, "angle_deg": 0.0}
        row = {"wall": w["name"], "guid": w["guid"], "truth": t["status"], "reported": w["status"],
               "truth_offset_m": t["offset_m"], "truth_angle_deg": t["angle_deg"],
               "offset_m": w["offset_m"], "angle_deg": w["angle_deg"]}
        rows.append(row)
        big = abs(t["offset_m"]) >= 0.05 or abs(t["angle_deg"]) >= 2.0
        if t["status"] == "NOT_BUILT" or (t["status"] == "MOVED" and big):
            if w["status"] != t["status"]:
                missed.append(w["name"])
        if t["status"] == "MOVED" and w["status"] == "MOVED":
            off_err.append(w["offset_m"] - t["offset_m"])
            ang_err.append(w["angle_deg"] - t["angle_deg"])
        small = abs(t["offset_m"]) <= 0.02 and abs(t["angle_deg"]) <= 0.5
        if t["status"] != "NOT_BUILT" and small and w["status"] == "MOVED":
            false_moved.append(w["name"])
        if w["status"] == "NOT_BUILT" and t["status"] != "NOT_BUILT":
            false_not_built.append(w["name"])
    reported_extra = [w for w in walls if w["status"] == "EXTRA"]
    long_extras = [e for e in extras
                   if math.hypot(e["end"][0] - e["start"][0], e["end"][1] - e["start"][1]) >= 1.0]
    not_in_view = []
    if truth_path is not None:
        built = _as_built(walls, truth, extras, doors)
        not_in_view = [e for e in long_extras if not in_view(e, built, truth_path)]
        long_extras = [e for e in long_extras if e not in not_in_view]
    found = [e for e in long_extras if any(_explains(e, w) for w in reported_extra)]
    unexplained = [w for w in reported_extra if not any(_explains(e, w) for e in extras)]

    def rmse(v):
        return math.sqrt(sum(x * x for x in v) / len(v)) if v else 0.0

    return dict(_doors(doors, closed), **{"walls": rows, "missed": missed, "false_moved": false_moved,
            "false_not_built": false_not_built, "offset_rmse_m": rmse(off_err),
            "angle_rmse_deg": rmse(ang_err), "moved_measured": len(off_err),
            "extra_walls": len(long_extras), "extra_found": len(found),
            "extra_not_in_view": [[e["start"], e["end"]] for e in not_in_view],
            "extra_unexplained": len(unexplained),
            "deviations": sum(1 for t in truth.values()) + len(extras) + len(closed)})


def format_summary(r):
    return ("against the scenario's %d known deviations: missed %d %s, offset RMSE %.1f cm and "
            "angle RMSE %.2f° over %d MOVED walls, false MOVED %d %s, false NOT_BUILT %d %s, "
            "EXTRA found %d of %d (>= 1 m%s), EXTRA unexplained %d; closed doors found %d of %d, "
            "reported PRESENT %s, false CLOSED %d %s (doors PRESENT %d, NOT_SEEN %d)" % (
                r["deviations"], len(r["missed"]), r["missed"], 100 * r["offset_rmse_m"],
                r["angle_rmse_deg"], r["moved_measured"], len(r["false_moved"]), r["false_moved"],
                len(r["false_not_built"]), r["false_not_built"], r["extra_found"],
                r["extra_walls"],
                (", in view; %d never in view" % len(r["extra_not_in_view"]))
                if r.get("extra_not_in_view") else "",
                r["extra_unexplained"], r["closed_found"], r["closed_doors"],
                r["closed_reported_present"], len(r["false_closed"]), r["false_closed"],
                r["doors_present"], r["doors_not_seen"]))
