"""Steps and ramps between the floor levels of one storey (``steps:``, ``ramps:``).

A flight of steps or a ramp starts in a door or doorless opening between two rooms of different
floor levels: its foot lies on the face of the door's wall in the higher room, at the door's
sill (the lower floor), and it climbs straight away from the wall into the higher room, whose
floor slab is cut over it. It must reach that room's floor (within RISE_TOLERANCE), keep its
risers at most MAX_STEP_RISER high or its slope at most MAX_RAMP_DEG, lie inside the room with
LANDING m of its floor beyond its top, and not overlap another flight or ramp.
"""
from __future__ import annotations

import math

from . import building_geometry as geo
from .building_model import Layout, Ramp, Stair
from .building_parse import Reader
from .building_rooms import room_holding

STEP_KEYS = ("id", "start", "direction", "width", "risers", "riser_height", "tread")
RAMP_KEYS = ("id", "start", "direction", "width", "length", "rise")
MAX_STEP_RISER = 0.2     # m
MAX_RAMP_DEG = 10.0      # degrees
RISE_TOLERANCE = 0.005   # m: steps and ramps must reach the higher floor this closely
LANDING = 0.5            # m of the higher room's floor beyond the top, to arrive on
FACE_TOLERANCE = 0.001   # m: the foot must lie on the wall face this closely


def read_steps_and_ramps(r: Reader, lay: Layout) -> None:
    for i, sd in r.items("steps"):
        f = f"steps[{i}]"
        sid, start, d, width = _common(r, lay, sd, f)
        risers = sd.get("risers")
        if isinstance(risers, bool) or not isinstance(risers, int) or risers < 2:
            raise r.error(f"{f}.risers", f"expected a whole number >= 2, got {risers!r}")
        h = r.number(sd, "riser_height", f, 0.0, lo=0.0)
        tread = r.number(sd, "tread", f, None, lo=0.0, lo_open=True)
        r.done(sd, f, STEP_KEYS)
        if h > MAX_STEP_RISER + 1e-9:
            raise r.error(f"{f}.riser_height", f"{h:g} m risers are too high (at most {MAX_STEP_RISER:g} m)")
        st = Stair(sid, 0, start, d, width, risers, h, tread, solid=True)
        low, high, door = _between_levels(r, lay, f, f"steps '{sid}'", st.footprint, st.rect(st.run, st.run + LANDING))
        if "riser_height" not in sd:
            st.riser_height = h = (high.floor - low.floor) / risers
            if h > MAX_STEP_RISER + 1e-9:
                raise r.error(f"{f}.risers", f"{risers} risers up {high.floor - low.floor:g} m are {h:.3g} m "
                              f"high (at most {MAX_STEP_RISER:g} m)")
        elif abs(risers * h - (high.floor - low.floor)) > RISE_TOLERANCE:
            raise r.error(f"{f}.riser_height", f"steps '{sid}' rise {risers} x {h:g} = {risers * h:.3g} m and do "
                          f"not reach the floor of '{high.name}': it is {high.floor - low.floor:.3g} m above "
                          f"'{low.name}'")
        st.base, st.door = low.floor, door.id
        _place(r, lay, f, st, "steps")
        lay.steps.append(st)
    for i, sd in r.items("ramps"):
        f = f"ramps[{i}]"
        rid, start, d, width = _common(r, lay, sd, f)
        length = r.number(sd, "length", f, None, lo=0.0, lo_open=True)
        rise = r.number(sd, "rise", f, 0.0, lo=0.0)
        r.done(sd, f, RAMP_KEYS)
        rp = Ramp(rid, start, d, width, length, rise)
        if "rise" in sd:
            _check_slope(r, f"{f}.rise", rp)
        low, high, door = _between_levels(r, lay, f, f"ramp '{rid}'", rp.footprint, rp.rect(length, length + LANDING))
        if "rise" not in sd:
            rp.rise = high.floor - low.floor
            _check_slope(r, f"{f}.length", rp)
        elif abs(rise - (high.floor - low.floor)) > RISE_TOLERANCE:
            raise r.error(f"{f}.rise", f"ramp '{rid}' rises {rise:g} m and does not reach the floor of "
                          f"'{high.name}': it is {high.floor - low.floor:.3g} m above '{low.name}'")
        rp.base, rp.door = low.floor, door.id
        _place(r, lay, f, rp, "ramp")
        lay.ramps.append(rp)


def _common(r: Reader, lay: Layout, sd: dict, f: str):
    sid = r.string(sd, "id", f)
    if any(x.id == sid for x in lay.steps + lay.ramps):
        raise r.error(f"{f}.id", f"duplicate id '{sid}' (steps and ramps share their ids)")
    start = r.point(sd, "start", f)
    dv = r.point(sd, "direction", f)
    if geo.norm(dv) < 1e-9:
        raise r.error(f"{f}.direction", "must not be zero")
    return sid, start, geo.unit(dv), r.number(sd, "width", f, None, lo=0.0, lo_open=True)


def _check_slope(r: Reader, fld: str, rp: Ramp) -> None:
    if rp.slope_deg > MAX_RAMP_DEG + 1e-9:
        raise r.error(fld,
                      f"ramp '{rp.id}' rises {rp.rise:g} m over {rp.length:g} m: a slope of {rp.slope_deg:.1f} deg "
                      f"(1:{rp.length / rp.rise:.1f}), steeper than {MAX_RAMP_DEG:g} deg")


def _between_levels(r: Reader, lay: Layout, f: str, what: str, footprint, landing):
    """(lower room, higher room, door) of a flight or ramp: it lies in the higher room and its
    foot is in a door or opening to a lower room."""
    high = room_holding(lay, footprint)
    if high is None:
        raise r.error(f"{f}.start", f"{what}: not inside one room (it would cross a wall)")
    if room_holding(lay, landing) is not high:
        raise r.error(f"{f}.start", f"{what}: no {LANDING:g} m of room '{high.name}''s floor beyond the top to "
                      "arrive on")
    foot0, foot1 = footprint[0], footprint[3]   # the foot's ends (u = 0)
    d = geo.unit(geo.sub(footprint[1], footprint[0]))
    for door in lay.doors:
        w = lay.wall(door.wall)
        ax = w.axis
        if abs(geo.dot(d, ax.direction)) > 1e-6 or high.name not in door.rooms:
            continue
        side = 1.0 if geo.dot(d, geo.left(ax.direction)) > 0 else -1.0
        if any(abs(ax.offset(p) - side * 0.5 * w.thickness) > FACE_TOLERANCE for p in (foot0, foot1)):
            continue
        ts = sorted(ax.param(p) for p in (foot0, foot1))
        if ts[0] < door.at - 0.5 * door.width - FACE_TOLERANCE or ts[1] > door.at + 0.5 * door.width + FACE_TOLERANCE:
            continue
        others = [rm for rm in lay.rooms if rm.name in door.rooms and rm is not high]
        if not others or others[0].floor == high.floor:
            where = f"both at {high.floor:g} m" if others else "to outdoors"
            raise r.error(f"{f}.start", f"{what}: door '{door.id}' is not between rooms of different levels "
                          f"({where}); steps and ramps join rooms of different floor levels")
        low = others[0]
        if low.floor > high.floor:
            raise r.error(f"{f}.start", f"{what}: in room '{high.name}' ({high.floor:g} m), the lower side of door "
                          f"'{door.id}'; steps and ramps climb from the door (its sill is on the lower floor) "
                          f"into the higher room, here '{low.name}' ({low.floor:g} m)")
        return low, high, door
    raise r.error(f"{f}.start", f"{what}: not between rooms of different levels: its foot (centre "
                  f"{_fmt(geo.add(foot0, geo.sub(foot1, foot0), 0.5))}) must lie on a wall face of room "
                  f"'{high.name}' within a door or opening to a lower room, climbing straight away from the wall")


def _place(r: Reader, lay: Layout, f: str, x, kind: str) -> None:
    """No overlap with other steps or ramps; the higher floor's slab is cut over it."""
    for other in lay.steps + lay.ramps:
        if geo.convex_overlap(other.footprint, x.footprint):
            raise r.error(f"{f}.start", f"'{x.id}' overlaps '{other.id}'")
    if lay.floor_thickness > 0:
        lay.level_openings.append((f"slab_opening:FLOOR:{kind}:{x.id}", f"{x.id} opening", x.footprint))


def _fmt(p) -> str:
    return f"({p[0]:g}, {p[1]:g})"
