"""Wall-surfaces from a wall's triangles, independent of how the IFC represents the wall.

The vertical triangles are grouped into planes without trusting their winding (surface models
are not oriented). Two parallel planes with an overlapping extent are a wall's two faces when the
material lies between them; each face's normal then points away from the other one, i.e. out of
the material. The largest plane is paired first, with its largest valid partner ("the two largest
opposed planes"): reveals and end caps are small. When the wall's Axis is a straight line only
planes along it qualify and the wall gives one pair; otherwise (L-shaped polyline walls, no axis)
the remaining planes may give more pairs, one per straight piece.
"""
from dataclasses import dataclass

import numpy as np
import ifcopenshell.util.placement as uplacement

VERTICAL_NZ = 0.05          # |n_z| below this: a vertical face
SAME_DIR_COS = np.cos(np.radians(3.0))
PARALLEL_COS = np.cos(np.radians(5.0))
ALONG_AXIS_SIN = np.sin(np.radians(5.0))
COPLANAR_TOL = 0.01         # m
MIN_THICKNESS = 0.01        # m
MAX_THICKNESS = 2.0         # m
MIN_FACE_AREA = 0.05        # m^2
MIN_PIECE_RATIO = 0.2       # a further piece's faces: at least this share of the first's
MAX_PIECES = 4              # more straight pieces than this: a curved wall, not a polyline


@dataclass
class Plane:
    normal: np.ndarray      # unit, horizontal (3,)
    d: float                # n . p = d
    area: float
    points: np.ndarray      # (K, 3) vertices of its triangles

    @property
    def tangent(self):
        return np.array([-self.normal[1], self.normal[0], 0.0])   # z x n

    def t_range(self, tangent=None):
        s = self.points @ (self.tangent if tangent is None else tangent)
        return float(s.min()), float(s.max())

    @property
    def z_range(self):
        return float(self.points[:, 2].min()), float(self.points[:, 2].max())

    def point_at(self, s):
        """The 2D point of the plane at tangent coordinate s."""
        return (self.d * self.normal + s * self.tangent)[:2]

    def flipped(self):
        return Plane(-self.normal, -self.d, self.area, self.points)


@dataclass
class WallPiece:
    faces: tuple            # (Plane, Plane), normals pointing out of the material
    thickness: float
    start: np.ndarray       # wall point w_s (3,)
    center: np.ndarray      # (3,)
    length: float
    height: float
    z_min: float
    z_max: float


def vertical_planes(shape):
    """Groups the vertical triangles into planes (normal sign arbitrary), largest area first;
    also returns the total vertical area."""
    normals, areas, centroids = shape.triangle_normals_areas()
    keep = (np.abs(normals[:, 2]) < VERTICAL_NZ) & (areas > 1e-8)
    idx = np.nonzero(keep)[0]
    idx = idx[np.argsort(-areas[idx], kind="stable")]
    clusters = []   # [normal_sum, d_rep, n_rep, [triangle ids]]
    for i in idx:
        n = normals[i].copy()
        n[2] = 0.0
        n /= np.linalg.norm(n)
        tri = shape.verts[shape.faces[i]]
        for c in clusters:
            dot = n @ c[2]
            if abs(dot) > SAME_DIR_COS and np.all(np.abs(tri @ c[2] - c[1]) < COPLANAR_TOL):
                c[0] += areas[i] * (n if dot > 0 else -n)
                c[3].append(i)
                break
        else:
            clusters.append([areas[i] * n, float(centroids[i] @ n), n, [i]])
    planes = []
    for nsum, _, _, tris in clusters:
        n = nsum / np.linalg.norm(nsum)
        a = areas[tris]
        d = float((centroids[tris] @ n) @ a / a.sum())
        planes.append(Plane(n, d, float(a.sum()), shape.verts[shape.faces[tris].ravel()]))
    planes.sort(key=lambda p: -p.area)
    return planes, float(areas[keep].sum())


def _overlap(a, b):
    return min(a[1], b[1]) - max(a[0], b[0])


def _as_pair(a, b):
    """(outer a, outer b, thickness, t overlap) of two parallel planes, or None when they cannot
    be the two faces of one piece of wall."""
    b_on_a = b if a.normal @ b.normal > 0 else b.flipped()
    gap = b_on_a.d - a.d
    if not (MIN_THICKNESS <= abs(gap) <= MAX_THICKNESS):
        return None
    if _overlap(a.z_range, b.z_range) <= 0.0:
        return None
    t_ov = _overlap(a.t_range(a.tangent), b.t_range(a.tangent))
    if t_ov < max(0.5 * abs(gap), 0.02):      # end caps, piers: thicker than long
        return None
    # Material between: the plane further along +n gets +n, the other one -n.
    if gap > 0:
        return b_on_a, a.flipped(), gap, t_ov
    return a, b_on_a.flipped(), -gap, t_ov


def _make_piece(a, b):
    t = a.tangent
    (a0, a1), (b0, b1) = a.t_range(t), b.t_range(t)
    s0, s1 = min(a0, b0), max(a1, b1)
    z0 = min(a.z_range[0], b.z_range[0])
    z1 = max(a.z_range[1], b.z_range[1])
    on_a = a.d * a.normal + 0.5 * (s0 + s1) * t
    thickness = float(b.d - b.normal @ on_a)      # distance from a's point to b's plane
    ws = on_a - 0.5 * thickness * a.normal
    ws[2] = z0
    q = [ws - (f.normal @ ws - f.d) * f.normal for f in (a, b)]
    return WallPiece((a, b), thickness, ws, 0.5 * (q[0] + q[1]), s1 - s0, z1 - z0, z0, z1)


def _inside_piece(point, piece, margin=0.02):
    a, b = piece.faces
    if a.normal @ point - a.d > margin or b.normal @ point - b.d > margin:
        return False
    s, s_mid = point @ a.tangent, piece.start @ a.tangent
    return abs(s - s_mid) <= 0.5 * piece.length + margin


def _holds_all(piece, verts, margin=0.02):
    """Whether every vertex lies inside a straight piece's box (2D, within margin)."""
    a, b = piece.faces
    s_mid = piece.start @ a.tangent
    return bool(np.all(verts @ a.normal - a.d <= margin)
                and np.all(verts @ b.normal - b.d <= margin)
                and np.all(np.abs(verts @ a.tangent - s_mid) <= 0.5 * piece.length + margin))


def wall_pieces(shape, axis_dir=None):
    """([WallPiece], problem): the straight pieces of a wall, or [] and why there are none.

    axis_dir: the wall's straight axis direction (3,) in world coordinates, if known."""
    if len(shape.faces) == 0:
        return [], "no geometry"
    planes, vertical_area = vertical_planes(shape)
    planes = [p for p in planes if p.area >= MIN_FACE_AREA]
    if axis_dir is not None:
        planes = [p for p in planes if abs(p.normal @ axis_dir) < ALONG_AXIS_SIN]
    if not planes:
        return [], "no vertical faces along it (zero length or height, or degenerate geometry)"
    used = [False] * len(planes)
    pieces = []
    for i, a in enumerate(planes):
        if used[i]:
            continue
        best = None
        for j, b in enumerate(planes):
            if j == i or used[j] or abs(a.normal @ b.normal) < PARALLEL_COS:
                continue
            pair = _as_pair(a, b)
            if pair is not None and (best is None or b.area > best[0] + 1e-9):
                best = (b.area, j, pair)
        if best is None:
            continue
        _, j, (fa, fb, _, _) = best
        if pieces and min(a.area, planes[j].area) < MIN_PIECE_RATIO * min(
                f.area for f in pieces[0].faces):
            continue
        piece = _make_piece(fa, fb)
        mid = piece.start + np.array([0.0, 0.0, 0.5 * piece.height])
        if any(_inside_piece(mid, p) for p in pieces):
            continue
        used[i] = used[j] = True
        pieces.append(piece)
        if axis_dir is not None:
            break
    if not pieces:
        return [], ("no two parallel vertical faces with material between them "
                    "(zero length or thickness, or not a solid)")
    paired_area = sum(p.faces[0].area + p.faces[1].area for p in pieces)
    if len(pieces) == 1 and paired_area < 0.4 * vertical_area \
            and _holds_all(pieces[0], shape.verts):
        # Every vertex lies between the two faces: a straight wall whose inside has many faces
        # of its own (a slatted screen of mapped breps: Smiley West's six privacy walls).
        return pieces, None
    if len(pieces) > MAX_PIECES or paired_area < 0.4 * vertical_area:
        return [], ("not made of straight pieces (curved?): its largest opposed faces cover "
                    f"{100.0 * paired_area / vertical_area:.0f}% of its vertical area")
    return pieces, None


def axis_info(wall):
    """('straight', world direction) | ('curved', None) | ('polyline', None) | (None, None)
    from the wall's Axis representation."""
    rep = getattr(wall, "Representation", None)
    for r in (rep.Representations if rep else ()):
        if (r.RepresentationIdentifier or "") != "Axis":
            continue
        for item in r.Items or ():
            curves = [item]
            if item.is_a("IfcCompositeCurve"):
                curves = [seg.ParentCurve for seg in item.Segments or ()]
            for c in curves:
                basis = c.BasisCurve if c.is_a("IfcTrimmedCurve") else c
                if basis.is_a("IfcConic") or basis.is_a("IfcBSplineCurve"):
                    return "curved", None
            if len(curves) != 1:
                return "polyline", None
            local = _straight_direction(curves[0])
            if local is None:
                return "polyline", None
            try:
                m = uplacement.get_local_placement(wall.ObjectPlacement)
            except Exception:
                return None, None
            d = np.asarray(m)[:3, :3] @ np.array([local[0], local[1], 0.0])
            d[2] = 0.0
            norm = np.linalg.norm(d)
            return ("straight", d / norm) if norm > 1e-9 else (None, None)
    return None, None


def _straight_direction(curve):
    """Local 2D direction of a straight axis curve, None when it is not one straight segment."""
    if curve.is_a("IfcPolyline"):
        pts = [np.array(p.Coordinates[:2], dtype=float) for p in curve.Points]
        if len(pts) != 2:
            return None
        return pts[1] - pts[0]
    if curve.is_a("IfcTrimmedCurve") and curve.BasisCurve.is_a("IfcLine"):
        return np.array(curve.BasisCurve.Dir.Orientation.DirectionRatios[:2], dtype=float)
    if curve.is_a("IfcIndexedPolyCurve"):
        pts = curve.Points.CoordList
        return np.array(pts[-1][:2], dtype=float) - np.array(pts[0][:2], dtype=float) \
            if len(pts) == 2 else None
    return None


MAX_CURTAIN_DEPTH = 0.6     # m: a straight curtain wall's panels and mullions lie within this


def straight_piece(points):
    """(WallPiece, None) for an element whose points lie in one straight vertical slab (a
    curtain wall's panels and mullions taken together): its faces are the slab's two outer
    planes. ([], why) when the points do not make a straight slab."""
    if len(points) < 4:
        return None, "no geometry"
    xy = points[:, :2] - points[:, :2].mean(axis=0)
    w, v = np.linalg.eigh(xy.T @ xy)
    n = np.array([v[0, 0], v[1, 0], 0.0])
    n /= np.linalg.norm(n)
    if n[0] < -1e-9 or (abs(n[0]) <= 1e-9 and n[1] < 0):
        n = -n                      # a deterministic sign
    s = points @ n
    depth = float(s.max() - s.min())
    t = np.array([-n[1], n[0], 0.0])
    st = points @ t
    if depth < MIN_THICKNESS:
        return None, f"without thickness (its parts span {depth:.3f} m across it)"
    if depth > MAX_CURTAIN_DEPTH:
        return None, (f"not one straight slab: its parts span {depth:.2f} m across its "
                      f"{float(st.max() - st.min()):.2f} m length (curved or bent?)")
    a = Plane(n, float(s.max()), 0.0, points)
    b = Plane(-n, -float(s.min()), 0.0, points)
    return _make_piece(a, b), None
