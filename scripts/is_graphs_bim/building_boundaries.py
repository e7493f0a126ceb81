"""IfcRelSpaceBoundary relations for the procedural buildings (used by building_ifc).

One relation per stretch of wall face bounding a room (``Room.boundaries``) and one per door
in such a stretch. The connection geometry is an IfcCurveBoundedPlane in the space's object
coordinate system (the storey's, spaces sit at the storey origin): the plane's origin is the
stretch's start at floor level, its x axis runs along the stretch, its normal points away
from the space (into the wall) and so its y axis is up; the outer boundary is the stretch's
rectangle, door openings in it are inner boundaries. The boundaries are split by element but
not by what lies behind the wall, so they are 1st-level boundaries (Name "1stLevel").
"""
from __future__ import annotations

from . import building_geometry as geo


def _door_interval(lay, door, bd, length: float):
    """The door's extent along boundary ``bd`` as (t0, t1), or None if it is not in it."""
    w = lay.wall(door.wall)
    if w.id != bd.wall:
        return None
    ax = w.axis
    d = geo.unit(geo.sub(bd.end, bd.start))
    ts = sorted(geo.dot(geo.sub(geo.add(ax.start, ax.direction, door.at + s * 0.5 * door.width), bd.start), d)
                for s in (-1.0, 1.0))
    if ts[0] < -1e-6 or ts[1] > length + 1e-6:
        return None
    return ts[0], ts[1]


def add_space_boundaries(b, spaces: dict, walls: dict, doors: dict) -> None:
    """``b`` is the IfcBuilder; spaces/walls/doors map layout names to IFC entities."""
    lay, f = b.lay, b.f
    height = lay.height

    def rect(t0, t1, z0, z1):
        return b.polyline([(t0, z0), (t1, z0), (t1, z1), (t0, z1)], True)

    def relation(key, room, element, external, start, d, outer, inner):
        plane = f.createIfcPlane(f.createIfcAxis2Placement3D(
            b.pt(start[0], start[1], 0.0), b.direction(d[1], -d[0], 0.0), b.direction(d[0], d[1], 0.0)))
        geom = f.createIfcConnectionSurfaceGeometry(f.createIfcCurveBoundedPlane(plane, outer, inner), None)
        rel = b.rooted("IfcRelSpaceBoundary", key, "1stLevel")
        rel.RelatingSpace = spaces[room.name]
        rel.RelatedBuildingElement = element
        rel.ConnectionGeometry = geom
        rel.PhysicalOrVirtualBoundary = "PHYSICAL"
        rel.InternalOrExternalBoundary = "EXTERNAL" if external else "INTERNAL"

    for room in lay.rooms:
        top = height - room.floor   # space coordinates: z = 0 at the room's floor
        for k, bd in enumerate(room.boundaries):
            wall = lay.wall(bd.wall)
            d = geo.unit(geo.sub(bd.end, bd.start))
            length = geo.norm(geo.sub(bd.end, bd.start))
            in_here = [(door, iv) for door in lay.doors
                       if (iv := _door_interval(lay, door, bd, length)) is not None]
            # a door's sill is on the lower floor of its rooms: below the higher room's floor
            def hole(door, t0, t1):
                return rect(t0, t1, max(0.0, door.sill - room.floor), door.sill + door.height - room.floor)
            inner = [hole(door, t0, t1) for door, (t0, t1) in in_here]
            relation(f"boundary:{room.name}:{k}", room, walls[bd.wall], wall.external, bd.start, d,
                     rect(0.0, length, 0.0, top), inner)
            for door, (t0, t1) in in_here:
                relation(f"boundary:{room.name}:{k}:{door.id}", room, doors[door.id], wall.external,
                         bd.start, d, hole(door, t0, t1), [])
