"""Writing a conversion result as `<prefix>.agraph.json` + `<prefix>.obj` (docs/agraph_format.md).

Output is deterministic: elements in sorted order, floats rounded to 1e-6 (no -0.0), one element
per line so that diffs of two conversions stay readable.
"""
import json
import os

from . import CONVERTER_VERSION, mesh
from .converter import orientation, surface_rooms
from .room_floors import per_storey
from .spaces import centroid


def _r(x):
    v = round(float(x), 6)
    return 0.0 if v == 0.0 else v


def _v(xs):
    return [_r(x) for x in xs]


def _guid(entity):
    return getattr(entity, "GlobalId", None) or "" if entity is not None else ""


def _id(entity):
    return entity.id() if entity is not None else -1


def build(result, mesh_name):
    """The A-Graph as a JSON-ready dict."""
    m = result.model
    s_rooms = surface_rooms(result)
    storeys = [{"id": k, "ifc_id": _id(s), "guid": _guid(s), "name": (s.Name or "") if s else "",
                "elevation": _r(z), "height": _r(h)}
               for k, (s, z, h) in enumerate(result.storeys)]
    surfaces, walls = [], []
    for wi, wo in enumerate(result.walls):
        p = wo.piece
        for face, sid in zip(p.faces, wo.surfaces):
            t = face.tangent
            s0, s1 = face.t_range()
            surfaces.append({
                "id": sid, "ifc_id": wo.entity.id(), "guid": _guid(wo.entity), "wall": wi,
                "storey": wo.storey, "normal": _v(face.normal), "d": _r(face.d),
                "orientation": orientation(face.normal),
                "start": _v(face.point_at(s0)), "end": _v(face.point_at(s1)),
                "z_min": _r(face.z_range[0]), "z_max": _r(face.z_range[1]),
                "rooms": s_rooms.get(sid, [])})
            assert (face.point_at(s1) - face.point_at(s0)) @ t[:2] > 0.0
        walls.append({
            "id": wi, "ifc_id": wo.entity.id(), "guid": _guid(wo.entity),
            "name": wo.entity.Name or "", "kind": wo.kind, "ifc_class": wo.entity.is_a(),
            "storey": wo.storey, "surfaces": list(wo.surfaces),
            "thickness": _r(p.thickness), "start": _v(p.start), "center": _v(p.center),
            "length": _r(p.length), "height": _r(p.height), "external": bool(wo.external)})
    rooms = []
    for ri, r in enumerate(result.rooms):
        c = centroid(r.polygon)
        sids = sorted(r.surfaces)
        rooms.append({
            "id": ri, "ifc_id": r.ifc_id, "guid": _guid(r.entity), "name": r.entity.Name or "",
            "long_name": getattr(r.entity, "LongName", None) or "", "storey": r.storey,
            "polygon": [_v(p) for p in r.polygon], "z_min": _r(r.z_min), "z_max": _r(r.z_max),
            "floor_z": _r(r.floor_z), "floor_source": r.floor_source,
            "center": _v([c[0], c[1], 0.5 * (r.z_min + r.z_max)]), "area": _r(r.area),
            "surfaces": sids, "walls": sorted({surfaces[s]["wall"] for s in sids}),
            "doorways": sorted(r.doorways)})
    doorways = [{"id": di, "ifc_id": _id(d.entity), "guid": _guid(d.entity),
                 "name": (getattr(d.entity, "Name", None) or "") if d.entity is not None else "",
                 "storey": d.storey, "wall": d.wall,
                 "position": _v(d.position), "width": _r(d.width), "height": _r(d.height),
                 "rooms": list(d.rooms), "kind": d.kind} for di, d in enumerate(result.doorways)]
    return {
        "format": "is_graphs.agraph", "version": 1,
        "source": {"file": os.path.basename(m.path), "sha256": m.sha256, "schema": m.schema,
                   "application": m.application, "length_unit_m": _r(m.length_unit_m),
                   "converter_version": CONVERTER_VERSION},
        "building": m.building_name, "mesh": mesh_name,
        "storeys": storeys, "wall_surfaces": surfaces, "walls": walls, "rooms": rooms,
        "doorways": doorways, "warnings": list(result.warnings),
        "report": report(result, storeys, surfaces, walls, rooms, doorways)}


KINDS = ("door", "opening", "virtual")


def report(result, storeys, surfaces, walls, rooms, doorways):
    """Per storey: what was kept (counts) and what was dropped, by IFC class and reason."""
    out = []
    floors = per_storey(result.rooms)
    for s in storeys:
        k = s["id"]

        def count(items):
            return sum(1 for e in items if e["storey"] == k)
        kinds = {kind: sum(1 for d in doorways if d["storey"] == k and d["kind"] == kind)
                 for kind in KINDS}
        dropped = sorted((result.dropped.get(k) or {}).items())
        real = [w for w in walls if w["kind"] != "flush_element"]
        fl = [w for w in walls if w["kind"] == "flush_element" and w["storey"] == k]
        out.append({
            "storey": k, "name": s["name"],
            "kept": {"walls": len({w["ifc_id"] for w in real if w["storey"] == k}),
                     "wall_pieces": count(real), "wall_surfaces": count(surfaces),
                     "flush_elements": len({w["ifc_id"] for w in fl}),
                     "flush_surfaces": sum(1 for w in fl for sid in w["surfaces"]
                                           if surfaces[sid]["rooms"]),
                     "rooms": count(rooms), "doorways": kinds,
                     "floors_from_spaces": result.made_floors.per_storey.get(k, 0)},
            "dropped": [{"ifc_class": cls, "reason": why, "count": n}
                        for (cls, why), n in dropped],
            "room_floors": [{"room": ri, "name": name, "floor_z": _r(z), "source": src}
                            for ri, name, z, src in floors.get(k, [])]})
    return out


def dumps(graph):
    """JSON text: top-level keys on their own lines, one array element per line."""
    def one(x):
        return json.dumps(x, ensure_ascii=False, separators=(", ", ": "))
    parts = []
    for key, value in graph.items():
        if isinstance(value, list):
            inner = ",\n".join("    " + one(e) for e in value)
            parts.append(f'  {one(key)}: [\n{inner}\n  ]' if value else f"  {one(key)}: []")
        else:
            parts.append(f"  {one(key)}: {one(value)}")
    return "{\n" + ",\n".join(parts) + "\n}\n"


def write(result, out_prefix):
    """Writes `<out_prefix>.obj` then `<out_prefix>.agraph.json` (each atomically); returns the
    absolute path of the JSON."""
    out_prefix = os.path.abspath(out_prefix)
    directory = os.path.dirname(out_prefix)
    os.makedirs(directory, exist_ok=True)
    obj_path = out_prefix + ".obj"
    json_path = out_prefix + ".agraph.json"
    mesh_name = os.path.basename(obj_path)
    graph = build(result, mesh_name)
    tmp_obj, tmp_json = obj_path + ".part", json_path + ".part"
    mesh.write_obj(tmp_obj, result.shapes,
                   header=f"from {graph['source']['file']} sha256 {graph['source']['sha256']}",
                   extra=result.made_floors.shapes)
    os.replace(tmp_obj, obj_path)
    with open(tmp_json, "w", encoding="utf-8", newline="\n") as fh:
        fh.write(dumps(graph))
    os.replace(tmp_json, json_path)
    return json_path


def summary_lines(graph):
    """One human line per storey: counts of wall-surfaces, walls, rooms, doorways."""
    lines = [f"{graph['source']['file']}: {graph['source']['schema']}, "
             f"{graph['source']['application'] or 'unknown application'}, "
             f"unit {graph['source']['length_unit_m']} m, {len(graph['warnings'])} warning(s)"]
    for s in graph["storeys"]:
        def count(key):
            return sum(1 for e in graph[key] if e["storey"] == s["id"])
        lines.append(f"  storey {s['id']} '{s['name']}' z={s['elevation']:.3f} m: "
                     f"{count('wall_surfaces')} wall-surfaces, {count('walls')} walls, "
                     f"{count('rooms')} rooms, {count('doorways')} doorways")
        rep = next((r for r in graph.get("report", []) if r["storey"] == s["id"]), None)
        if rep is None:
            continue
        kinds = rep["kept"]["doorways"]
        if kinds.get("opening") or kinds.get("virtual"):
            lines.append("    doorways: " + ", ".join(f"{kinds.get(k, 0)} {k}" for k in KINDS))
        if rep["kept"].get("flush_elements"):
            lines.append(f"    flush elements: {rep['kept']['flush_elements']} (columns and the "
                         f"like on a room outline): {rep['kept']['flush_surfaces']} "
                         "wall-surface(s) bounding rooms")
        if rep["kept"].get("floors_from_spaces"):
            lines.append(f"    floors from spaces: {rep['kept']['floors_from_spaces']} (no slab "
                         "under them: their footprints added to the mesh as floors)")
        for d in rep["dropped"]:
            lines.append(f"    dropped: {d['count']} {d['ifc_class']}: {d['reason']}")
        lines += _floor_lines(rep, s["elevation"])
    return lines


def _floor_lines(rep, elevation):
    """'room floors: 3 slab, 1 space', and the rooms whose floor is off the storey's elevation
    by more than OFF_LINE (split levels, steps, a storey level at the raw slab)."""
    floors = rep.get("room_floors") or []
    if not floors:
        return []
    by_src = {}
    for f in floors:
        by_src[f["source"]] = by_src.get(f["source"], 0) + 1
    out = ["    room floors: " + ", ".join(f"{n} {src}" for src, n in sorted(by_src.items()))]
    off = [f for f in floors if abs(f["floor_z"] - elevation) > OFF_LINE]
    if off:
        out.append(f"    off the storey's elevation by more than {OFF_LINE} m: " + ", ".join(
            f"'{f['name']}' {f['floor_z']:.3f} m ({f['floor_z'] - elevation:+.2f})" for f in off))
    return out


OFF_LINE = 0.1
