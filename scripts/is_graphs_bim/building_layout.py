"""Layout YAML -> validated building layout (one storey, or several with stairs; in plan).

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
from .building_model import Boundary, Door, Layout, Room, Stair, Wall
from .building_parse import LayoutError, Reader
from .building_rooms import _r, read_rooms

__all__ = ["Layout", "Wall", "Room", "Door", "Boundary", "Stair", "LayoutError", "load_layout", "parse_layout"]

STAIR_KEYS = ("id", "storey", "start", "direction", "width", "risers", "riser_height", "tread")
RISE_TOLERANCE = 0.001   # m: the flight must reach the next storey's floor this closely
MAX_RISER = 0.25         # m: higher risers are no stair a legged robot (or a code) accepts

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
        return _parse_storeys(r, default_name, allow_invalid)
    lay = Layout(walls=[], rooms=[], doors=[], source=source, **r.header(default_name))
    _read_walls(r, lay)
    read_rooms(r, lay)
    _read_doors(r, lay)
    _check(r, lay, allow_invalid)
    return lay


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
            if len(d.rooms) == 2:
                parent[find(d.rooms[0])] = find(d.rooms[1])
        root = find(lay.rooms[0].name)
        for i, rm in enumerate(lay.rooms):
            if find(rm.name) != root:
                problems.append((f"rooms[{i}]", f"room '{rm.name}' is not reachable from room "
                                 f"'{lay.rooms[0].name}' through doors"))
                break
    for fld, msg in problems:
        if not allow_invalid:
            raise r.error(fld, msg)
        lay.warnings.append(f"{fld}: {msg}")


# --- several storeys (issue 22) --------------------------------------------------------------
def _parse_storeys(r: Reader, default_name: str, allow_invalid: bool) -> Layout:
    head = r.header(default_name, multi=True)
    lay = Layout(walls=[], rooms=[], doors=[], source=r.source, **head)
    seq = r.list(r.data, "storeys", "")
    if len(seq) < 2:
        raise r.error("storeys", "a layout with storeys needs at least two (one storey: use 'storey')")
    for i, sd in enumerate(seq):
        f = f"storeys[{i}]"
        if not isinstance(sd, dict):
            raise r.error(f, "expected a mapping")
        sr = r.sub(sd, f + ".")
        base = dict(head)
        base.update(sr.storey(f"Storey {i}"))
        st = Layout(walls=[], rooms=[], doors=[], source=r.source, **base)
        if any(o.storey_name == st.storey_name for o in lay.storeys):
            raise r.error(f"{f}.name", f"duplicate storey name '{st.storey_name}'")
        if lay.storeys and st.elevation <= lay.storeys[-1].elevation:
            raise r.error(f"{f}.elevation", f"{st.elevation:g} must be above the storey below "
                          f"('{lay.storeys[-1].storey_name}', {lay.storeys[-1].elevation:g})")
        _read_walls(sr, st)
        read_rooms(sr, st)
        _read_doors(sr, st)
        _check(sr, st, allow_invalid)
        lay.warnings += [f"{f}.{w}" for w in st.warnings]
        if lay.storeys and st.floor_thickness > 0:
            below = lay.storeys[-1]
            if below.height + st.floor_thickness > st.elevation - below.elevation + 1e-9:
                raise r.error(f"{f}.floor_slab.thickness", f"the floor slab ({st.floor_thickness:g} m) under storey "
                              f"'{st.storey_name}' runs into the walls of '{below.storey_name}' "
                              f"({below.height:g} m high, {st.elevation - below.elevation:g} m below)")
        lay.storeys.append(st)
    lay.storey_name, lay.elevation = lay.storeys[0].storey_name, lay.storeys[0].elevation
    _read_stairs(r, lay)
    return lay


def _storey_index(r: Reader, lay: Layout, v, fld: str) -> int:
    if isinstance(v, int) and not isinstance(v, bool):
        if not 0 <= v < len(lay.storeys):
            raise r.error(fld, f"no storey {v} (0..{len(lay.storeys) - 1})")
        return v
    name = r.to_str(v, fld)
    for k, st in enumerate(lay.storeys):
        if st.storey_name == name:
            return k
    raise r.error(fld, f"no storey '{name}'")


def _inside_room(lay: Layout, poly) -> Room | None:
    """The room whose inner-face polygon holds the whole of ``poly`` (a convex polygon)."""
    c = (sum(p[0] for p in poly) / len(poly), sum(p[1] for p in poly) / len(poly))
    inner = [geo.add(p, geo.sub(c, p), 1e-4) for p in poly]   # just inside its corners
    for rm in lay.rooms:
        if all(geo.point_in_polygon(p, rm.polygon) for p in inner) and not any(
                geo.segments_cross(inner[k], inner[(k + 1) % len(inner)], rm.polygon[j],
                                   rm.polygon[(j + 1) % len(rm.polygon)])
                for k in range(len(inner)) for j in range(len(rm.polygon))):
            return rm
    return None


def _convex_overlap(a, b) -> bool:
    """Whether two convex polygons overlap with positive area (separating axis test)."""
    for poly in (a, b):
        for k in range(len(poly)):
            n = geo.left(geo.unit(geo.sub(poly[(k + 1) % len(poly)], poly[k])))
            pa, pb = [geo.dot(p, n) for p in a], [geo.dot(p, n) for p in b]
            if max(pa) <= min(pb) + 1e-9 or max(pb) <= min(pa) + 1e-9:
                return False
    return True


def _read_stairs(r: Reader, lay: Layout) -> None:
    for i, sd in r.items("stairs"):
        f = f"stairs[{i}]"
        sid = r.string(sd, "id", f)
        if any(x.id == sid for x in lay.stairs):
            raise r.error(f"{f}.id", f"duplicate stair id '{sid}'")
        if "storey" not in sd:
            raise r.error(f"{f}.storey", "missing (the storey the flight starts on: a name or an index)")
        lower = _storey_index(r, lay, sd["storey"], f"{f}.storey")
        if lower == len(lay.storeys) - 1:
            raise r.error(f"{f}.storey", f"'{lay.storeys[lower].storey_name}' is the top storey: "
                          "a flight needs a storey above it")
        start = r.point(sd, "start", f)
        dv = r.point(sd, "direction", f)
        if geo.norm(dv) < 1e-9:
            raise r.error(f"{f}.direction", "must not be zero")
        width = r.number(sd, "width", f, None, lo=0.0, lo_open=True)
        risers = sd.get("risers")
        if isinstance(risers, bool) or not isinstance(risers, int) or risers < 2:
            raise r.error(f"{f}.risers", f"expected a whole number >= 2, got {risers!r}")
        lo_st, up_st = lay.storeys[lower], lay.storeys[lower + 1]
        rise = up_st.elevation - lo_st.elevation
        h = r.number(sd, "riser_height", f, rise / risers, lo=0.0, lo_open=True)
        tread = r.number(sd, "tread", f, None, lo=0.0, lo_open=True)
        r.done(sd, f, STAIR_KEYS)
        if abs(risers * h - rise) > RISE_TOLERANCE:
            raise r.error(f"{f}.riser_height", f"flight '{sid}' rises {risers} x {h:g} = {risers * h:g} m, not the "
                          f"{rise:g} m from '{lo_st.storey_name}' up to '{up_st.storey_name}'")
        if h > MAX_RISER:
            raise r.error(f"{f}.riser_height", f"{h:g} m risers are too high (at most {MAX_RISER:g} m)")
        st = Stair(sid, lower, start, geo.unit(dv), width, risers, h, tread)
        if _inside_room(lo_st, st.footprint) is None:
            raise r.error(f"{f}.start", f"flight '{sid}' is not inside one room of storey '{lo_st.storey_name}'")
        for oid, hole in lo_st.floor_openings:
            if _convex_overlap(hole, st.footprint):
                raise r.error(f"{f}.start", f"flight '{sid}' stands over the floor opening for flight '{oid}'")
        if _inside_room(up_st, st.footprint) is None:
            raise r.error(f"{f}.start", f"the opening over flight '{sid}' is not inside one room of storey "
                          f"'{up_st.storey_name}'")
        landing = st.rect(st.run, st.run + 0.5)
        if _inside_room(up_st, landing) is None:
            raise r.error(f"{f}.start", f"flight '{sid}' does not arrive in a room of storey "
                          f"'{up_st.storey_name}' (0.5 m of floor beyond its top riser)")
        for other in lay.stairs:
            if other.lower == lower and _convex_overlap(other.footprint, st.footprint):
                raise r.error(f"{f}.start", f"flight '{sid}' overlaps flight '{other.id}'")
        if up_st.floor_thickness > 0:
            up_st.floor_openings.append((sid, st.footprint))
        if lo_st.ceiling_thickness > 0:
            lo_st.ceiling_openings.append((sid, st.footprint))
        lay.stairs.append(st)
