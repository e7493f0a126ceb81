"""Triangulating every element with IfcOpenShell, and writing the building mesh (OBJ)."""
import os
from dataclasses import dataclass

import numpy as np
import ifcopenshell
import ifcopenshell.geom

# Not written to the mesh, with their subtypes: spaces and other spatial elements are air (IFC4's
# IfcExternalSpatialElement is a box around the whole site, IfcSpatialZone a volume), openings
# are already cut out of their walls (IFC4's IfcOpeningStandardCase too), virtual elements are
# no matter. Seen in KIT-EDC_with_SB.ifc: both IFC4 subtypes were in the mesh, the site box
# around the building and every door's opening solid across its doorway.
NOT_IN_MESH = ("IfcSpatialElement", "IfcSpatialStructureElement", "IfcSpace",
               "IfcOpeningElement", "IfcVirtualElement")


def in_mesh(entity):
    """Whether an element's body belongs in the building mesh (not air, not a hole)."""
    for ifc_class in NOT_IN_MESH:
        try:
            if entity.is_a(ifc_class):
                return False
        except Exception:  # a class the file's schema does not have (IFC2X3: IfcSpatialElement)
            continue
    return True


@dataclass
class Shape:
    """One element's triangles in world coordinates (metres, bim frame)."""
    id: int
    ifc_class: str
    verts: np.ndarray   # (N, 3) float64
    faces: np.ndarray   # (M, 3) int64
    solid: bool = True  # written to the mesh (in_mesh: not a space, opening or virtual element)

    def triangle_normals_areas(self):
        """(unit normals (M,3), areas (M,), centroids (M,3)) of the triangles."""
        a, b, c = (self.verts[self.faces[:, k]] for k in range(3))
        cross = np.cross(b - a, c - a)
        norm = np.linalg.norm(cross, axis=1)
        ok = norm > 0
        normals = np.zeros_like(cross)
        normals[ok] = cross[ok] / norm[ok, None]
        return normals, 0.5 * norm, (a + b + c) / 3.0


def _silence_ifcopenshell_log():
    """IfcOpenShell logs geometry failures itself; we report them our own way."""
    try:
        ifcopenshell.ifcopenshell_wrapper.set_log_format_json()
        ifcopenshell.ifcopenshell_wrapper.turn_off_detailed_logging()
    except Exception:
        pass


def triangulate(model, force_metres=False):
    """{step id: Shape} for every product with a 3D body, in world coordinates, metres."""
    settings = ifcopenshell.geom.settings()
    settings.set("use-world-coords", True)
    settings.set("weld-vertices", True)
    if force_metres:
        settings.set("length-unit", 1.0)
    _silence_ifcopenshell_log()
    threads = max(1, min(8, os.cpu_count() or 1))
    shapes = {}
    it = ifcopenshell.geom.iterator(settings, model.file, threads)
    try:
        ok = it.initialize()
    except Exception:
        ok = False
    if not ok:
        return shapes
    while True:
        shape = it.get()
        geom = shape.geometry
        faces = np.asarray(geom.faces, dtype=np.int64).reshape(-1, 3)
        if len(faces):
            verts = np.asarray(geom.verts, dtype=np.float64).reshape(-1, 3)
            entity = model.file.by_id(shape.id)
            shapes[shape.id] = Shape(shape.id, entity.is_a(), verts, faces, in_mesh(entity))
        if not it.next():
            break
    return shapes


def _fmt(x):
    s = f"{x:.6f}"
    return "0.000000" if s == "-0.000000" else s


def write_obj(path, shapes, header="", extra=()):
    """Writes every shape but spaces and openings, sorted by STEP id, one `o` per element; then
    the `extra` shapes (floors made from spaces) in their order, as `o <ifc_class>#<id>`."""
    lines = ["# is_graphs building mesh: metres, bim frame, z up; one object per IFC element"]
    if header:
        lines.append(f"# {header}")
    base = 1
    todo = [shapes[sid] for sid in sorted(shapes) if shapes[sid].solid]
    for shape in todo + list(extra):
        lines.append(f"o {shape.ifc_class}#{shape.id}")
        v = np.round(shape.verts, 6) + 0.0
        lines.extend(f"v {_fmt(x)} {_fmt(y)} {_fmt(z)}" for x, y, z in v.tolist())
        f = shape.faces + base
        lines.extend(f"f {a} {b} {c}" for a, b, c in f.tolist())
        base += len(v)
    with open(path, "w", encoding="utf-8", newline="\n") as fh:
        fh.write("\n".join(lines) + "\n")
