"""Split levels inside one storey: rooms whose floor stands above or below the storey's level.

A room's ``floor`` (metres, relative to the storey's elevation, default 0) sets where its
IfcSpace starts and where the floor slab under it has its top face. From the rooms' floors:

* a wall stands on the lowest floor of the rooms it bounds, or on the storey's level if that is
  lower (``Wall.bottom``); its top stays where the layout puts it (the ceiling is one plane);
* a door or doorless opening has its sill on the lower floor of the rooms it joins
  (``Door.sill``), as an exporter places a door at its host wall's base;
* the floor slab is written in pieces, one per room (``slab_polygon``), each at its room's level.

All levels of one storey lie within MAX_LEVEL_SPREAD of each other and of the storey's own level:
more is a storey change. Steps and ramps between levels: building_steps.
"""
from __future__ import annotations

from . import building_geometry as geo
from .building_model import Layout, Room
from .building_parse import Reader
from .building_rooms import _covering, _r

MAX_LEVEL_SPREAD = 0.6   # m: larger level differences inside one storey are a storey change
THRESHOLD_STEP = 0.2     # m: a door between levels this close is passable without steps


def check_levels(r: Reader, lay: Layout) -> None:
    """Refuses level differences of a storey change, and a slab outline with split levels."""
    lo = hi = 0.0   # the storey's own level counts: floors are relative to it
    lo_name = hi_name = "the storey's own level"
    for i, rm in enumerate(lay.rooms):
        if rm.floor < lo:
            lo, lo_name = rm.floor, f"room '{rm.name}'"
        if rm.floor > hi:
            hi, hi_name = rm.floor, f"room '{rm.name}'"
        if hi - lo > MAX_LEVEL_SPREAD + 1e-9:
            other = lo_name if rm.floor == hi else hi_name
            raise r.error(f"rooms[{i}].floor", f"room '{rm.name}' at {rm.floor:g} m is {hi - lo:.3g} m from "
                          f"{other} ({lo if rm.floor == hi else hi:g} m): more than {MAX_LEVEL_SPREAD:g} m "
                          "inside one storey is a storey change (give it a storey of its own under "
                          "'storeys:')")
    if lay.has_levels and lay.slab_outline is not None:
        raise r.error("floor_slab.outline", "not with rooms at floor levels of their own (the slab is "
                      "written in one piece per room, at its floor)")


def apply_levels(r: Reader, lay: Layout) -> None:
    """Wall bottoms and door sills from the rooms' floors; doors must stay under their wall's top."""
    floors = {rm.name: rm.floor for rm in lay.rooms}
    for w in lay.walls:
        bounded = [rm.floor for rm in lay.rooms if any(bd.wall == w.id for bd in rm.boundaries)]
        w.bottom = min([0.0] + bounded)
    for i, d in enumerate(lay.doors):
        d.sill = min((floors[n] for n in d.rooms), default=0.0)
        wall = lay.wall(d.wall)
        if d.sill + d.height > wall.height + 1e-9:
            raise r.error(f"doors[{i}].height", f"door '{d.id}' (sill at {d.sill:g} m, {d.height:g} m high) "
                          f"is higher than wall '{wall.id}' ({wall.height:g} m)")


def door_links(lay: Layout, d) -> bool:
    """Whether a door joining two rooms is a way between them: on one level, a step no higher
    than THRESHOLD_STEP, or steps or a ramp standing in it."""
    if len(d.rooms) != 2:
        return False
    a, b = (next(rm for rm in lay.rooms if rm.name == n) for n in d.rooms)
    if abs(a.floor - b.floor) <= THRESHOLD_STEP + 1e-9:
        return True
    return any(getattr(x, "door", None) == d.id for x in list(lay.steps) + list(lay.ramps))


def slab_polygon(lay: Layout, room: Room) -> list:
    """The floor slab piece under a room: its corner polygon (on the wall axes), pushed out to the
    outer face of exterior walls; under a wall between two levels the lower room's piece reaches
    the far face and the higher room's stops at its own face (so nothing of the higher floor is
    left in a doorway on the lower one); between rooms of one level the pieces meet on the axis."""
    n = len(room.corners)
    halves = []
    for k in range(n):
        cov = _covering(lay, room.corners[k], room.corners[(k + 1) % n])
        w = cov[0][0]
        others = [rm.floor for rm in lay.rooms if rm is not room and any(bd.wall == w.id for bd in rm.boundaries)]
        if w.external or any(f > room.floor for f in others):
            halves.append(-0.5 * w.thickness)
        elif any(f < room.floor for f in others):
            halves.append(0.5 * w.thickness)
        else:
            halves.append(0.0)
    try:
        return [_r(p) for p in geo.inner_polygon(room.corners, halves)]
    except ValueError:  # an exterior edge collinear with an interior one: stop at the axes
        return list(room.corners)
