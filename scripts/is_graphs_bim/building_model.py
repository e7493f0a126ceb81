"""The validated building layout: plain data, in the storey's plan frame, metres.

Built by ``building_layout.parse_layout`` from the layout YAML (format in bim/README.md).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from . import building_geometry as geo

Point = geo.Point

@dataclass
class Wall:
    id: str
    start: Point
    end: Point
    thickness: float
    height: float
    external: bool
    footprint: list[Point] = field(default_factory=list)  # ccw, plan frame

    @property
    def axis(self) -> geo.Axis:
        return geo.Axis(self.start, self.end, self.thickness)

    @property
    def length(self) -> float:
        return self.axis.length


@dataclass
class Boundary:
    """A stretch of a wall face bounding a room: ``start -> end`` on the face, room on the left."""
    wall: str
    start: Point
    end: Point


@dataclass
class Room:
    name: str
    long_name: str
    corners: list[Point]                 # ccw, on the wall axes
    polygon: list[Point] = field(default_factory=list)   # ccw, inner faces
    boundaries: list[Boundary] = field(default_factory=list)

    @property
    def area(self) -> float:
        return geo.signed_area(self.polygon)


@dataclass
class Door:
    id: str
    wall: str
    at: float          # distance of the door centre from the wall's start, along its axis
    width: float
    height: float
    rooms: list[str] = field(default_factory=list)   # room names the door opens into (1 or 2)


@dataclass
class Stair:
    """A straight flight from storey ``lower`` up to storey ``lower + 1`` (issue 22).

    ``start`` is the middle of the first riser's foot (on the lower storey's floor), the flight
    climbs along ``direction`` (a unit vector): ``risers`` risers of ``riser_height``, and
    ``risers - 1`` treads of depth ``tread`` between them; the last riser steps onto the upper
    storey's floor, whose slab edge is the end of the flight's run.
    """
    id: str
    lower: int                # index of the storey the flight starts on
    start: Point
    direction: Point
    width: float
    risers: int
    riser_height: float
    tread: float
    headroom_margin: float = 0.0  # m: how far the slab openings reach beyond the flight's run

    @property
    def run(self) -> float:
        return (self.risers - 1) * self.tread

    @property
    def rise(self) -> float:
        return self.risers * self.riser_height

    def rect(self, u0: float, u1: float, extra_width: float = 0.0) -> list[Point]:
        """The plan rectangle between u0 and u1 m along the flight, ccw."""
        d, n = self.direction, geo.left(self.direction)
        half = 0.5 * self.width + extra_width
        return [geo.add(geo.add(self.start, d, u0), n, -half), geo.add(geo.add(self.start, d, u1), n, -half),
                geo.add(geo.add(self.start, d, u1), n, half), geo.add(geo.add(self.start, d, u0), n, half)]

    @property
    def footprint(self) -> list[Point]:
        return self.rect(0.0, self.run)


@dataclass
class Layout:
    name: str
    source: str
    schema: str
    units: str
    space_boundaries: bool
    rotation_deg: float
    translation: tuple[float, float, float]
    storey_name: str
    elevation: float
    floor_thickness: float      # 0: no floor slab
    ceiling_thickness: float    # 0: no ceiling slab
    slab_outline: list[Point] | None
    walls: list[Wall]
    rooms: list[Room]
    doors: list[Door]
    warnings: list[str] = field(default_factory=list)
    # a multi-storey layout (``storeys:`` in the YAML): one Layout per storey (its plan, slabs,
    # name and elevation), the flights between them; walls/rooms/doors above stay empty
    storeys: list["Layout"] = field(default_factory=list)
    stairs: list[Stair] = field(default_factory=list)
    # slab openings (plan polygons) over flights: set on each storey's Layout
    floor_openings: list[tuple[str, list[Point]]] = field(default_factory=list)
    ceiling_openings: list[tuple[str, list[Point]]] = field(default_factory=list)

    def wall(self, wid: str) -> Wall:
        return next(w for w in self.walls if w.id == wid)

    @property
    def height(self) -> float:
        return max((w.height for w in self.walls), default=0.0)

    def to_world(self, p: Point) -> Point:
        """Plan point -> world (x, y) after the building's rotation and translation."""
        c, s = math.cos(math.radians(self.rotation_deg)), math.sin(math.radians(self.rotation_deg))
        return (c * p[0] - s * p[1] + self.translation[0], s * p[0] + c * p[1] + self.translation[1])
