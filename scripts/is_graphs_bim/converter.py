"""IFC -> A-Graph: the whole conversion, element by element (docs/agraph_format.md)."""
from collections import Counter, defaultdict
from dataclasses import dataclass, field

import numpy as np

from . import (boundaries, door_conversion, doors, floors, flush, ifc_model, mesh, openings,
               room_floors, spaces, walls)
from .floors import Floors


@dataclass
class WallOut:
    entity: object
    storey: int
    piece: walls.WallPiece
    surfaces: tuple         # (surface id, surface id)
    external: bool
    kind: str = "wall"      # "wall" | "curtain_wall" | "flush_element" (flush.py)
    face_rooms: tuple = None   # flush_element: (room ids of face a, of face b)


@dataclass
class Result:
    model: ifc_model.IfcModel
    storeys: list           # [(entity or None, elevation, height)]
    walls: list             # [WallOut]
    rooms: list             # [spaces.Room]
    doorways: list          # [doors.Doorway]
    shapes: dict            # {step id: mesh.Shape}
    warnings: list
    dropped: dict = field(default_factory=dict)   # {storey: Counter({(IfcClass, reason): n})}
    made_floors: Floors = field(default_factory=Floors)   # made from spaces (issue 24)


class Tally:
    """What the conversion dropped, per storey and reason (the A-Graph's "report")."""

    def __init__(self):
        self.dropped = defaultdict(Counter)

    def drop(self, storey, entity_or_class, reason):
        what = entity_or_class if isinstance(entity_or_class, str) else entity_or_class.is_a()
        self.dropped[storey][(what, reason)] += 1


class _StoreyIndex:
    def __init__(self, storeys):
        self.by_id = {s.id(): k for k, (s, _) in enumerate(storeys) if s is not None}
        self.elevations = [z for _, z in storeys]

    def of(self, element, z=None):
        s = ifc_model.storey_of(element)
        if s is not None and s.id() in self.by_id:
            return self.by_id[s.id()]
        if z is None or not self.elevations:
            return 0
        below = [k for k, e in enumerate(self.elevations) if e <= z + 0.1]
        return below[-1] if below else 0


def _convert_walls(model, shapes, sidx, diag, tally):
    out = []
    for w in sorted(model.file.by_type("IfcWall"), key=lambda w: w.id()):
        shape = shapes.get(w.id())
        if shape is None:
            diag.warn("no 3D body geometry (missing, empty or failed to triangulate): skipped", w)
            tally.drop(sidx.of(w), w, "no 3D body geometry")
            continue
        kind, axis_dir = walls.axis_info(w)
        if kind == "curved":
            diag.warn("curved wall (its axis is an arc): cannot split into two plane faces; "
                      "skipped", w)
            tally.drop(sidx.of(w), w, "curved")
            continue
        pieces, problem = walls.wall_pieces(shape, axis_dir)
        if problem:
            diag.warn(f"{problem}: skipped", w)
            tally.drop(sidx.of(w, float(shape.verts[:, 2].min())), w, problem.split(" (")[0])
            continue
        if len(pieces) > 1:
            diag.warn(f"footprint is not one straight piece: split into {len(pieces)} straight "
                      "walls with the same ifc_id", w)
        storey = sidx.of(w, min(p.z_min for p in pieces))
        ext = ifc_model.wall_is_external(w)
        for p in pieces:
            out.append(WallOut(w, storey, p, (-1, -1), ext))
    out += _convert_curtain_walls(model, shapes, sidx, diag, tally)
    return out


def _number_walls(out):
    out.sort(key=lambda wo: (wo.storey, wo.entity.id()))   # stable: keeps piece order
    for k, wo in enumerate(out):
        wo.surfaces = (2 * k, 2 * k + 1)
    return out


def _convert_flush_elements(model, shapes, rooms, sidx, diag, tally):
    """Pseudo-walls of columns and other elements flush with the outline of a room a space
    boundary says they bound (flush.py)."""
    out = []
    for _, (e, room_ids) in flush.candidates(model, rooms).items():
        shape = shapes.get(e.id())
        if not room_ids:
            diag.warn("named by an IfcRelSpaceBoundary, but none of the spaces it bounds is a "
                      "room: no wall-surface", e)
            tally.drop(sidx.of(e), e, "bounds no converted room")
            continue
        if shape is None:
            diag.warn("bounds a room (IfcRelSpaceBoundary) but has no 3D body geometry: no "
                      "wall-surface", e)
            tally.drop(sidx.of(e), e, "no 3D body geometry")
            continue
        found, why = flush.element_faces(shape, room_ids, rooms)
        if not found:
            names = ", ".join(f"'{rooms[ri].entity.Name or ''}'" for ri in room_ids)
            diag.warn(f"bounds room(s) {names} (IfcRelSpaceBoundary) but {why}: no wall-surface",
                      e)
            tally.drop(sidx.of(e, float(shape.verts[:, 2].min())), e, why.split(" (")[0])
            continue
        ext = flush.is_external(e)
        for fd in found:
            out.append(WallOut(e, sidx.of(e, fd.piece.z_min), fd.piece, (-1, -1), ext,
                               "flush_element", fd.rooms))
    return out


def _parts(element, depth=0):
    """An element's parts (IfcRelAggregates), recursively."""
    out = []
    for rel in getattr(element, "IsDecomposedBy", None) or ():
        for p in rel.RelatedObjects or ():
            out.append(p)
            if depth < 4:
                out += _parts(p, depth + 1)
    return out


def _convert_curtain_walls(model, shapes, sidx, diag, tally):
    """An IfcCurtainWall (its own body and its plates and members together) is one straight wall
    whose faces are the outer planes of all its parts."""
    out = []
    for cw in sorted(model.file.by_type("IfcCurtainWall"), key=lambda w: w.id()):
        parts = _parts(cw)
        panels = [p for p in parts if p.is_a("IfcPlate") and p.id() in shapes]
        pieces = [shapes[e.id()] for e in [cw] + parts if e.id() in shapes]
        if not panels:
            diag.warn(f"curtain wall without panels (no IfcPlate with geometry among its "
                      f"{len(parts)} parts): skipped", cw)
            tally.drop(sidx.of(cw), cw, "curtain wall without panels")
            continue
        points = np.vstack([sh.verts for sh in pieces])
        piece, problem = walls.straight_piece(points)
        if piece is None:
            diag.warn(f"curtain wall {problem}: skipped", cw)
            tally.drop(sidx.of(cw, float(points[:, 2].min())), cw, "curtain wall not straight")
            continue
        storey = sidx.of(cw, piece.z_min)
        out.append(WallOut(cw, storey, piece, (-1, -1), ifc_model.wall_is_external(cw),
                           "curtain_wall"))
    return out


def _convert_rooms(model, shapes, sidx, diag, tally):
    rooms = []
    for sp in sorted(model.file.by_type("IfcSpace"), key=lambda s: s.id()):
        shape = shapes.get(sp.id())
        if shape is None:
            diag.warn("no 3D body geometry: no usable footprint (not a room); skipped", sp)
            tally.drop(sidx.of(sp), sp, "no 3D body geometry")
            continue
        poly, z_min, z_max = spaces.footprint(shape)
        if poly is None:
            diag.warn(f"no usable footprint ({z_min}): not a room (no floor area); skipped", sp)
            tally.drop(sidx.of(sp), sp, "no floor area")
            continue
        rooms.append(spaces.Room(sp, sidx.of(sp, z_min), poly, z_min, z_max))
    if not rooms:
        raise ifc_model.ConversionError("no IfcSpace with a usable footprint: rooms cannot be built")
    rooms.sort(key=lambda r: (r.storey, r.ifc_id))
    return rooms


def _space_boundary_pairs(model):
    pairs = set()
    for rel in model.file.by_type("IfcRelSpaceBoundary"):
        space, element = rel.RelatingSpace, rel.RelatedBuildingElement
        if space is not None and element is not None:
            pairs.add((space.id(), element.id()))
    return pairs


def _check_rooms(model, rooms, diag):
    """Warnings for spaces that are poor rooms: no bounding wall, no space boundary."""
    bounded = {rel.RelatingSpace.id() for rel in model.file.by_type("IfcRelSpaceBoundary")
               if rel.RelatingSpace is not None}
    for r in rooms:
        if not r.surfaces:
            diag.warn("no wall-surface along its outline (not a room bounded by walls): kept as "
                      "a room without walls (its footprint and doorways only)", r.entity)
        if bounded and r.ifc_id not in bounded:
            diag.warn("no IfcRelSpaceBoundary (the file has them for other spaces): its walls "
                      "found from the geometry alone", r.entity)


def _infer_external(wall_list, rooms):
    """IsExternal when given; else a wall one face of which bounds a room and the other none."""
    bounded = defaultdict(int)
    for r in rooms:
        for sid in r.surfaces:
            bounded[sid] += 1
    for wo in wall_list:
        if wo.external is None:
            a, b = (bounded[s] > 0 for s in wo.surfaces)
            wo.external = a != b


def _wall_like_shapes(model, shapes):
    """Shapes that stand between rooms: walls, curtain walls and their parts."""
    out = []
    for cls in ("IfcWall", "IfcCurtainWall"):
        for e in model.file.by_type(cls):
            parts = [e] + [p for rel in getattr(e, "IsDecomposedBy", None) or ()
                           for p in rel.RelatedObjects]
            out.extend(shapes[p.id()] for p in parts if p.id() in shapes)
    return out


def _convert_virtual(model, shapes, rooms, sidx, door_list, diag, tally):
    """Doorways of kind "virtual": open boundaries between two spaces (see openings.py)."""
    f = model.file
    rsb = f.by_type("IfcRelSpaceBoundary")
    room_of = {r.ifc_id: ri for ri, r in enumerate(rooms)}
    marked = {rel.RelatingSpace.id() for rel in rsb
              if rel.RelatingSpace is not None and rel.PhysicalOrVirtualBoundary == "VIRTUAL"}
    by_pair = {}
    for ve in sorted(f.by_type("IfcVirtualElement"), key=lambda e: e.id()):
        spaces_ = sorted({rel.RelatingSpace.id() for rel in f.get_inverse(ve)
                          if rel.is_a("IfcRelSpaceBoundary") and rel.RelatingSpace is not None})
        rs = sorted({room_of[s] for s in spaces_ if s in room_of})
        if len(rs) != 2:
            diag.warn(f"virtual separation bounding {len(rs)} converted space(s) (two are "
                      "needed): not a doorway", ve)
            tally.drop(sidx.of(ve), ve, "does not separate two rooms")
            continue
        a, b = rs
        if rooms[a].storey != rooms[b].storey:
            diag.warn("virtual separation between spaces on different storeys "
                      f"({ifc_model.entity_label(rooms[a].entity)} '{rooms[a].entity.Name or ''}',"
                      f" {ifc_model.entity_label(rooms[b].entity)} '{rooms[b].entity.Name or ''}'"
                      "): a vertical link (stair, void), not a doorway", ve)
            tally.drop(rooms[a].storey, ve, "joins spaces on different storeys")
            continue
        by_pair[(a, b)] = ve
    blockers = openings.WallFootprints(_wall_like_shapes(model, shapes))
    out, used = [], set()
    for a in range(len(rooms)):
        ra = rooms[a]
        lo_a, hi_a = ra.polygon.min(axis=0) - 0.1, ra.polygon.max(axis=0) + 0.1
        for b in range(a + 1, len(rooms)):
            rb = rooms[b]
            if rb.storey != ra.storey:
                continue
            if (a, b) not in by_pair and rsb and ra.ifc_id not in marked \
                    and rb.ifc_id not in marked:
                continue
            lo_b, hi_b = rb.polygon.min(axis=0), rb.polygon.max(axis=0)
            if np.any(lo_b > hi_a) or np.any(hi_b < lo_a):
                continue
            best = None
            for seg in openings.shared_stretches(ra.polygon, rb.polygon):
                run = openings.open_runs(seg, blockers)
                if run is not None and (best is None or np.hypot(*(run[1] - run[0]))
                                        > np.hypot(*(best[1] - best[0]))):
                    best = run
            width = float(np.hypot(*(best[1] - best[0]))) if best is not None else 0.0
            ve = by_pair.get((a, b))
            if width < openings.MIN_WIDTH:
                if ve is not None:
                    diag.warn("virtual separation whose two spaces share no wall-free boundary "
                              f"of {openings.MIN_WIDTH} m or more: not a doorway", ve)
                    tally.drop(ra.storey, ve, "no shared wall-free boundary")
                    used.add((a, b))
                continue
            mid = 0.5 * (best[0] + best[1])
            near = [d for d in door_list if sorted(d.rooms) == [a, b]
                    and _dist_to_segment(d.position[:2], best) < 0.3]
            if near:        # the door or opening there already joins them
                used.add((a, b))
                if ve is not None:
                    tally.drop(ra.storey, ve, "a door already joins its spaces there")
                continue
            z0 = max(ra.z_min, rb.z_min)
            pos = np.array([mid[0], mid[1], z0])
            used.add((a, b))
            out.append(doors.Doorway(ve, ra.storey, -1, pos, width,
                                     min(ra.z_max, rb.z_max) - z0, [a, b], "virtual"))
    for pair, ve in sorted(by_pair.items()):
        if pair not in used:
            diag.warn("virtual separation whose two spaces do not touch: not a doorway", ve)
            tally.drop(rooms[pair[0]].storey, ve, "its spaces do not touch")
    return out


def _dist_to_segment(p, seg):
    a, b = seg
    ab = b - a
    u = 0.0 if ab @ ab < 1e-12 else float(np.clip((p - a) @ ab / (ab @ ab), 0.0, 1.0))
    return float(np.hypot(*(p - (a + u * ab))))


def _number_doorways(doorways, rooms):
    def key(d):
        has = d.entity is not None
        return (d.storey, 0 if has else 1, d.entity.id() if has else 0,
                round(float(d.position[0]), 3), round(float(d.position[1]), 3))
    doorways.sort(key=key)
    for di, d in enumerate(doorways):
        for ri in d.rooms:
            rooms[ri].doorways.add(di)
    return doorways


def _storey_heights(storeys, wall_list):
    out = []
    for k, (s, z) in enumerate(storeys):
        if k + 1 < len(storeys):
            h = storeys[k + 1][1] - z
        else:
            tops = [wo.piece.z_max - z for wo in wall_list if wo.storey == k]
            h = max(tops) if tops else 0.0
        out.append((s, z, max(0.0, h)))
    return out


def convert(path, diag, allow_dangling=False):
    """Converts one IFC file; raises ifc_model.ConversionError when it cannot."""
    model, forced_unit = ifc_model.open_model(path, diag, allow_dangling)
    if not model.file.by_type("IfcWall"):
        raise ifc_model.ConversionError(
            "no IfcWall in the file: an A-Graph needs walls (were walls exported as IfcWall?)")
    if not model.file.by_type("IfcSpace"):
        raise ifc_model.ConversionError(
            "no IfcSpace in the file: rooms cannot be built; the authoring tool must export "
            "spaces (Revit: rooms/areas, ArchiCAD: zones) to IFC as IfcSpace")
    shapes = mesh.triangulate(model, forced_unit)
    storeys = ifc_model.list_storeys(model, diag, shapes)
    if not storeys:
        diag.warn("no IfcBuildingStorey: everything is put on one storey at elevation 0")
        storeys = [(None, 0.0)]
    sidx = _StoreyIndex(storeys)
    tally = Tally()
    wall_list = _convert_walls(model, shapes, sidx, diag, tally)
    if not wall_list:
        raise ifc_model.ConversionError("no IfcWall could be converted (see the warnings above)")
    rooms = _convert_rooms(model, shapes, sidx, diag, tally)
    room_floors.assign(model, shapes, rooms, storeys, diag)
    wall_list = _number_walls(
        wall_list + _convert_flush_elements(model, shapes, rooms, sidx, diag, tally))
    rsb = _space_boundary_pairs(model)
    triples = [(wo.entity.id(), wo.piece, wo.surfaces) for wo in wall_list
               if wo.kind != "flush_element"]
    for ri, sid in boundaries.bound_rooms(triples, rooms, rsb):
        rooms[ri].surfaces.add(sid)
    for wo in wall_list:
        if wo.kind == "flush_element":
            for sid, room_ids in zip(wo.surfaces, wo.face_rooms):
                for ri in room_ids:
                    rooms[ri].surfaces.add(sid)
    _check_rooms(model, rooms, diag)
    _infer_external(wall_list, rooms)
    door_list = door_conversion.convert_doors(model, shapes, wall_list, rooms, sidx, rsb, diag,
                                              tally)
    door_list += door_conversion.convert_openings(model, shapes, wall_list, rooms, sidx, door_list,
                                                  diag, tally)
    door_list += _convert_virtual(model, shapes, rooms, sidx, door_list, diag, tally)
    doorways = _number_doorways(door_list, rooms)
    made = floors.make_floors(model, shapes, rooms, storeys, sidx, diag)
    return Result(model, _storey_heights(storeys, wall_list), wall_list, rooms, doorways,
                  shapes, diag.warnings, dict(tally.dropped), made)


def surface_rooms(result):
    """{surface id: sorted room ids}."""
    out = defaultdict(list)
    for ri, r in enumerate(result.rooms):
        for sid in r.surfaces:
            out[sid].append(ri)
    return {k: sorted(v) for k, v in out.items()}


def orientation(normal):
    c = float(np.cos(np.radians(10.0)))
    if abs(normal[0]) >= c:
        return "x"
    if abs(normal[1]) >= c:
        return "y"
    return "other"
