"""Room footprints from IfcSpace triangles, and the 2D polygon helpers the converter uses."""
from collections import defaultdict
from dataclasses import dataclass, field

import numpy as np

DOWN_NZ = -0.9          # a triangle facing down
FLOOR_TOL = 0.02        # m: triangles of the footprint lie this close to the lowest one
WELD = 1e-4             # m: vertices closer than this are one
COLLINEAR_TOL = 1e-3    # m: a vertex this close to the line of its neighbours is dropped


@dataclass
class Room:
    entity: object          # the IfcSpace
    storey: int             # index into the storeys
    polygon: np.ndarray     # (K, 2) counter-clockwise
    z_min: float
    z_max: float
    surfaces: set = field(default_factory=set)
    doorways: set = field(default_factory=set)
    floor_z: float = None   # the floor walked on, and where it came from (room_floors.py)
    floor_source: str = ""

    @property
    def ifc_id(self):
        return self.entity.id()

    @property
    def area(self):
        return signed_area(self.polygon)

    def contains(self, p, z):
        return self.z_min - 0.5 <= z <= self.z_max and point_in_polygon(p, self.polygon)


def signed_area(poly):
    x, y = poly[:, 0], poly[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def centroid(poly):
    x, y = poly[:, 0], poly[:, 1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    cross = x * yn - xn * y
    a = 0.5 * cross.sum()
    return np.array([((x + xn) * cross).sum() / (6 * a), ((y + yn) * cross).sum() / (6 * a)])


def point_in_polygon(p, poly):
    """Even-odd rule; points on the boundary may go either way."""
    x, y = poly[:, 0], poly[:, 1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    crosses = (y > p[1]) != (yn > p[1])
    with np.errstate(divide="ignore", invalid="ignore"):
        xi = x + (p[1] - y) * (xn - x) / (yn - y)
    return bool(np.count_nonzero(crosses & (p[0] < xi)) % 2)


def simplify(poly):
    """Drops repeated and collinear vertices (repeatedly, until none is left)."""
    pts = [p for p in poly]
    changed = True
    while changed and len(pts) >= 3:
        changed = False
        for i in range(len(pts)):
            a, b, c = pts[i - 1], pts[i], pts[(i + 1) % len(pts)]
            ac = c - a
            length = np.linalg.norm(ac)
            if np.linalg.norm(b - a) < WELD:
                dist = 0.0
            elif length < WELD:
                dist = np.linalg.norm(b - a)
            else:
                dist = abs(ac[0] * (b - a)[1] - ac[1] * (b - a)[0]) / length
            if dist < COLLINEAR_TOL:
                del pts[i]
                changed = True
                break
    return np.array(pts)


def _loops(edges):
    """Chains directed boundary edges (start key, end key) into closed loops of keys."""
    out = defaultdict(list)
    for a, b in edges:
        out[a].append(b)
    loops = []
    for start in sorted(out):
        while out[start]:
            loop = [start]
            cur = out[start].pop()
            steps = 0
            while cur != start and out.get(cur) and steps < 100000:
                loop.append(cur)
                cur = out[cur].pop()
                steps += 1
            if cur == start and len(loop) >= 3:
                loops.append(loop)
    return loops


def footprint(shape):
    """(polygon (K,2) CCW simplified, z_min, z_max) of a space, or (None, why, None)."""
    if len(shape.faces) == 0:
        return None, "no geometry", None
    normals, areas, _ = shape.triangle_normals_areas()
    z_min, z_max = float(shape.verts[:, 2].min()), float(shape.verts[:, 2].max())
    tri_z = shape.verts[shape.faces][:, :, 2]
    down = (normals[:, 2] < DOWN_NZ) & (areas > 1e-10)
    if not down.any():
        return None, "no downward-facing (floor) faces", None
    floor_z = tri_z[down].max(axis=1).min()
    sel = down & (tri_z.max(axis=1) <= floor_z + FLOOR_TOL)
    keys = {}
    coords = []

    def key(v):
        k = (int(round(v[0] / WELD)), int(round(v[1] / WELD)))
        if k not in keys:
            keys[k] = len(coords)
            coords.append(v[:2])
        return keys[k]

    count = defaultdict(int)
    directed = []
    for tri in shape.faces[sel]:
        ks = [key(shape.verts[i]) for i in tri]
        for a, b in ((ks[0], ks[1]), (ks[1], ks[2]), (ks[2], ks[0])):
            if a != b:
                count[(min(a, b), max(a, b))] += 1
                directed.append((a, b))
    boundary = [(a, b) for a, b in directed if count[(min(a, b), max(a, b))] == 1]
    loops = _loops(boundary)
    if not loops:
        return None, "its floor faces do not form a closed outline", None
    coords = np.array(coords)
    polys = [coords[loop] for loop in loops]
    best = max(polys, key=lambda p: abs(signed_area(p)))
    if signed_area(best) < 0:
        best = best[::-1]
    best = simplify(best)
    if len(best) < 3 or signed_area(best) < 0.01:
        return None, "its footprint is degenerate (area below 0.01 m^2)", None
    # Start at the lowest-left vertex so the output does not depend on triangle order.
    first = min(range(len(best)), key=lambda i: (round(best[i][1], 6), round(best[i][0], 6)))
    best = np.roll(best, -first, axis=0)
    return best, z_min, z_max
