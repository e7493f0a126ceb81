"""Floors made from space footprints where the file has no floor slab under a space (issue 24).

Some exports have no IfcSlab on a storey (or under some of its rooms). The mesh then has no
floor there: the simulated LiDAR sees no ground and the S-Graph finds no floor plane. For every
converted room (an IfcSpace with a footprint) that no floor element covers, the converter adds
its footprint, triangulated, at the space's bottom to the mesh as `o FloorFromSpace#<space id>`.

Coverage rule (docs/agraph_format.md, Mesh): the floor elements are every IfcSlab (any
PredefinedType, whichever storey contains it: exporters put the slab between two storeys on
either) and every IfcCovering with PredefinedType FLOORING, with their aggregated parts. Their
upward-facing triangles whose z lies within [bottom - COVER_BELOW, bottom + COVER_ABOVE] of a
space's bottom, and the holes cut in them (openings voiding them, reaching that band), projected
to plan and merged, must overlap more than COVERED_FRACTION of the space's footprint area;
otherwise the space is uncovered and gets a floor over its whole footprint.
"""
from collections import defaultdict
from dataclasses import dataclass, field

import numpy as np
import shapely
from shapely.geometry import Polygon

from .mesh import Shape

COVER_BELOW = 0.5       # m: a slab top this far below the bottom (screed, finishes) floors it
COVER_ABOVE = 0.5       # m: ... and this far above it (a slab modelled on top of its level)
COVERED_FRACTION = 0.5  # a space is covered when more than this share of its footprint is
UP_NZ = 0.9             # a triangle facing up
CLASS = "FloorFromSpace"


def upward_triangles(shape):
    """[(plan Polygon, z)] of a shape's upward-facing triangles (z: the triangle's centroid's)."""
    normals, areas, centroids = shape.triangle_normals_areas()
    up = (normals[:, 2] > UP_NZ) & (areas > 1e-8)
    return [(Polygon(shape.verts[tri, :2]), float(z))
            for tri, z in zip(shape.faces[up], centroids[up, 2])]


@dataclass
class Floors:
    shapes: list = field(default_factory=list)            # [Shape] (id: the IfcSpace's step id)
    per_storey: dict = field(default_factory=dict)        # {storey index: spaces given a floor}


def _floor_elements(f):
    """IfcSlab (all types) and IfcCovering FLOORING, with their aggregated parts."""
    out = list(f.by_type("IfcSlab"))
    out += [c for c in f.by_type("IfcCovering")
            if getattr(c, "PredefinedType", None) == "FLOORING"]
    seen, todo = set(), list(out)
    while todo:
        e = todo.pop()
        if e.id() in seen:
            continue
        seen.add(e.id())
        for rel in getattr(e, "IsDecomposedBy", None) or ():
            todo.extend(rel.RelatedObjects or ())
    return sorted(seen)


class _UpFaces:
    """What floors a space, in plan, with z ranges, for quick lookup: the upward-facing triangles
    of the floor elements, and the holes cut in them (IfcOpeningElement voiding one: a stair
    hole or a shaft is part of the floor's design, not a missing floor)."""

    def __init__(self, model, shapes, ids):
        polys, lo, hi = [], [], []
        for sid in ids:
            sh = shapes.get(sid)
            if sh is None:
                continue
            for poly, z in upward_triangles(sh):
                polys.append(poly)
                lo.append(z)
                hi.append(z)
            for rel in getattr(model.file.by_id(sid), "HasOpenings", None) or ():
                op = shapes.get(rel.RelatedOpeningElement.id())
                if op is None:
                    continue
                normals, areas, _ = op.triangle_normals_areas()
                flat = (np.abs(normals[:, 2]) > 0.1) & (areas > 1e-8)
                if flat.any():
                    polys.append(shapely.union_all([Polygon(op.verts[t, :2])
                                                    for t in op.faces[flat]]))
                    lo.append(float(op.verts[:, 2].min()))
                    hi.append(float(op.verts[:, 2].max()))
        self.polys = np.array(polys, dtype=object)
        self.lo, self.hi = np.array(lo), np.array(hi)
        self.tree = shapely.STRtree(self.polys) if polys else None

    def covered_share(self, footprint, z):
        """The share of `footprint` (a shapely polygon) that what floors a space covers between
        z - COVER_BELOW and z + COVER_ABOVE."""
        if self.tree is None or footprint.area <= 0.0:
            return 0.0
        idx = self.tree.query(footprint)
        idx = idx[(self.hi[idx] >= z - COVER_BELOW) & (self.lo[idx] <= z + COVER_ABOVE)]
        if not len(idx):
            return 0.0
        under = shapely.union_all(self.polys[idx])
        return float(footprint.intersection(under).area / footprint.area)


def _plan_polygon(poly2d):
    p = Polygon(poly2d)
    return p if p.is_valid else shapely.make_valid(p)


def _ear_clip(ring):
    """Triangles [(a, b, c)] of a simple counter-clockwise ring [(x, y)] (not closed)."""
    pts, out = list(ring), []

    def cross(a, b, c):
        return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    while len(pts) > 3:
        n = len(pts)
        for i in range(n):
            a, b, c = pts[i - 1], pts[i], pts[(i + 1) % n]
            turn = cross(a, b, c)
            if abs(turn) <= 1e-12:      # b on the line a-c: drop it, no triangle
                break
            if turn < 0 or any(cross(a, b, p) >= 0 and cross(b, c, p) >= 0 and
                               cross(c, a, p) >= 0 for p in pts if p not in (a, b, c)):
                continue                # reflex, or another vertex in the triangle: no ear
            out.append((a, b, c))
            break
        else:
            return out                  # no ear left (numerically degenerate): what was found
        del pts[i]
    if len(pts) == 3 and abs(cross(*pts)) > 1e-12:
        out.append(tuple(pts))
    return out


def _constrained_triangles(plan):
    """Triangles (a geometry with .geoms) exactly covering `plan`: shapely's constrained Delaunay
    triangulation (shapely 2.1, Python 3.10 and newer), else (shapely 2.0, Python 3.9) ear
    clipping, holes first cut open by splitting the polygon across each of them."""
    if hasattr(shapely, "constrained_delaunay_triangles"):
        return shapely.constrained_delaunay_triangles(plan)
    from shapely.geometry import GeometryCollection, LineString
    from shapely.geometry.polygon import orient
    from shapely.ops import split
    todo, tris = [plan], []
    while todo:
        g = todo.pop()
        if hasattr(g, "geoms"):
            todo.extend(g.geoms)
        elif isinstance(g, Polygon) and g.area > 0:
            if g.interiors:
                x0, _, x1, _ = g.interiors[0].bounds
                _, y0, _, y1 = g.bounds
                todo.extend(split(g, LineString([(0.5 * (x0 + x1), y0 - 1.0),
                                                 (0.5 * (x0 + x1), y1 + 1.0)])).geoms)
            else:
                ring = list(orient(g, 1.0).exterior.coords)[:-1]
                tris += [Polygon(t) for t in _ear_clip(ring)]
    return GeometryCollection(tris)


def triangulate_footprint(poly2d, z, space_id):
    """The footprint (K, 2) as an upward-facing triangle mesh at height z (a Shape), or None."""
    plan = _plan_polygon(poly2d)
    tris = _constrained_triangles(plan) if plan.area > 0 else None
    keys, verts, faces = {}, [], []

    def vid(x, y):
        k = (round(x, 9), round(y, 9))
        if k not in keys:
            keys[k] = len(verts)
            verts.append((x, y, z))
        return keys[k]
    for g in getattr(tris, "geoms", ()):
        if not g.area > 1e-12:
            continue
        (ax, ay), (bx, by), (cx, cy) = list(g.exterior.coords)[:3]
        if (bx - ax) * (cy - ay) - (by - ay) * (cx - ax) < 0:     # make it counter-clockwise
            (bx, by), (cx, cy) = (cx, cy), (bx, by)
        faces.append((vid(ax, ay), vid(bx, by), vid(cx, cy)))
    if not faces:
        return None
    return Shape(space_id, CLASS, np.array(verts, dtype=np.float64),
                 np.array(faces, dtype=np.int64))


def _bottom(room, storeys):
    """The space's bottom, or its storey's elevation when the bottom is unusable (not finite, more
    than 1 m below the storey or at or above the next storey)."""
    elev = storeys[room.storey][1] if storeys else 0.0
    nxt = storeys[room.storey + 1][1] if room.storey + 1 < len(storeys) else np.inf
    z = room.z_min
    if np.isfinite(z) and elev - 1.0 <= z < nxt:
        return float(z), True
    return float(elev), False


def make_floors(model, shapes, rooms, storeys, sidx, diag):
    """Floors for the rooms no slab or floor covering covers, with the warnings (module doc)."""
    up = _UpFaces(model, shapes, _floor_elements(model.file))
    out = Floors()
    total = defaultdict(int)
    given = defaultdict(list)
    for r in sorted(rooms, key=lambda r: r.ifc_id):
        total[r.storey] += 1
        z, usable = _bottom(r, storeys)
        if up.covered_share(_plan_polygon(r.polygon), z) > COVERED_FRACTION:
            continue
        shape = triangulate_footprint(r.polygon, z, r.ifc_id)
        if shape is None:
            diag.warn("no slab under it and its footprint gives no triangles: no floor made "
                      "from it", r.entity)
            continue
        if not usable:
            diag.warn(f"no slab under it and its bottom (z = {r.z_min:.3f} m) is unusable: its "
                      f"floor is made at its storey's elevation (z = {z:.3f} m)", r.entity)
        out.shapes.append(shape)
        given[r.storey].append(r)
    converted = {r.ifc_id for r in rooms}
    no_footprint = defaultdict(list)
    for sp in sorted(model.file.by_type("IfcSpace"), key=lambda s: s.id()):
        if sp.id() not in converted:
            no_footprint[sidx.of(sp)].append(sp)
    for k in sorted(given):
        st = storeys[k][0] if storeys else None
        name = f" '{st.Name or ''}'" if st is not None else ""
        n = len(given[k])
        what = (f"storey{name} has no IfcSlab or IfcCovering FLOORING under {n} of its {total[k]} "
                f"space(s): floors made from their footprints added to the mesh (objects "
                f"{CLASS}#<space id>)")
        diag.warn(what, st)
        for sp in no_footprint.get(k, ()):
            diag.warn("no usable footprint, on a storey lacking floor slabs: no floor made from "
                      "it (the mesh may have no floor there)", sp)
        out.per_storey[k] = n
    out.shapes.sort(key=lambda s: s.id)
    return out
