"""Doorways of kind "door" (IfcDoor) and "opening" (unfilled wall openings): their host wall,
position, size and the rooms they join (doors.py, openings.py; docs/agraph_format.md)."""
from collections import defaultdict

from . import doors, ifc_model, openings


def convert_doors(model, shapes, wall_list, rooms, sidx, rsb, diag, tally):
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
            tally.drop(sidx.of(door), door, "no geometry")
            continue
        pieces = by_host.get(host.id(), []) if host is not None else []
        if host is None:
            diag.warn("no host wall (no IfcRelFillsElement/IfcRelVoidsElement): wall -1", door)
        elif not pieces and host.is_a("IfcWall"):
            diag.warn(f"its host {ifc_model.entity_label(host)} was skipped: wall -1", door)
        wi, pos, width, height, n, half = doors.locate(door, shape.verts, pieces,
                                                       model.length_unit_m)
        rsb_rooms = {room_of_space[s] for s, e in rsb if e == door.id() and s in room_of_space}
        top = max(float(shape.verts[:, 2].max()), float(pos[2]) + height)
        found = doors.connect(pos, n, half, rooms, rsb_rooms, top)
        if not found:
            diag.warn("touches no room (no IfcSpace on either side of it): skipped", door)
            tally.drop(sidx.of(door, float(pos[2])), door, "touches no room")
            continue
        if len(found) == 1 and not (wi >= 0 and wall_list[wi].external):
            name = rooms[found[0]].entity.Name or ""
            diag.warn(f"opens into one room only ({ifc_model.entity_label(rooms[found[0]].entity)}"
                      f" '{name}') but is not on an external wall: kept as an exterior doorway",
                      door)
        storey = sidx.of(door, float(pos[2]))
        out.append(doors.Doorway(door, storey, wi, pos, width, height, found))
    return out


def _walls_by_host(wall_list):
    by_host = defaultdict(list)
    for wi, wo in enumerate(wall_list):
        by_host[wo.entity.id()].append((wi, wo.piece))
    return by_host


def convert_openings(model, shapes, wall_list, rooms, sidx, door_list, diag, tally):
    """Doorways of kind "opening": unfilled openings through walls (see openings.py)."""
    by_host = _walls_by_host(wall_list)
    out = []
    for op in sorted(model.file.by_type("IfcOpeningElement"), key=lambda o: o.id()):
        if getattr(op, "HasFillings", None):
            continue        # a door (or a window) fills it
        voids = getattr(op, "VoidsElements", None) or ()
        host = voids[0].RelatingBuildingElement if voids else None
        if host is None:
            diag.warn("opening in no element (no IfcRelVoidsElement): not a doorway", op)
            tally.drop(sidx.of(op), op, "in no element")
            continue
        if not host.is_a("IfcWall"):
            # Openings in slabs, roofs and furniture (stair holes...): not passages between rooms.
            tally.drop(sidx.of(op), op, f"in an {host.is_a()}, not in a wall")
            continue
        pieces = by_host.get(host.id(), [])
        if not pieces:
            diag.warn(f"its host {ifc_model.entity_label(host)} was skipped: not a doorway", op)
            tally.drop(sidx.of(op), op, "host wall skipped")
            continue
        shape = shapes.get(op.id())
        if shape is None:
            diag.warn("doorless opening without geometry: not a doorway", op)
            tally.drop(sidx.of(op), op, "no geometry")
            continue
        wi, pos, _, _, n, half = doors.locate(op, shape.verts, pieces, model.length_unit_m)
        piece = wall_list[wi].piece
        top = float(shape.verts[:, 2].max())
        found = doors.connect(pos, n, half, rooms, set(), top)
        fit = openings.fit_opening(shape.verts, piece, [rooms[ri].floor_z for ri in found])
        storey = sidx.of(op, float(pos[2]))
        if not fit.ok:
            diag.warn(f"doorless opening in {ifc_model.entity_label(host)} that {fit.why}: "
                      "not a doorway", op)
            tally.drop(storey, op, fit.why.split(" (")[0])
            continue
        t = piece.faces[0].tangent
        dup = [d for d in door_list if d.wall == wi
               and abs((d.position - pos) @ t) < 0.5 * (fit.width + d.width)]
        if dup:
            diag.warn(f"doorless opening overlapping {ifc_model.entity_label(dup[0].entity)} in "
                      "the same wall: not a second doorway", op)
            tally.drop(storey, op, "overlaps a door")
            continue
        if not found:
            diag.warn("doorless opening that touches no room: not a doorway", op)
            tally.drop(storey, op, "touches no room")
            continue
        if len(found) == 1 and not wall_list[wi].external:
            room = rooms[found[0]].entity
            diag.warn(f"doorless opening into one room only ({ifc_model.entity_label(room)} "
                      f"'{room.Name or ''}') but not in an external wall: kept as an exterior "
                      "doorway", op)
        out.append(doors.Doorway(op, storey, wi, pos, fit.width, fit.height, found, "opening"))
    return out
