"""Rooms of a layout: inner-face polygons from corners on the wall axes, and the stretches
of wall face bounding each room (used for IfcRelSpaceBoundary and by the tests)."""
from __future__ import annotations

from . import building_geometry as geo
from .building_model import Boundary, Layout, Point, Room, Wall
from .building_parse import Reader

def _covering(lay: Layout, a: Point, b: Point) -> list[tuple[Wall, float, float]]:
    """Walls whose axis lies on segment a-b, with the covered parameter interval on a-b."""
    d, length = geo.unit(geo.sub(b, a)), geo.norm(geo.sub(b, a))
    out = []
    for w in lay.walls:
        ax = w.axis
        if ax.length < 1e-6 or abs(geo.cross(ax.direction, d)) > 1e-9:
            continue
        if abs(geo.cross(d, geo.sub(ax.start, a))) > 1e-6:
            continue
        lo, hi = sorted((geo.dot(geo.sub(ax.start, a), d), geo.dot(geo.sub(ax.end, a), d)))
        lo, hi = max(lo, 0.0), min(hi, length)
        if hi - lo > 1e-6:
            out.append((w, lo, hi))
    return sorted(out, key=lambda t: t[1])


def read_rooms(r: Reader, lay: Layout) -> None:
    for i, rm in r.items("rooms"):
        f = f"rooms[{i}]"
        name = r.string(rm, "name", f)
        if any(x.name == name for x in lay.rooms):
            raise r.error(f"{f}.name", f"duplicate room name '{name}'")
        long_name = r.string(rm, "long_name", f, name)
        corners = [r.to_point(p, f"{f}.corners[{k}]") for k, p in enumerate(r.list(rm, "corners", f))]
        floor = r.number(rm, "floor", f, 0.0)
        r.done(rm, f)
        if len(corners) < 3:
            raise r.error(f"{f}.corners", "a room needs at least 3 corners")
        if geo.signed_area(corners) < 0:
            corners.reverse()
        room = Room(name, long_name, corners, floor=floor)
        halves, covers = [], []
        for k in range(len(corners)):
            a, b = corners[k], corners[(k + 1) % len(corners)]
            cov = _covering(lay, a, b)
            length, reach = geo.norm(geo.sub(b, a)), 0.0
            for _, lo, hi in cov:
                if lo > reach + 1e-6:
                    break
                reach = max(reach, hi)
            if length < 1e-6 or reach < length - 1e-6:
                raise r.error(f"{f}.corners", f"edge {_fmt(a)}-{_fmt(b)} of room '{name}' is not "
                              "entirely on wall axes")
            if len({round(w.thickness, 9) for w, _, _ in cov}) > 1:
                raise r.error(f"{f}.corners", f"edge {_fmt(a)}-{_fmt(b)} lies on walls of different thickness")
            halves.append(0.5 * cov[0][0].thickness)
            covers.append(cov)
        try:
            room.polygon = [_r(p) for p in geo.inner_polygon(corners, halves)]
        except ValueError as e:
            raise r.error(f"{f}.corners", str(e)) from None
        if len(room.polygon) < 3 or room.area <= 1e-6 or not geo.is_simple(room.polygon):
            raise r.error(f"{f}.corners", f"room '{name}' has no valid inner polygon")
        for w in lay.walls:
            mid = geo.add(w.start, geo.sub(w.end, w.start), 0.5)
            if geo.point_in_polygon(mid, room.polygon):
                raise r.error(f"{f}.corners", f"wall '{w.id}' lies inside room '{name}'")
        _add_boundaries(room, covers, halves)
        lay.rooms.append(room)


def _add_boundaries(room: Room, covers, halves) -> None:
    """Splits the room's inner faces by wall: each stretch of face and the wall behind it."""
    n = len(room.corners)
    for k in range(n):
        a, b = room.corners[k], room.corners[(k + 1) % n]
        d = geo.unit(geo.sub(b, a))
        off = geo.left(d)
        # the inner face of edge k runs between the inner polygon's vertices on that line
        on_face = [p for p in room.polygon if abs(geo.dot(geo.sub(p, a), off) - halves[k]) < 1e-6]
        params = [geo.dot(geo.sub(p, a), d) for p in on_face]
        f_lo, f_hi = min(params), max(params)
        base = geo.add(a, off, halves[k])
        for w, lo, hi in covers[k]:
            lo = f_lo if lo <= 1e-6 else max(lo, f_lo)
            hi = f_hi if hi >= geo.norm(geo.sub(b, a)) - 1e-6 else min(hi, f_hi)
            if hi - lo > 1e-6 and not any(bd.wall == w.id and geo.same(bd.start, geo.add(base, d, lo))
                                          for bd in room.boundaries):
                room.boundaries.append(Boundary(w.id, geo.add(base, d, lo), geo.add(base, d, hi)))


def room_holding(lay: Layout, poly) -> Room | None:
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


def _r(p: Point) -> Point:
    """Rounds away float noise (1e-10 m) so that derived coordinates read and compare cleanly."""
    return (round(p[0], 10) + 0.0, round(p[1], 10) + 0.0)


def _fmt(p: Point) -> str:
    return f"({p[0]:g}, {p[1]:g})"
