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

    def wall(self, wid: str) -> Wall:
        return next(w for w in self.walls if w.id == wid)

    @property
    def height(self) -> float:
        return max((w.height for w in self.walls), default=0.0)

    def to_world(self, p: Point) -> Point:
        """Plan point -> world (x, y) after the building's rotation and translation."""
        c, s = math.cos(math.radians(self.rotation_deg)), math.sin(math.radians(self.rotation_deg))
        return (c * p[0] - s * p[1] + self.translation[0], s * p[0] + c * p[1] + self.translation[1])
