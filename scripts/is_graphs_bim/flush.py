"""Wall-surfaces from building elements other than walls that bound a room (issue 24).

An IfcColumn (or IfcMember, IfcPlate, IfcBuildingElementProxy) that a PHYSICAL
IfcRelSpaceBoundary names as bounding a space, and one of whose vertical faces lies on that
space's outline (flush: a footprint edge on the face's plane, the room on the side the face looks
at, no material of the element in front of it), gives that face as a wall-surface of the room when
the face is at least MIN_WIDTH wide and covers most of the room's height (a column's face in a
room corner, which a LiDAR sees as wall). A column standing free in a room is not on its outline
and gives nothing.

Each such face becomes a pseudo-wall (`walls[].kind == "flush_element"`): the face and the
element's opposite side (its back: the parallel plane through the element's furthest point behind
the face, or the opposite face when that one is flush with a room too), so that every wall keeps
two opposed surfaces.
"""
from dataclasses import dataclass, field

import numpy as np

from . import boundaries, walls

CLASSES = ("IfcColumn", "IfcMember", "IfcPlate", "IfcBuildingElementProxy")
MIN_WIDTH = 0.3             # m: narrower faces are not wall
MIN_HEIGHT_SHARE = 0.8      # of the room's height (z_max - z_min) the face must cover
IN_FRONT_TOL = 0.02         # m: element material allowed in front of a flush face


@dataclass
class Found:
    """One pseudo-wall: a straight piece and the rooms each of its two faces bounds."""
    entity: object
    piece: walls.WallPiece
    rooms: tuple = field(default_factory=lambda: (set(), set()))   # room indices per face


def candidates(model, rooms):
    """{element step id: (element, sorted room indices)} for the elements of CLASSES that a
    PHYSICAL IfcRelSpaceBoundary names, except curtain wall parts (the curtain wall covers them).
    The room list holds only converted spaces; an element naming none gets []."""
    room_of = {r.ifc_id: ri for ri, r in enumerate(rooms)}
    out = {}
    for rel in model.file.by_type("IfcRelSpaceBoundary"):
        e, sp = rel.RelatedBuildingElement, rel.RelatingSpace
        if e is None or sp is None or rel.PhysicalOrVirtualBoundary != "PHYSICAL":
            continue
        if not any(e.is_a(c) for c in CLASSES) or _in_curtain_wall(e):
            continue
        entry = out.setdefault(e.id(), (e, set()))
        if sp.id() in room_of:
            entry[1].add(room_of[sp.id()])
    return {k: (e, sorted(rs)) for k, (e, rs) in sorted(out.items())}


def _in_curtain_wall(e):
    for rel in getattr(e, "Decomposes", None) or ():
        whole = rel.RelatingObject
        if whole is not None and (whole.is_a("IfcCurtainWall") or _in_curtain_wall(whole)):
            return True
    return False


def _face_verdict(face, room, verts):
    """'ok', or why this oriented face does not bound the room: 'not flush', 'narrow', 'low'."""
    if float(np.max(verts @ face.normal - face.d)) > IN_FRONT_TOL:
        return "not flush"          # material in front: not an outer face on this side
    if boundaries.contact(face, room) <= 0.0:
        return "not flush"
    s0, s1 = face.t_range()
    if s1 - s0 < MIN_WIDTH:
        return "narrow"
    z0, z1 = face.z_range
    h = room.z_max - room.z_min
    if min(z1, room.z_max) - max(z0, room.z_min) < MIN_HEIGHT_SHARE * h:
        return "low"
    return "ok"


REASONS = {   # worst first: the reason given is the closest the element came to being used
    "low": "its face flush with the room outline is not wall-high",
    "narrow": f"its face flush with the room outline is narrower than {MIN_WIDTH} m",
    "not flush": "it is not flush with the outline of any room it bounds (free-standing)",
}


def element_faces(shape, room_ids, rooms):
    """([Found], reason or None): the pseudo-walls of one element."""
    planes, _ = walls.vertical_planes(shape)
    planes = [p for p in planes if p.area >= walls.MIN_FACE_AREA]
    verts = shape.verts
    hits = []           # [(oriented plane, {room index})]
    verdicts = set()
    for p in planes:
        for face in (p, p.flipped()):
            got = set()
            for ri in room_ids:
                v = _face_verdict(face, rooms[ri], verts)
                verdicts.add(v)
                if v == "ok":
                    got.add(ri)
            if got:
                hits.append((face, got))
    if not hits:
        why = next((REASONS[k] for k in ("low", "narrow", "not flush") if k in verdicts),
                   REASONS["not flush"])
        return [], why
    out, used = [], [False] * len(hits)
    for i, (a, ra) in enumerate(hits):
        if used[i]:
            continue
        used[i] = True
        partner = None
        for j in range(i + 1, len(hits)):
            b, rb = hits[j]
            if not used[j] and a.normal @ b.normal < -walls.PARALLEL_COS \
                    and a.d + b.d >= walls.MIN_THICKNESS:
                partner = j
                break
        if partner is not None:          # two opposite faces, each flush with a room
            used[partner] = True
            b, rb = hits[partner]
            out.append(Found(None, walls._make_piece(a, b), (set(ra), set(rb))))
            continue
        s = verts @ a.normal
        back_d = float(s.min())
        back_pts = verts[s <= back_d + walls.COPLANAR_TOL]
        if a.d - back_d < walls.MIN_THICKNESS:
            continue                    # no depth behind it (a surface element)
        back = walls.Plane(-a.normal, -back_d, 0.0, back_pts)
        out.append(Found(None, walls._make_piece(a, back), (set(ra), set())))
    if not out:
        return [], "its flush faces have no material behind them (no thickness)"
    return out, None


def is_external(element):
    """IsExternal from the element's Pset_<Class>Common when present, else False (an element
    in a room's outline is not taken as part of the building envelope)."""
    import ifcopenshell.util.element as uelement
    for name, props in uelement.get_psets(element).items():
        if name.startswith("Pset_") and name.endswith("Common") and "IsExternal" in props:
            return bool(props["IsExternal"])
    return False
