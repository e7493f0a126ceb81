"""What people walk on, for building_ifc: floor slabs (one, or one piece per floor level),
stair flights (between storeys, or steps inside one) and ramps.

Each function takes the IfcBuilder ``b`` (its file, current storey and layout, and helpers).
"""
from __future__ import annotations

import math

import ifcopenshell.api.aggregate
import ifcopenshell.api.feature
import ifcopenshell.api.pset

from . import building_geometry as geo
from .building_levels import slab_polygon

OPENING_OVERSHOOT = 0.05  # slab openings stick out of each slab face by this much (metres)
WAIST = 0.25              # m: the concrete under the treads of a flight between storeys


def slabs(b) -> list:
    """The storey's floor slab (FLOOR, top at the storey's level; with split levels one slab per
    level, one body item per room on it) and ceiling slab (ROOF, on the walls), with the openings
    cut in them over flights, steps and ramps."""
    lay, out = b.lay, []
    outline = lay.slab_outline
    if outline is None:
        pts = [p for w in lay.walls if w.length > 1e-6 for p in w.footprint]
        xs, ys = [p[0] for p in pts], [p[1] for p in pts]
        outline = [(min(xs), min(ys)), (max(xs), min(ys)), (max(xs), max(ys)), (min(xs), max(ys))]
    elif geo.signed_area(outline) < 0:
        outline = outline[::-1]
    floor_holes = [(f"slab_opening:FLOOR:{sid}", f"{sid} stairwell", hole) for sid, hole in lay.floor_openings]
    floor_holes += lay.level_openings
    if lay.floor_thickness > 0 and lay.has_levels:
        out += _level_slabs(b, floor_holes)
    elif lay.floor_thickness > 0:
        out.append(_slab(b, "slab:FLOOR", "Floor slab", "FLOOR", -lay.floor_thickness, [outline],
                         lay.floor_thickness, floor_holes))
    if lay.ceiling_thickness > 0:
        holes = [(f"slab_opening:ROOF:{sid}", f"{sid} stairwell", hole) for sid, hole in lay.ceiling_openings]
        out.append(_slab(b, "slab:ROOF", "Ceiling slab", "ROOF", lay.height, [outline], lay.ceiling_thickness, holes))
    return out


def _level_slabs(b, holes) -> list:
    lay, out = b.lay, []
    pieces = {rm.name: slab_polygon(lay, rm) for rm in lay.rooms}
    for level in sorted({rm.floor for rm in lay.rooms}):
        polys = [pieces[rm.name] for rm in lay.rooms if rm.floor == level]
        mine = [h for h in holes if _level_of(lay, pieces, h[2]) == level]
        key, name = ("slab:FLOOR", "Floor slab") if level == 0 else \
            (f"slab:FLOOR@{level:g}", f"Floor slab {level:+g} m")
        out.append(_slab(b, key, name, "FLOOR", level - lay.floor_thickness, polys, lay.floor_thickness, mine))
    return out


def _level_of(lay, pieces, hole) -> float:
    c = (sum(p[0] for p in hole) / len(hole), sum(p[1] for p in hole) / len(hole))
    return next((rm.floor for rm in lay.rooms if geo.point_in_polygon(c, pieces[rm.name])), 0.0)


def _slab(b, key, name, kind, z0, polys, thick, holes):
    slab = b.rooted("IfcSlab", key, name, kind)
    b.place(slab, b.storey, (0.0, 0.0, z0))
    b.shape(slab, [b.extrusion(p if geo.signed_area(p) > 0 else p[::-1], thick) for p in polys])
    for hkey, hname, hole in holes:
        op = b.rooted("IfcOpeningElement", hkey, hname, None if b.f.schema == "IFC2X3" else "OPENING")
        ifcopenshell.api.feature.add_feature(b.f, feature=op, element=slab)
        b.place(op, slab)
        b.shape(op, [b.extrusion(hole if geo.signed_area(hole) > 0 else hole[::-1],
                                 thick + 2 * OPENING_OVERSHOOT, -OPENING_OVERSHOOT)])
    return slab


def _side_solid(b, prof, width):
    """A side profile (x along the run, y up) extruded across ``width`` about the centre line."""
    f = b.f
    profile = f.createIfcArbitraryClosedProfileDef("AREA", None, b.polyline(prof, True))
    # profile plane: x along the flight, y up; extruded along -y of the flight (its width)
    pos = f.createIfcAxis2Placement3D(b.pt(0.0, 0.5 * width, 0.0), b.direction(0.0, -1.0, 0.0),
                                      b.direction(1.0, 0.0, 0.0))
    return f.createIfcExtrudedAreaSolid(profile, pos, b.direction(0.0, 0.0, 1.0), b.L(width))


def flight(b, s, key: str = "stair"):
    """IfcStair > IfcStairFlight: the flight's side profile (risers and treads, a WAIST under
    them, or solid down to its base for steps inside a storey) extruded across its width.
    ``key``: "stair" for flights between storeys, "steps" for steps inside one."""
    f = b.f
    ifc2x3 = f.schema == "IFC2X3"
    stair = b.rooted("IfcStair", f"{key}:{s.id}", s.id, None if ifc2x3 else "STRAIGHT_RUN_STAIR")
    if ifc2x3:
        stair.ShapeType = "STRAIGHT_RUN_STAIR"
    fl = b.rooted("IfcStairFlight", f"flight:{s.id}" if key == "stair" else f"{key}_flight:{s.id}",
                  f"{s.id} flight", None if ifc2x3 else "STRAIGHT")
    if ifc2x3:
        fl.NumberOfRiser, fl.NumberOfTreads = s.risers, s.risers - 1
    else:
        fl.NumberOfRisers, fl.NumberOfTreads = s.risers, s.risers - 1
    fl.RiserHeight, fl.TreadLength = b.L(s.riser_height), b.L(s.tread)
    b.place(stair, b.storey, (*s.start, s.base), s.direction)
    b.place(fl, stair)
    n, h, t = s.risers, s.riser_height, s.tread
    prof = [(0.0, 0.0)]
    for k in range(1, n):
        prof += [((k - 1) * t, k * h), (k * t, k * h)]
    if s.solid:
        prof += [((n - 1) * t, 0.0)]
    else:
        prof += [((n - 1) * t, (n - 1) * h - WAIST), (t, 0.0)]
    b.shape(fl, [_side_solid(b, prof, s.width)])
    rel = ifcopenshell.api.aggregate.assign_object(f, products=[fl], relating_object=stair)
    rel.RelatedObjects = [fl]
    return stair


def ramp(b, rp):
    """IfcRamp > IfcRampFlight: a solid wedge from the lower floor up to the higher one."""
    f = b.f
    ifc2x3 = f.schema == "IFC2X3"
    e = b.rooted("IfcRamp", f"ramp:{rp.id}", rp.id, None if ifc2x3 else "STRAIGHT_RUN_RAMP")
    if ifc2x3:
        e.ShapeType = "STRAIGHT_RUN_RAMP"
    fl = b.rooted("IfcRampFlight", f"ramp_flight:{rp.id}", f"{rp.id} flight", None if ifc2x3 else "STRAIGHT")
    b.place(e, b.storey, (*rp.start, rp.base), rp.direction)
    b.place(fl, e)
    b.shape(fl, [_side_solid(b, [(0.0, 0.0), (rp.length, 0.0), (rp.length, rp.rise)], rp.width)])
    pset = ifcopenshell.api.pset.add_pset(f, product=fl, name="Pset_RampFlightCommon")
    ifcopenshell.api.pset.edit_pset(f, pset=pset, properties={"Slope": round(math.atan2(rp.rise, rp.length), 12)})
    rel = ifcopenshell.api.aggregate.assign_object(f, products=[fl], relating_object=e)
    rel.RelatedObjects = [fl]
    return e
