"""Layouts of several storeys (``storeys:``) joined by straight stair flights (``stairs:``).

Each storey is read and checked as a one-storey layout (building_layout), its errors naming
``storeys[<i>].<field>``; then the flights between storeys (format in bim/README.md).
"""
from __future__ import annotations

from . import building_geometry as geo
from .building_model import Layout, Stair
from .building_parse import Reader
from .building_rooms import room_holding

STAIR_KEYS = ("id", "storey", "start", "direction", "width", "risers", "riser_height", "tread")
RISE_TOLERANCE = 0.001   # m: the flight must reach the next storey's floor this closely
MAX_RISER = 0.25         # m: higher risers are no stair a legged robot (or a code) accepts


def parse_storeys(r: Reader, default_name: str, allow_invalid: bool, read_plan) -> Layout:
    """A multi-storey layout; ``read_plan(reader, storey)`` reads and checks one storey's plan."""
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
        read_plan(sr, st)
        lay.warnings += [f"{f}.{w}" for w in st.warnings]
        if lay.storeys and st.floor_thickness > 0:
            below = lay.storeys[-1]
            lowest = min([0.0] + [rm.floor for rm in st.rooms])   # a split level below the storey's
            if below.height + st.floor_thickness - lowest > st.elevation - below.elevation + 1e-9:
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
        if room_holding(lo_st, st.footprint) is None:
            raise r.error(f"{f}.start", f"flight '{sid}' is not inside one room of storey '{lo_st.storey_name}'")
        for oid, hole in lo_st.floor_openings:
            if geo.convex_overlap(hole, st.footprint):
                raise r.error(f"{f}.start", f"flight '{sid}' stands over the floor opening for flight '{oid}'")
        if room_holding(up_st, st.footprint) is None:
            raise r.error(f"{f}.start", f"the opening over flight '{sid}' is not inside one room of storey "
                          f"'{up_st.storey_name}'")
        landing = st.rect(st.run, st.run + 0.5)
        if room_holding(up_st, landing) is None:
            raise r.error(f"{f}.start", f"flight '{sid}' does not arrive in a room of storey "
                          f"'{up_st.storey_name}' (0.5 m of floor beyond its top riser)")
        for end, room in (("starts", room_holding(lo_st, st.footprint)), ("arrives", room_holding(up_st, landing))):
            if room.floor != 0.0:
                raise r.error(f"{f}.start", f"flight '{sid}' {end} in room '{room.name}', at a floor level of its own "
                              f"({room.floor:g} m): flights between storeys join rooms at their storey's level")
        for other in lay.stairs:
            if other.lower == lower and geo.convex_overlap(other.footprint, st.footprint):
                raise r.error(f"{f}.start", f"flight '{sid}' overlaps flight '{other.id}'")
        if up_st.floor_thickness > 0:
            up_st.floor_openings.append((sid, st.footprint))
        if lo_st.ceiling_thickness > 0:
            lo_st.ceiling_openings.append((sid, st.footprint))
        lay.stairs.append(st)
