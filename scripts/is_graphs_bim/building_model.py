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
    bottom: float = 0.0   # its foot relative to the storey: the lowest floor it bounds, or 0

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
    floor: float = 0.0                   # its floor level relative to the storey's elevation

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
    leaf: bool = True      # False: a doorless opening (an IfcOpeningElement, no IfcDoor)
    sill: float = 0.0      # relative to the storey: the lower floor of its rooms


def run_rect(start: Point, d: Point, width: float, u0: float, u1: float) -> list[Point]:
    """The plan rectangle ``width`` wide between u0 and u1 m from ``start`` along ``d``, ccw."""
    n, half = geo.left(d), 0.5 * width
    return [geo.add(geo.add(start, d, u0), n, -half), geo.add(geo.add(start, d, u1), n, -half),
            geo.add(geo.add(start, d, u1), n, half), geo.add(geo.add(start, d, u0), n, half)]


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
    base: float = 0.0             # steps inside a storey: the lower floor relative to the storey
    solid: bool = False           # steps inside a storey: solid down to ``base`` (no waist)
    door: str = ""                # steps inside a storey: the door or opening they start in

    @property
    def run(self) -> float:
        return (self.risers - 1) * self.tread

    @property
    def rise(self) -> float:
        return self.risers * self.riser_height

    def rect(self, u0: float, u1: float, extra_width: float = 0.0) -> list[Point]:
        """The plan rectangle between u0 and u1 m along the flight, ccw."""
        return run_rect(self.start, self.direction, self.width + 2 * extra_width, u0, u1)

    @property
    def footprint(self) -> list[Point]:
        return self.rect(0.0, self.run)


@dataclass
class Ramp:
    """A straight ramp inside one storey, from a doorway up into a higher room.

    ``start`` is the middle of its foot (on the lower floor, ``base`` relative to the storey);
    it climbs along ``direction`` (a unit vector) by ``rise`` over the horizontal ``length``.
    """
    id: str
    start: Point
    direction: Point
    width: float
    length: float
    rise: float
    base: float = 0.0
    door: str = ""     # the door or opening it starts in

    @property
    def slope_deg(self) -> float:
        return math.degrees(math.atan2(self.rise, self.length))

    def rect(self, u0: float, u1: float) -> list[Point]:
        return run_rect(self.start, self.direction, self.width, u0, u1)

    @property
    def footprint(self) -> list[Point]:
        return self.rect(0.0, self.length)


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
    # split levels inside a storey: steps and ramps between its rooms' floor levels, and the
    # openings they cut in the floor slab of the higher level, as (GlobalId key, name, polygon)
    steps: list[Stair] = field(default_factory=list)
    ramps: list[Ramp] = field(default_factory=list)
    level_openings: list[tuple[str, str, list[Point]]] = field(default_factory=list)

    def wall(self, wid: str) -> Wall:
        return next(w for w in self.walls if w.id == wid)

    @property
    def has_levels(self) -> bool:
        """Whether some room stands at a floor level of its own (split levels)."""
        return any(rm.floor != 0.0 for rm in self.rooms)

    @property
    def height(self) -> float:
        return max((w.height for w in self.walls), default=0.0)

    def to_world(self, p: Point) -> Point:
        """Plan point -> world (x, y) after the building's rotation and translation."""
        c, s = math.cos(math.radians(self.rotation_deg)), math.sin(math.radians(self.rotation_deg))
        return (c * p[0] - s * p[1] + self.translation[0], s * p[0] + c * p[1] + self.translation[1])
