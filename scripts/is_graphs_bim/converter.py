"""IFC -> A-Graph: the whole conversion, element by element (docs/agraph_format.md)."""
from collections import defaultdict
from dataclasses import dataclass

import numpy as np

from . import boundaries, doors, ifc_model, mesh, spaces, walls


@dataclass
class WallOut:
    entity: object
    storey: int
    piece: walls.WallPiece
    surfaces: tuple         # (surface id, surface id)
    external: bool


@dataclass
class Result:
    model: ifc_model.IfcModel
    storeys: list           # [(entity or None, elevation, height)]
    walls: list             # [WallOut]
    rooms: list             # [spaces.Room]
    doorways: list          # [doors.Doorway]
    shapes: dict            # {step id: mesh.Shape}
    warnings: list


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


def _convert_walls(model, shapes, sidx, diag):
    out = []
    for w in sorted(model.file.by_type("IfcWall"), key=lambda w: w.id()):
        shape = shapes.get(w.id())
        if shape is None:
            diag.warn("no 3D body geometry (missing, empty or failed to triangulate): skipped", w)
            continue
        kind, axis_dir = walls.axis_info(w)
        if kind == "curved":
            diag.warn("curved wall (its axis is an arc): cannot split into two plane faces; "
                      "skipped", w)
            continue
        pieces, problem = walls.wall_pieces(shape, axis_dir)
        if problem:
            diag.warn(f"{problem}: skipped", w)
            continue
        if len(pieces) > 1:
            diag.warn(f"footprint is not one straight piece: split into {len(pieces)} straight "
                      "walls with the same ifc_id", w)
        storey = sidx.of(w, min(p.z_min for p in pieces))
        ext = ifc_model.wall_is_external(w)
        for p in pieces:
            out.append(WallOut(w, storey, p, (-1, -1), ext))
    out.sort(key=lambda wo: (wo.storey, wo.entity.id()))   # stable: keeps piece order
    for k, wo in enumerate(out):
        wo.surfaces = (2 * k, 2 * k + 1)
    return out


def _convert_rooms(model, shapes, sidx, diag):
    rooms = []
    for sp in sorted(model.file.by_type("IfcSpace"), key=lambda s: s.id()):
        shape = shapes.get(sp.id())
        if shape is None:
            diag.warn("no 3D body geometry: no usable footprint; skipped", sp)
            continue
        poly, z_min, z_max = spaces.footprint(shape)
        if poly is None:
            diag.warn(f"no usable footprint ({z_min}): skipped", sp)
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


def _convert_doors(model, shapes, wall_list, rooms, sidx, rsb, diag):
    by_host = defaultdict(list)
    for wi, wo in enumerate(wall_list):
        by_host[wo.entity.id()].append((wi, wo.piece))
    room_of_space = {r.ifc_id: ri for ri, r in enumerate(rooms)}
    out = []
    for door in sorted(model.file.by_type("IfcDoor"), key=lambda d: d.id()):
        host, opening = doors.host_wall_entity(door)
        shape = shapes.get(door.id()) or (shapes.get(opening.id()) if opening else None)
        if shape is None:
            diag.warn("no geometry for the door or its opening: skipped", door)
            continue
        pieces = by_host.get(host.id(), []) if host is not None else []
        if host is None:
            diag.warn("no host wall (no IfcRelFillsElement/IfcRelVoidsElement): wall -1", door)
        elif not pieces and host.is_a("IfcWall"):
            diag.warn(f"its host {ifc_model.entity_label(host)} was skipped: wall -1", door)
        wi, pos, width, height, n, half = doors.locate(door, shape.verts, pieces,
                                                       model.length_unit_m)
        rsb_rooms = {room_of_space[s] for s, e in rsb if e == door.id() and s in room_of_space}
        found = doors.connect(pos, n, half, rooms, rsb_rooms)
        if not found:
            diag.warn("touches no room (no IfcSpace on either side of it): skipped", door)
            continue
        if len(found) == 1 and not (wi >= 0 and wall_list[wi].external):
            name = rooms[found[0]].entity.Name or ""
            diag.warn(f"opens into one room only ({ifc_model.entity_label(rooms[found[0]].entity)}"
                      f" '{name}') but is not on an external wall: kept as an exterior doorway",
                      door)
        storey = sidx.of(door, float(pos[2]))
        out.append(doors.Doorway(door, storey, wi, pos, width, height, found))
    out.sort(key=lambda d: (d.storey, d.entity.id()))
    for di, d in enumerate(out):
        for ri in d.rooms:
            rooms[ri].doorways.add(di)
    return out


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


def convert(path, diag):
    """Converts one IFC file; raises ifc_model.ConversionError when it cannot."""
    model, forced_unit = ifc_model.open_model(path, diag)
    storeys = ifc_model.list_storeys(model)
    if not storeys:
        diag.warn("no IfcBuildingStorey: everything is put on one storey at elevation 0")
        storeys = [(None, 0.0)]
    sidx = _StoreyIndex(storeys)
    if not model.file.by_type("IfcWall"):
        raise ifc_model.ConversionError(
            "no IfcWall in the file: an A-Graph needs walls (were walls exported as IfcWall?)")
    if not model.file.by_type("IfcSpace"):
        raise ifc_model.ConversionError(
            "no IfcSpace in the file: rooms cannot be built; the authoring tool must export "
            "spaces (Revit: rooms/areas, ArchiCAD: zones) to IFC as IfcSpace")
    shapes = mesh.triangulate(model, forced_unit)
    wall_list = _convert_walls(model, shapes, sidx, diag)
    if not wall_list:
        raise ifc_model.ConversionError("no IfcWall could be converted (see the warnings above)")
    rooms = _convert_rooms(model, shapes, sidx, diag)
    rsb = _space_boundary_pairs(model)
    triples = [(wo.entity.id(), wo.piece, wo.surfaces) for wo in wall_list]
    for ri, sid in boundaries.bound_rooms(triples, rooms, rsb):
        rooms[ri].surfaces.add(sid)
    _infer_external(wall_list, rooms)
    doorways = _convert_doors(model, shapes, wall_list, rooms, sidx, rsb, diag)
    return Result(model, _storey_heights(storeys, wall_list), wall_list, rooms, doorways,
                  shapes, diag.warnings)


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
