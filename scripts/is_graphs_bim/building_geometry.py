"""Plane (2D) geometry for the procedural building generator.

Walls are given by their axis segments; this module derives what the IFC writer needs from
them, exactly (no snapping, no tolerance games beyond ``EPS``):

* ``wall_footprints``: each wall's plan polygon with clean joints: at a node where wall ends
  meet, neighbouring faces are intersected (mitre for an L, pie slices for three or more);
  a wall end that lies inside another wall's axis (a T-junction) stops at that wall's face.
  Adjacent walls therefore tile the plan without gaps, so a room's faces close up exactly.
* ``inner_polygon``: a room's inner-face polygon from its corners on the wall axes.

Points are ``(x, y)`` tuples of floats in metres, in the storey's plan frame.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Tuple

EPS = 1e-7          # length tolerance, metres
MIN_JOINT_DEG = 15.0  # smallest angle allowed between two walls meeting at a node

Point = Tuple[float, float]  # typing.Tuple: evaluated at import, tuple[...] needs Python 3.9


def sub(a: Point, b: Point) -> Point:
    return (a[0] - b[0], a[1] - b[1])


def add(a: Point, b: Point, s: float = 1.0) -> Point:
    return (a[0] + s * b[0], a[1] + s * b[1])


def dot(a: Point, b: Point) -> float:
    return a[0] * b[0] + a[1] * b[1]


def cross(a: Point, b: Point) -> float:
    return a[0] * b[1] - a[1] * b[0]


def norm(a: Point) -> float:
    return math.hypot(a[0], a[1])


def unit(a: Point) -> Point:
    n = norm(a)
    return (a[0] / n, a[1] / n) if n > EPS else (1.0, 0.0)


def left(d: Point) -> Point:
    """``d`` turned by +90 degrees (its counter-clockwise normal)."""
    return (-d[1], d[0])


def same(a: Point, b: Point, tol: float = 1e-6) -> bool:
    return abs(a[0] - b[0]) <= tol and abs(a[1] - b[1]) <= tol


def line_intersection(p: Point, d: Point, q: Point, e: Point) -> Point | None:
    """Intersection of the lines ``p + s d`` and ``q + u e``; None when (nearly) parallel."""
    den = cross(d, e)
    if abs(den) < 1e-9:
        return None
    s = cross(sub(q, p), e) / den
    return add(p, d, s)


def signed_area(poly: list[Point]) -> float:
    return 0.5 * sum(cross(poly[i], poly[(i + 1) % len(poly)]) for i in range(len(poly)))


def point_in_polygon(pt: Point, poly: list[Point]) -> bool:
    """Strictly inside (even-odd rule; points on the boundary may go either way)."""
    inside = False
    x, y = pt
    for i in range(len(poly)):
        (x1, y1), (x2, y2) = poly[i], poly[(i + 1) % len(poly)]
        if (y1 > y) != (y2 > y) and x < x1 + (y - y1) * (x2 - x1) / (y2 - y1):
            inside = not inside
    return inside


def segments_cross(a0: Point, a1: Point, b0: Point, b1: Point) -> bool:
    """True when the open segments intersect at one point interior to both."""
    da, db = sub(a1, a0), sub(b1, b0)
    den = cross(da, db)
    if abs(den) < 1e-12:
        return False
    s = cross(sub(b0, a0), db) / den
    u = cross(sub(b0, a0), da) / den
    la, lb = norm(da), norm(db)
    return EPS / la < s < 1 - EPS / la and EPS / lb < u < 1 - EPS / lb


def is_simple(poly: list[Point]) -> bool:
    n = len(poly)
    for i in range(n):
        for j in range(i + 2, n):
            if i == 0 and j == n - 1:
                continue
            if segments_cross(poly[i], poly[(i + 1) % n], poly[j], poly[(j + 1) % n]):
                return False
    return True


def drop_collinear(poly: list[Point]) -> list[Point]:
    """Removes repeated vertices and vertices lying on the line of their neighbours."""
    out = [p for i, p in enumerate(poly) if not same(p, poly[i - 1], EPS)]
    changed = True
    while changed and len(out) > 3:
        changed = False
        for i in range(len(out)):
            a, b, c = out[i - 1], out[i], out[(i + 1) % len(out)]
            if abs(cross(unit(sub(b, a)), sub(c, b))) < EPS and dot(sub(b, a), sub(c, b)) > 0:
                del out[i]
                changed = True
                break
    return out


@dataclass(frozen=True)
class Axis:
    """A wall axis as the geometry sees it."""
    start: Point
    end: Point
    thickness: float

    @property
    def direction(self) -> Point:
        return unit(sub(self.end, self.start))

    @property
    def length(self) -> float:
        return norm(sub(self.end, self.start))

    def param(self, p: Point) -> float:
        """Distance of ``p``'s projection along the axis from ``start``."""
        return dot(sub(p, self.start), self.direction)

    def offset(self, p: Point) -> float:
        """Signed distance of ``p`` from the axis line (positive on the left)."""
        return dot(sub(p, self.start), left(self.direction))

    def contains_interior(self, p: Point) -> bool:
        s = self.param(p)
        return abs(self.offset(p)) < 1e-6 and 1e-6 < s < self.length - 1e-6


@dataclass(frozen=True)
class EndCorners:
    """The plan corners of one wall end: ``left``/``right`` seen looking away from the node."""
    left: Point
    right: Point
    node: Point | None  # the node itself when it is a polygon vertex (pie-slice joints)


class JointError(ValueError):
    """A joint the generator cannot build: carries the indices of the walls involved."""

    def __init__(self, walls: tuple[int, ...], message: str):
        super().__init__(message)
        self.walls = walls


def _end_corners(i: int, at_start: bool, axes: list[Axis]) -> EndCorners:
    a = axes[i]
    p = a.start if at_start else a.end
    d = a.direction if at_start else (-a.direction[0], -a.direction[1])
    half = 0.5 * a.thickness
    lft = left(d)
    hosts = [j for j, b in enumerate(axes) if j != i and b.length > EPS and b.contains_interior(p)]
    if len(hosts) > 1:
        raise JointError((i, *hosts), "wall end lies inside two other walls")
    if hosts:  # T-junction: stop at the host's face on this wall's side
        h = axes[hosts[0]]
        side = 1.0 if dot(d, left(h.direction)) > 0 else -1.0
        if abs(dot(d, left(h.direction))) < math.sin(math.radians(MIN_JOINT_DEG)):
            raise JointError((i, hosts[0]), "wall meets its host wall at too small an angle")
        face_pt = add(h.start, left(h.direction), side * 0.5 * h.thickness)
        cl = line_intersection(add(p, lft, half), d, face_pt, h.direction)
        cr = line_intersection(add(p, lft, -half), d, face_pt, h.direction)
        return EndCorners(cl, cr, None)
    # walls with an end at this node, as (angle, index, direction away from the node)
    ends = []
    for j, b in enumerate(axes):
        if b.length <= EPS:
            continue
        for q, dj in ((b.start, b.direction), (b.end, (-b.direction[0], -b.direction[1]))):
            if same(q, p):
                ends.append((math.atan2(dj[1], dj[0]), j, dj))
    if len(ends) <= 1:
        return EndCorners(add(p, lft, half), add(p, lft, -half), None)
    ends.sort()
    k = next(m for m, e in enumerate(ends) if e[1] == i and same(e[2], d, 1e-9))
    nxt, prv = ends[(k + 1) % len(ends)], ends[k - 1]
    for other in (nxt, prv):
        gap = abs(math.degrees(other[0] - ends[k][0])) % 360.0
        gap = min(gap, 360.0 - gap)
        if gap < MIN_JOINT_DEG:
            raise JointError((i, other[1]), f"walls meet at {gap:.1f} degrees (minimum {MIN_JOINT_DEG})")
    # left corner: this wall's left face against the next wall's (counter-clockwise) right face
    cl = line_intersection(add(p, lft, half), d,
                           add(p, left(nxt[2]), -0.5 * axes[nxt[1]].thickness), nxt[2])
    cr = line_intersection(add(p, lft, -half), d,
                           add(p, left(prv[2]), 0.5 * axes[prv[1]].thickness), prv[2])
    cl = cl if cl is not None else add(p, lft, half)
    cr = cr if cr is not None else add(p, lft, -half)
    node = p if abs(cross(unit(sub(cl, cr)), sub(p, cr))) > 1e-9 else None
    return EndCorners(cl, cr, node)


def wall_footprints(axes: list[Axis]) -> list[list[Point]]:
    """Counter-clockwise plan polygon of every wall (degenerate walls give a degenerate one)."""
    out = []
    for i, a in enumerate(axes):
        if a.length <= EPS:
            half = 0.5 * a.thickness
            p = a.start
            out.append([(p[0], p[1] - half), (p[0], p[1] - half), (p[0], p[1] + half), (p[0], p[1] + half)])
            continue
        s, e = _end_corners(i, True, axes), _end_corners(i, False, axes)
        poly = [s.right, e.left] + ([e.node] if e.node else []) + [e.right, s.left]
        poly += [s.node] if s.node else []
        out.append(poly)
    return out


def face_extent(axis: Axis, footprint: list[Point]) -> tuple[float, float]:
    """The axis interval ``[lo, hi]`` over which both faces of the wall exist."""
    lo, hi = -math.inf, math.inf
    for side in (1.0, -1.0):
        params = [axis.param(p) for p in footprint if abs(axis.offset(p) - side * 0.5 * axis.thickness) < 1e-6]
        if params:
            lo, hi = max(lo, min(params)), min(hi, max(params))
    return lo, hi


def inner_polygon(corners: list[Point], half_thickness: list[float]) -> list[Point]:
    """A room's inner-face polygon from its counter-clockwise corners on the wall axes.

    ``half_thickness[i]`` is half the thickness of the wall under edge ``corners[i] ->
    corners[i+1]``; each edge moves inward (to its left) by it and consecutive edges are
    intersected. Collinear consecutive edges must have equal thickness (ValueError otherwise).
    """
    n = len(corners)
    lines = []
    for i in range(n):
        d = unit(sub(corners[(i + 1) % n], corners[i]))
        lines.append((add(corners[i], left(d), half_thickness[i]), d))
    out = []
    for i in range(n):
        (p, d), (q, e) = lines[i - 1], lines[i]
        x = line_intersection(p, d, q, e)
        if x is None:
            if abs(cross(d, sub(q, p))) > 1e-6 or dot(d, e) < 0:
                raise ValueError(f"corner {i}: collinear edges with different wall thickness")
            continue
        out.append(x)
    return drop_collinear(out)


def convex_overlap(a, b) -> bool:
    """Whether two convex polygons overlap with positive area (separating axis test)."""
    for poly in (a, b):
        for k in range(len(poly)):
            n = left(unit(sub(poly[(k + 1) % len(poly)], poly[k])))
            pa, pb = [dot(p, n) for p in a], [dot(p, n) for p in b]
            if max(pa) <= min(pb) + 1e-9 or max(pb) <= min(pa) + 1e-9:
                return False
    return True
