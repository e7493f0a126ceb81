"""Layout YAML -> validated building layout (one storey, or several with stairs; split levels
with steps and ramps inside a storey; in plan).

The format is documented in ``bim/README.md``. All lengths in the YAML are metres, whatever
unit the IFC file is written in. Everything a writer or a test needs is derived here once:
wall footprints with clean joints, room inner-face polygons and areas, which wall bounds
which room over which stretch, and the rooms each door connects.

Errors raise ``LayoutError`` naming the file and the field, e.g.
``layout office.yaml: doors[3].wall: no wall 'w17'``.
"""
from __future__ import annotations

from pathlib import Path

import yaml

from . import building_geometry as geo
from .building_model import Boundary, Door, Layout, Ramp, Room, Stair, Wall
from .building_parse import LayoutError, Reader
from .building_rooms import _r, read_rooms
from .building_levels import apply_levels, check_levels, door_links
from .building_steps import read_steps_and_ramps
from .building_storeys import parse_storeys

__all__ = ["Layout", "Wall", "Room", "Door", "Boundary", "Stair", "Ramp", "LayoutError", "load_layout", "parse_layout"]

Point = geo.Point


def load_layout(path: str | Path, allow_invalid: bool = False) -> Layout:
    path = Path(path)
    try:
        data = yaml.safe_load(path.read_text())
    except (OSError, yaml.YAMLError) as e:
        raise LayoutError(path.name, "", f"cannot read: {e}") from None
    return parse_layout(data, path.name, default_name=path.stem, allow_invalid=allow_invalid)


def parse_layout(data, source: str, default_name: str = "building", allow_invalid: bool = False) -> Layout:
    r = Reader(source, data, allow_invalid)
    if "storeys" in data:
        return parse_storeys(r, default_name, allow_invalid, lambda sr, st: _read_plan(sr, st, allow_invalid))
    lay = Layout(walls=[], rooms=[], doors=[], source=source, **r.header(default_name))
    _read_plan(r, lay, allow_invalid)
    return lay


def _read_plan(r: Reader, lay: Layout, allow_invalid: bool) -> None:
    """One storey's plan: walls, rooms, doors, then the checks of the whole storey."""
    _read_walls(r, lay)
    read_rooms(r, lay)
    check_levels(r, lay)
    _read_doors(r, lay)
    apply_levels(r, lay)
    read_steps_and_ramps(r, lay)
    _check(r, lay, allow_invalid)


def _read_walls(r: Reader, lay: Layout) -> None:
    for i, w in r.items("walls", required=True):
        f = f"walls[{i}]"
        wid = r.string(w, "id", f)
        if any(x.id == wid for x in lay.walls):
            raise r.error(f"{f}.id", f"duplicate wall id '{wid}'")
        external = r.boolean(w, "external", f, False)
        thick = r.number(w, "thickness", f, r.defaults["exterior_thickness" if external else "wall_thickness"],
                         lo=0.0, lo_open=not r.allow_zero)
        wall = Wall(wid, r.point(w, "from", f), r.point(w, "to", f), thick,
                    r.number(w, "height", f, r.defaults["wall_height"], lo=0.0, lo_open=True), external)
        r.done(w, f)
        if wall.length < 1e-6:
            msg = f"{f}: wall '{wid}' has zero length"
            if not r.allow_zero:
                raise r.error(f"{f}.to", f"wall '{wid}' has zero length")
            lay.warnings.append(msg)
        elif thick == 0.0:
            lay.warnings.append(f"{f}: wall '{wid}' has zero thickness")
        lay.walls.append(wall)
    axes = [w.axis for w in lay.walls]
    for i in range(len(axes)):
        for j in range(i + 1, len(axes)):
            a, b = axes[i], axes[j]
            if a.length < 1e-6 or b.length < 1e-6:
                continue
            if geo.segments_cross(a.start, a.end, b.start, b.end):
                raise r.error(f"walls[{j}]", f"wall '{lay.walls[j].id}' crosses wall '{lay.walls[i].id}'")
            if abs(geo.cross(a.direction, b.direction)) < 1e-9 and abs(a.offset(b.start)) < 1e-6:
                lo, hi = sorted((a.param(b.start), a.param(b.end)))
                if min(hi, a.length) - max(lo, 0.0) > 1e-6:
                    raise r.error(f"walls[{j}]", f"wall '{lay.walls[j].id}' overlaps wall '{lay.walls[i].id}'")
    try:
        for w, poly in zip(lay.walls, geo.wall_footprints(axes)):
            w.footprint = [_r(p) for p in poly]
    except geo.JointError as e:
        ids = ", ".join(f"'{lay.walls[k].id}'" for k in e.walls)
        raise r.error(f"walls[{e.walls[0]}]", f"{e} (walls {ids})") from None

def _read_doors(r: Reader, lay: Layout) -> None:
    for i, dr in r.items("doors"):
        f = f"doors[{i}]"
        did = r.string(dr, "id", f)
        if any(x.id == did for x in lay.doors):
            raise r.error(f"{f}.id", f"duplicate door id '{did}'")
        wid = r.string(dr, "wall", f)
        if not any(w.id == wid for w in lay.walls):
            raise r.error(f"{f}.wall", f"no wall '{wid}'")
        wall = lay.wall(wid)
        door = Door(did, wid, r.number(dr, "at", f), r.number(dr, "width", f, r.defaults["door_width"], lo=0.0,
                    lo_open=True), r.number(dr, "height", f, r.defaults["door_height"], lo=0.0, lo_open=True))
        connects = r.list(dr, "connects", f, None)
        door.leaf = r.boolean(dr, "leaf", f, True)
        r.done(dr, f)
        lo, hi = geo.face_extent(wall.axis, wall.footprint)
        margin = 0.05
        if door.at - door.width / 2 < lo + margin - 1e-9 or door.at + door.width / 2 > hi - margin + 1e-9:
            raise r.error(f"{f}.at", f"door '{did}' ({door.at - door.width / 2:.3f}..{door.at + door.width / 2:.3f}"
                          f" along '{wid}') does not fit in the wall's clear length {lo:.3f}..{hi:.3f} "
                          f"with {margin} m to spare")
        if door.height > wall.height - 1e-9:
            raise r.error(f"{f}.height", f"door '{did}' is higher than wall '{wid}'")
        for k, st in enumerate(lay.walls):  # walls butting into this one (T-junctions)
            ends = [q for q in (st.start, st.end) if wall.axis.contains_interior(q)]
            for q in ends:
                if abs(wall.axis.param(q) - door.at) < 0.5 * (door.width + st.thickness) + margin:
                    raise r.error(f"{f}.at", f"door '{did}' runs into wall '{st.id}' meeting '{wid}' there")
        for other in lay.doors:
            if other.wall == wid and abs(other.at - door.at) < (other.width + door.width) / 2 + 0.1:
                raise r.error(f"{f}.at", f"door '{did}' overlaps door '{other.id}' (less than 0.1 m apart)")
        ax = wall.axis
        centre = geo.add(ax.start, ax.direction, door.at)
        for side in (1.0, -1.0):
            probe = geo.add(centre, geo.left(ax.direction), side * (0.5 * wall.thickness + 0.05))
            door.rooms += [rm.name for rm in lay.rooms if geo.point_in_polygon(probe, rm.polygon)]
        if connects is not None:
            want = [r.to_str(x, f"{f}.connects[{k}]") for k, x in enumerate(connects)]
            for k, x in enumerate(want):
                if not any(rm.name == x for rm in lay.rooms):
                    raise r.error(f"{f}.connects[{k}]", f"no room '{x}'")
            if sorted(want) != sorted(door.rooms):
                raise r.error(f"{f}.connects", f"door '{did}' connects {sorted(door.rooms)} by geometry, "
                              f"not {sorted(want)}")
        lay.doors.append(door)


def _check(r: Reader, lay: Layout, allow_invalid: bool) -> None:
    """Checks that need the whole layout; with allow_invalid they become warnings."""
    problems = []
    for i, d in enumerate(lay.doors):
        if not d.rooms:
            problems.append((f"doors[{i}]", f"door '{d.id}' opens into no room"))
        elif len(d.rooms) == 1 and not lay.wall(d.wall).external:
            problems.append((f"doors[{i}]", f"door '{d.id}' in interior wall '{d.wall}' has a room on one "
                             "side only"))
    if not lay.rooms:
        problems.append(("rooms", "the layout has no rooms"))
    else:
        parent = {rm.name: rm.name for rm in lay.rooms}

        def find(x):
            while parent[x] != x:
                x = parent[x]
            return x
        for d in lay.doors:
            if door_links(lay, d):
                parent[find(d.rooms[0])] = find(d.rooms[1])
        root = find(lay.rooms[0].name)
        for i, rm in enumerate(lay.rooms):
            if find(rm.name) != root:
                levels = " (a door between floor levels needs steps or a ramp in it)" if lay.has_levels else ""
                problems.append((f"rooms[{i}]", f"room '{rm.name}' is not reachable from room "
                                 f"'{lay.rooms[0].name}' through doors{levels}"))
                break
    for fld, msg in problems:
        if not allow_invalid:
            raise r.error(fld, msg)
        lay.warnings.append(f"{fld}: {msg}")
