"""Doorways from IfcDoor: host wall, position, size and the rooms a door connects."""
from dataclasses import dataclass

import numpy as np

PROBE_BEYOND = 0.3      # m past the wall face where the rooms are probed


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


def _room_at(rooms, p, z, exclude=()):
    """The smallest room containing point p (2D) at height z, or None."""
    hits = [ri for ri, r in enumerate(rooms) if ri not in exclude and r.contains(p, z)]
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


def connect(pos, n, half, rooms, rsb_rooms):
    """The rooms on both sides of a doorway: probes beyond each wall face, then space boundaries.

    rsb_rooms: room indices that IfcRelSpaceBoundary names for this door (may be empty).
    """
    z = pos[2] + 0.1
    found = []
    for sign in (1.0, -1.0):
        probe = pos[:2] + sign * (half + PROBE_BEYOND) * n[:2]
        ri = _room_at(rooms, probe, z, exclude=found)
        if ri is not None:
            found.append(ri)
    for ri in sorted(rsb_rooms):
        if len(found) >= 2:
            break
        if ri not in found:
            found.append(ri)
    return sorted(found)
