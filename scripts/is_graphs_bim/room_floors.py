"""Each room's floor height: the z the robot stands on in it (docs/agraph_format.md, rooms).

A storey's elevation is not the floor of every room on it: split-level storeys have rooms a few
steps above or below the rest, and exports put the storey's level at the raw slab, a finish or
elsewhere. Per room, in this order (`floor_source`):

- "slab" / "covering": the top of the IfcSlab (any type) or IfcCovering FLOORING (or a part of
  one) under the room: their upward-facing triangles within FLOOR_BAND of the reference height
  (the space's bottom when usable, else the storey's elevation), grouped into levels LEVEL_TOL
  apart; a level counts when it covers at least MIN_SHARE of the footprint; of the levels covering
  nearly the most (within NEAR_BEST of the best share) the highest, the surface walked on (a
  covering on its slab);
- "space": the space's bottom, when usable (finite, at most 1 m below its storey's elevation,
  below the next storey's);
- "mesh": the same search over the upward faces of the other building elements in the mesh
  (proxies, stairs, ramps, roofs...; not furniture, doors, windows or equipment) between 1 m
  below the storey's elevation and the next storey's;
- "storey": the storey's elevation, with a warning naming the room.

A floor more than OFF_STOREY from its storey's elevation is kept, with a warning naming both.
"""
from collections import defaultdict

import numpy as np
import shapely

from . import ifc_model
from .floors import _floor_elements, _plan_polygon, upward_triangles
from .mesh import in_mesh

FLOOR_BAND = 0.5     # m: a floor element's top this far below or above the reference floors it
LEVEL_TOL = 0.005    # m: upward faces this close in height are one level
MIN_SHARE = 0.25     # a level must cover this share of the footprint
NEAR_BEST = 0.1      # levels covering within this share of the best one: the highest wins
OFF_STOREY = 1.5     # m: a floor further from its storey's elevation is warned about
NOT_FLOORS = ("IfcFurnishingElement", "IfcDoor", "IfcWindow", "IfcDistributionElement",
              "IfcWall", "IfcCurtainWall", "IfcColumn", "IfcBeam", "IfcMember")


class _Tops:
    """Upward-facing triangles (plan polygon, z, source) of some shapes, in an STRtree."""

    def __init__(self, shapes, ids, source_of):
        polys, zs, srcs = [], [], []
        for sid in ids:
            sh = shapes.get(sid)
            if sh is None:
                continue
            for poly, z in upward_triangles(sh):
                polys.append(poly)
                zs.append(z)
                srcs.append(source_of(sid))
        self.polys = np.array(polys, dtype=object)
        self.z = np.array(zs)
        self.src = srcs
        self.tree = shapely.STRtree(self.polys) if polys else None

    def floor(self, footprint, lo, hi):
        """(z, source) of the floor level under `footprint` between lo and hi, or None."""
        if self.tree is None or footprint.area <= 0.0:
            return None
        idx = self.tree.query(footprint)
        idx = idx[(self.z[idx] >= lo) & (self.z[idx] <= hi)]
        if not len(idx):
            return None
        idx = idx[np.argsort(self.z[idx], kind="stable")]
        levels, cur = [], [idx[0]]
        for i in idx[1:]:
            if self.z[i] - self.z[cur[-1]] <= LEVEL_TOL:
                cur.append(i)
            else:
                levels.append(cur)
                cur = [i]
        levels.append(cur)
        found = []
        for level in levels:
            share = footprint.intersection(shapely.union_all(self.polys[level])).area
            share /= footprint.area
            if share >= MIN_SHARE:
                zs = self.z[level]
                top = max(level, key=lambda i: self.z[i])
                found.append((share, float(np.median(zs)), self.src[top]))
        if not found:
            return None
        best = max(s for s, _, _ in found)
        share, z, src = max((f for f in found if f[0] >= best - NEAR_BEST), key=lambda f: f[1])
        return z, src


def _usable_bottom(room, elev, nxt):
    z = room.z_min
    return bool(np.isfinite(z) and elev - 1.0 <= z < nxt)


def _mesh_ids(model, shapes, skip):
    out = []
    for sid, sh in shapes.items():
        if sid in skip:
            continue
        e = model.file.by_id(sid)
        if in_mesh(e) and not any(_is_a(e, c) for c in NOT_FLOORS):
            out.append(sid)
    return sorted(out)


def _is_a(entity, cls):
    try:
        return entity.is_a(cls)
    except Exception:   # a class the file's schema does not have
        return False


def _source_of(model):
    def source(sid):
        e = model.file.by_id(sid)
        return "covering" if e.is_a("IfcCovering") else "slab"
    return source


def assign(model, shapes, rooms, storeys, diag):
    """Sets room.floor_z and room.floor_source for every room; warns as the module doc says."""
    floor_ids = _floor_elements(model.file)
    slabs = _Tops(shapes, floor_ids, _source_of(model))
    others = None
    for r in rooms:
        elev = storeys[r.storey][1] if storeys else 0.0
        nxt = storeys[r.storey + 1][1] if r.storey + 1 < len(storeys) else np.inf
        usable = _usable_bottom(r, elev, nxt)
        ref = r.z_min if usable else elev
        plan = _plan_polygon(r.polygon)
        found = slabs.floor(plan, ref - FLOOR_BAND, ref + FLOOR_BAND)
        if found is None and usable:
            found = (float(r.z_min), "space")
        if found is None:
            if others is None:
                others = _Tops(shapes, _mesh_ids(model, shapes, set(floor_ids)),
                               lambda _sid: "mesh")
            top = nxt - 0.1 if np.isfinite(nxt) else elev + 3.0
            found = others.floor(plan, elev - 1.0, top)
        name = f"'{r.entity.Name or ''}'"
        st = storeys[r.storey][0] if storeys else None
        st_name = f"'{(st.Name or '') if st is not None else ''}'"
        if found is None:
            diag.warn(f"room {name}: no floor found under it (no slab or floor covering, no "
                      f"usable space bottom, no upward face in the mesh): its floor is taken at "
                      f"the elevation of its storey {st_name} (z = {elev:.3f} m)", r.entity)
            found = (float(elev), "storey")
        r.floor_z, r.floor_source = found
        if abs(r.floor_z - elev) > OFF_STOREY:
            diag.warn(f"room {name}: its floor (z = {r.floor_z:.3f} m, from the {r.floor_source})"
                      f" is {abs(r.floor_z - elev):.2f} m from the elevation of its storey "
                      f"{st_name} ({ifc_model.entity_label(st) or 'no entity'}, z = {elev:.3f} m)"
                      ": kept", r.entity)


def per_storey(rooms):
    """{storey: [(room index, name, floor_z, source)]} in room order, for the report."""
    out = defaultdict(list)
    for ri, r in enumerate(rooms):
        out[r.storey].append((ri, r.entity.Name or "", r.floor_z, r.floor_source))
    return out
