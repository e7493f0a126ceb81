"""Which wall-surfaces bound which rooms.

A surface bounds a room when an edge of the room's footprint lies on the surface's plane (within a
tolerance), their extents overlap along the wall, and the room's inside is on the side the
surface's normal points to. IfcRelSpaceBoundary, where the file has it, names (space, wall) pairs
that are then accepted with a looser tolerance (spaces drawn to the wall axis, finishes...).
"""
import numpy as np

from .spaces import point_in_polygon

PARALLEL_SIN = np.sin(np.radians(5.0))
STRICT_TOL = 0.05       # m: polygon edge to face plane
MIN_CONTACT = 0.05      # m: overlap along the wall
PROBE = 0.05            # m: step into the room from its edge


def _overlap(a, b):
    return min(a[1], b[1]) - max(a[0], b[0])


def contact(face, room, tol=STRICT_TOL):
    """Length (m) along which `face` bounds `room` (a spaces.Room), 0.0 if it does not."""
    room_h = room.z_max - room.z_min
    if _overlap(face.z_range, (room.z_min, room.z_max)) < min(0.3, 0.5 * room_h):
        return 0.0
    n2, t2 = face.normal[:2], face.tangent[:2]
    f0, f1 = face.t_range()
    poly = room.polygon
    total = 0.0
    for k in range(len(poly)):
        p, q = poly[k], poly[(k + 1) % len(poly)]
        e = q - p
        length = float(np.hypot(e[0], e[1]))
        if length < 1e-6 or abs(e @ n2) / length > PARALLEL_SIN:
            continue
        dp, dq = float(n2 @ p - face.d), float(n2 @ q - face.d)
        if abs(dp) > tol or abs(dq) > tol:
            continue
        sp, sq = float(t2 @ p), float(t2 @ q)
        lo, hi = max(min(sp, sq), f0), min(max(sp, sq), f1)
        if hi - lo < MIN_CONTACT:
            continue
        u = (0.5 * (lo + hi) - sp) / (sq - sp)
        m = p + u * e
        behind = max(0.0, -float(n2 @ m - face.d))
        if point_in_polygon(m + n2 * (PROBE + behind), poly):
            total += hi - lo
    return total


def bound_rooms(walls, rooms, rsb_pairs):
    """{(room index, surface id)} pairs.

    walls: [(ifc_id, WallPiece, (surface id a, surface id b))]; rooms: [spaces.Room];
    rsb_pairs: {(space ifc id, element ifc id)} from IfcRelSpaceBoundary.
    """
    pairs = set()
    for ri, room in enumerate(rooms):
        x0, y0 = room.polygon.min(axis=0) - 1.0
        x1, y1 = room.polygon.max(axis=0) + 1.0
        for ifc_id, piece, sids in walls:
            pts = np.vstack([f.points[:, :2] for f in piece.faces])
            if pts[:, 0].max() < x0 or pts[:, 0].min() > x1 or pts[:, 1].max() < y0 \
                    or pts[:, 1].min() > y1:
                continue
            scores = [contact(f, room) for f in piece.faces]
            if max(scores) <= 0.0 and (room.ifc_id, ifc_id) in rsb_pairs:
                loose = 0.5 * piece.thickness + STRICT_TOL
                scores = [contact(f, room, loose) for f in piece.faces]
            for sid, score in zip(sids, scores):
                if score > 0.0:
                    pairs.add((ri, sid))
    return pairs
