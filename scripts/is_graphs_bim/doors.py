"""Doorways from IfcDoor: host wall, position, size and the rooms a door connects."""
from dataclasses import dataclass

import numpy as np

from .spaces import point_in_polygon

PROBE_BEYOND = 0.3      # m past the wall face where the rooms are probed
STEP_MAX = 0.6          # m: a doorway joins rooms whose floors differ by up to this (a step, a
                        # ramp); more is a change of storey
HEADROOM = 1.8          # m: a doorway reaches at least this far above a floor it opens onto


@dataclass
class Doorway:
    entity: object          # the IfcDoor, IfcOpeningElement or IfcVirtualElement; None for a
                            # virtual separation no IfcVirtualElement stands for
    storey: int
    wall: int               # index into the converter's walls, -1 if unknown
    position: np.ndarray    # (3,) on the host wall's mid-plane, z at the sill
    width: float
    height: float
    rooms: list             # room indices
    kind: str = "door"      # "door" | "opening" | "virtual" (docs/agraph_format.md)


def host_wall_entity(door):
    """The building element whose opening the door fills (IfcRelFillsElement/IfcRelVoidsElement)."""
    for fills in getattr(door, "FillsVoids", None) or ():
        opening = fills.RelatingOpeningElement
        for voids in getattr(opening, "VoidsElements", None) or ():
            return voids.RelatingBuildingElement, opening
        return None, opening
    return None, None


def _horizontal_frame(points):
    """(normal, tangent) of a door from its points: the thin horizontal direction is the normal."""
    xy = points[:, :2] - points[:, :2].mean(axis=0)
    w, v = np.linalg.eigh(xy.T @ xy)
    n = np.array([v[0, 0], v[1, 0], 0.0])
    return n, np.array([-n[1], n[0], 0.0])


def _opens_onto(room, p, bottom, top):
    """Whether a doorway reaching from z = bottom to top opens, at plan point p, onto the room:
    p is in its footprint and either its z range holds the sill (the rule for rooms level with
    the doorway) or its floor lies between STEP_MAX below the doorway's bottom and HEADROOM below
    its top (a room a step up or down: the doorway's bottom may be at the lower floor, or lower
    still where its geometry reaches down to the wall's base)."""
    if room.contains(p, bottom + 0.1):
        return True
    if room.floor_z is None or not point_in_polygon(p, room.polygon):
        return False
    return (bottom - STEP_MAX <= room.floor_z <= max(bottom + STEP_MAX, top - HEADROOM)
            and bottom < room.z_max)


def _room_at(rooms, p, bottom, top, exclude=()):
    """The smallest room a doorway from z = bottom to top opens onto at point p (2D), or None."""
    hits = [ri for ri, r in enumerate(rooms) if ri not in exclude
            and _opens_onto(r, p, bottom, top)]
    return min(hits, key=lambda ri: (rooms[ri].area, ri)) if hits else None


def locate(door, points, host_pieces, scale):
    """(wall index or -1, position, width, height, normal, half thickness) of a door."""
    lo, hi = points.min(axis=0), points.max(axis=0)
    c = 0.5 * (lo + hi)
    if host_pieces:
        def off(item):
            _, piece = item
            a = piece.faces[0]
            mid_d = a.d - 0.5 * piece.thickness
            s = c @ a.tangent
            s0 = piece.start @ a.tangent - 0.5 * piece.length
            outside = max(0.0, s0 - s, s - (s0 + piece.length))
            return (abs(c @ a.normal - mid_d) + outside, item[0])
        wi, piece = min(host_pieces, key=off)
        n, t = piece.faces[0].normal, piece.faces[0].tangent
        half = 0.5 * piece.thickness
        pos = c - (c @ n - (piece.faces[0].d - half)) * n
    else:
        wi = -1
        n, t = _horizontal_frame(points)
        s = points @ n
        half = 0.5 * float(s.max() - s.min())
        pos = c.copy()
    pos[2] = lo[2]
    s = points @ t
    width = float(getattr(door, "OverallWidth", None) or 0.0) * scale
    height = float(getattr(door, "OverallHeight", None) or 0.0) * scale
    if not width > 0.0:
        width = float(s.max() - s.min())
    if not height > 0.0:
        height = float(hi[2] - lo[2])
    return wi, pos, width, height, n, half


def connect(pos, n, half, rooms, rsb_rooms, top=None):
    """The rooms on both sides of a doorway: probes beyond each wall face, then space boundaries.

    pos: on the wall's mid-plane at the doorway's bottom; top: the z of its top (default: pos z
    plus 2.1 m). rsb_rooms: room indices that IfcRelSpaceBoundary names for this door (may be
    empty). Two rooms whose floors differ by more than STEP_MAX are on different levels, not a
    step apart: only the one whose floor is nearer the doorway's bottom is kept.
    """
    bottom = float(pos[2])
    top = bottom + 2.1 if top is None else float(top)
    found = []
    for sign in (1.0, -1.0):
        probe = pos[:2] + sign * (half + PROBE_BEYOND) * n[:2]
        ri = _room_at(rooms, probe, bottom, top, exclude=found)
        if ri is not None:
            found.append(ri)
    for ri in sorted(rsb_rooms):
        if len(found) >= 2:
            break
        if ri not in found:
            found.append(ri)
    if len(found) == 2 and all(rooms[ri].floor_z is not None for ri in found):
        a, b = (rooms[ri].floor_z for ri in found)
        if abs(a - b) > STEP_MAX + 1e-6:
            found = [min(found, key=lambda ri: (abs(rooms[ri].floor_z - bottom), ri))]
    return sorted(found)
