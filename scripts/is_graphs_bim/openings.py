"""Doorways without doors: doorless wall openings and virtual separations between spaces.

Doorless opening (kind "opening"): an IfcOpeningElement that voids a converted wall
(IfcRelVoidsElement), that no IfcRelFillsElement fills, and that is a passage, not a window:
- it goes through the wall: its extent across the wall covers the wall's thickness (2 cm slack)
  and it overlaps the wall along its length by at least MIN_WIDTH;
- its sill (lowest point) is at most MAX_SILL above the floor under it: the wall's bottom (the
  storey's floor) or, where it is higher, the floor of a room beside the opening that lies at or
  below the sill (on a split-level storey the wall stands on the lower floor, and an opening
  onto the upper room starts at the upper floor);
- its height inside the wall is at least MIN_HEIGHT.
The rooms it joins are found from the geometry (the rooms beyond each face of the wall), as
for doors without space links.

Virtual separation (kind "virtual"): two spaces of one storey whose footprints share a stretch
of boundary (edges on one line, within SHARED_TOL, the spaces on opposite sides) of at least
MIN_WIDTH that no wall stands on, and that the file marks as open: an IfcVirtualElement bounds
both (IfcRelSpaceBoundary), or one of them has a VIRTUAL space boundary, or the file has no
space boundaries at all (then the shared wall-free stretch is all there is to go by).
"""
from dataclasses import dataclass

import numpy as np

MIN_WIDTH = 0.5         # m: narrower passages are not doorways
MIN_HEIGHT = 1.8        # m: lower openings are windows, hatches or niches
MAX_SILL = 0.3          # m: above the floor under it; higher sills are windows
ACROSS_SLACK = 0.02     # m
SHARED_TOL = 0.05       # m: two space edges this close are one boundary line
PARALLEL_COS = np.cos(np.radians(5.0))
SAMPLE = 0.05           # m: step along a shared stretch when looking for walls on it
WALL_MARGIN = 0.02      # m


@dataclass
class OpeningFit:
    ok: bool
    why: str                # why it is not a doorway ("" when ok)
    width: float = 0.0
    height: float = 0.0
    sill: float = 0.0


def fit_opening(points, piece, floors=()):
    """Whether an opening (its triangle vertices, metres) is a door-like passage through a wall
    piece (walls.WallPiece); floors: the floor heights of the rooms beside it."""
    a = piece.faces[0]
    n, t = a.normal, a.tangent
    mid = a.d - 0.5 * piece.thickness
    s_n = points @ n - mid
    half = 0.5 * piece.thickness
    if s_n.min() > -half + ACROSS_SLACK or s_n.max() < half - ACROSS_SLACK:
        return OpeningFit(False, "does not go through its host wall (across the wall it reaches "
                          f"from {s_n.min():+.2f} to {s_n.max():+.2f} m of the mid-plane, the "
                          f"faces are at -/+{half:.2f} m)")
    s_t = points @ t
    w0, w1 = piece.start @ t - 0.5 * piece.length, piece.start @ t + 0.5 * piece.length
    width = min(s_t.max(), w1) - max(s_t.min(), w0)
    z0, z1 = float(points[:, 2].min()), float(points[:, 2].max())
    height = min(z1, piece.z_max) - max(z0, piece.z_min)
    base = max([piece.z_min] + [f for f in floors if f is not None and f <= z0 + ACROSS_SLACK])
    sill = z0 - base
    if width < MIN_WIDTH:
        return OpeningFit(False, f"overlaps its host wall along {max(width, 0.0):.2f} m only "
                          f"(< {MIN_WIDTH} m): not a passage", width, height, sill)
    if sill > MAX_SILL or height < MIN_HEIGHT:
        under = "the wall's bottom" if base == piece.z_min else "the floor beside it"
        return OpeningFit(False, f"window-like (sill {sill:.2f} m above {under}, "
                          f"height {height:.2f} m; a doorway needs a sill <= {MAX_SILL} m and a "
                          f"height >= {MIN_HEIGHT} m)", width, height, sill)
    return OpeningFit(True, "", float(width), float(height), float(sill))


def _footprints_2d(shape):
    """The 2D triangles (K, 3, 2) of a shape's horizontal faces: its plan footprint."""
    normals, areas, _ = shape.triangle_normals_areas()
    keep = (np.abs(normals[:, 2]) > 0.9) & (areas > 1e-8)
    return shape.verts[shape.faces[keep]][:, :, :2]


class WallFootprints:
    """Point queries against the plan footprints of walls (their horizontal faces)."""

    def __init__(self, shapes):
        tris = [_footprints_2d(s) for s in shapes if len(s.faces)]
        tris = [t for t in tris if len(t)]
        self.tris = np.concatenate(tris) if tris else np.zeros((0, 3, 2))
        if len(self.tris):
            self.lo = self.tris.min(axis=1) - WALL_MARGIN
            self.hi = self.tris.max(axis=1) + WALL_MARGIN

    def blocked(self, pts):
        """(N,) bool: which 2D points lie on a wall (within WALL_MARGIN)."""
        out = np.zeros(len(pts), dtype=bool)
        if not len(self.tris):
            return out
        for i, p in enumerate(pts):
            cand = np.nonzero(np.all((self.lo <= p) & (p <= self.hi), axis=1))[0]
            for k in cand:
                if _in_triangle(p, self.tris[k], WALL_MARGIN):
                    out[i] = True
                    break
        return out


def _in_triangle(p, tri, margin):
    a, b, c = tri
    area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    if abs(area) < 1e-12:
        return False
    sign = 1.0 if area > 0 else -1.0
    for u, v in ((a, b), (b, c), (c, a)):
        e = v - u
        length = float(np.hypot(e[0], e[1]))
        if length < 1e-12:
            continue
        cross = sign * (e[0] * (p[1] - u[1]) - e[1] * (p[0] - u[0])) / length
        if cross < -margin:
            return False
    return True


def shared_stretches(poly_a, poly_b):
    """[(p, q)] 2D segments along which the boundaries of two CCW polygons run together with the
    polygons on opposite sides."""
    out = []
    for i in range(len(poly_a)):
        p, q = poly_a[i], poly_a[(i + 1) % len(poly_a)]
        e = q - p
        length = float(np.hypot(*e))
        if length < 1e-6:
            continue
        u = e / length
        nrm = np.array([-u[1], u[0]])
        for j in range(len(poly_b)):
            r, s = poly_b[j], poly_b[(j + 1) % len(poly_b)]
            f = s - r
            lf = float(np.hypot(*f))
            if lf < 1e-6 or (f @ u) / lf > -PARALLEL_COS:   # opposite directions only
                continue
            if abs((r - p) @ nrm) > SHARED_TOL or abs((s - p) @ nrm) > SHARED_TOL:
                continue
            lo = max(0.0, min((r - p) @ u, (s - p) @ u))
            hi = min(length, max((r - p) @ u, (s - p) @ u))
            if hi - lo > 1e-3:
                out.append((p + lo * u, p + hi * u))
    return out


def open_runs(seg, walls):
    """The longest part (p, q) of a segment that no wall stands on, or None."""
    p, q = seg
    length = float(np.hypot(*(q - p)))
    k = max(2, int(np.ceil(length / SAMPLE)) + 1)
    ts = np.linspace(0.0, 1.0, k)
    pts = p[None, :] + ts[:, None] * (q - p)[None, :]
    free = ~walls.blocked(pts)
    best, start = None, None
    for i, ok in enumerate(list(free) + [False]):
        if ok and start is None:
            start = i
        elif not ok and start is not None:
            run = (ts[start], ts[i - 1])
            if best is None or run[1] - run[0] > best[1] - best[0]:
                best = run
            start = None
    if best is None:
        return None
    return p + best[0] * (q - p), p + best[1] * (q - p)
