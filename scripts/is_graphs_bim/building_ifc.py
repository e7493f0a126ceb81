"""Validated building layout -> IFC (IFC4 or IFC2X3, metres or millimetres), via ifcopenshell.api.

Spatial structure: IfcProject > IfcSite > IfcBuilding (carries the layout's rotation and
translation) > IfcBuildingStorey (at its elevation). Walls, doors and slabs are contained in
the storey; spaces are aggregated to it. Every wall is an IfcWall placed at its axis start
with its x axis along the axis: an 'Axis' curve and a 'Body' extrusion of its mitred plan
footprint. A door is an IfcOpeningElement voiding its host wall (IfcRelVoidsElement) filled
by an IfcDoor (IfcRelFillsElement). Optionally 1st-level IfcRelSpaceBoundary relations.
A layout with several storeys gets one IfcBuildingStorey each, and per flight an IfcStair
(contained in its lower storey) aggregating an IfcStairFlight whose Body is its stepped side
profile extruded across its width; the slabs over a flight are voided by IfcOpeningElements.
Split levels (building_levels): spaces start at their room's floor, walls at the lowest floor
they bound, doors at the lower floor; slabs, steps and ramps are written by building_ifc_floors.

The output is deterministic: GlobalIds are hashes of the building name and a stable key, the
header and owner history carry fixed timestamps, and entities are created in layout order.
"""
from __future__ import annotations

import hashlib
import math
import os
import tempfile
from pathlib import Path

import ifcopenshell
import ifcopenshell.api.aggregate
import ifcopenshell.api.context
import ifcopenshell.api.feature
import ifcopenshell.api.geometry
import ifcopenshell.api.project
import ifcopenshell.api.pset
import ifcopenshell.api.root
import ifcopenshell.api.spatial
import ifcopenshell.api.unit
import ifcopenshell.guid

from . import building_geometry as geo
from . import building_ifc_floors as floors
from .building_boundaries import add_space_boundaries
from .building_layout import Layout

FIXED_TIMESTAMP = "2024-01-01T00:00:00"
FIXED_EPOCH = 1704067200  # the same instant, for IfcOwnerHistory
ORIGINATING_SYSTEM = "is_graphs make_building.py"
OPENING_OVERSHOOT = 0.05  # openings stick out of each wall face by this much (metres)
DOOR_LEAF = 0.05          # door leaf thickness (metres)


class IfcBuilder:
    """Builds one ifcopenshell file from a Layout; ``build()`` returns it."""

    def __init__(self, lay: Layout):
        self.lay = lay
        self.scale = 1000.0 if lay.units == "mm" else 1.0
        self.keys: dict[int, str] = {}  # step id -> stable key for the GlobalId
        self.key_prefix = ""            # "storey:<i>/" while writing storey i of a multi-storey layout
        # placements are made last, parents first: the api's relation calls rewrite placements
        # they find (through 4x4 matrices), which would add rounding noise to exact values
        self.places: list[tuple] = []   # (product, parent product or None, origin, x direction)
        self.f = ifcopenshell.api.project.create_file(version=lay.schema)

    # --- low-level helpers ---------------------------------------------------------------
    def L(self, v: float) -> float:
        """Metres -> file length units, rounded so that the text is clean and stable."""
        r = round(v * self.scale, 9)
        return 0.0 if r == 0 else r

    def pt(self, *c: float):
        return self.f.createIfcCartesianPoint([self.L(v) for v in c])

    def direction(self, *c: float):
        return self.f.createIfcDirection([0.0 if round(v, 12) == 0 else round(v, 12) for v in c])

    def place(self, product, parent, origin=(0.0, 0.0, 0.0), xdir=None) -> None:
        self.places.append((product, parent, origin, xdir))

    def placement(self, rel_to, origin=(0.0, 0.0, 0.0), xdir=None):
        axis = ref = None
        if xdir is not None and not (abs(xdir[0] - 1.0) < 1e-15 and abs(xdir[1]) < 1e-15):
            axis, ref = self.direction(0.0, 0.0, 1.0), self.direction(xdir[0], xdir[1], 0.0)
        return self.f.createIfcLocalPlacement(rel_to, self.f.createIfcAxis2Placement3D(self.pt(*origin), axis, ref))

    def polyline(self, pts2d, closed: bool):
        pts = [self.pt(*p) for p in pts2d]
        return self.f.createIfcPolyline(pts + [pts[0]] if closed else pts)

    def extrusion(self, poly2d, depth: float, z0: float = 0.0):
        profile = self.f.createIfcArbitraryClosedProfileDef("AREA", None, self.polyline(poly2d, True))
        pos = self.f.createIfcAxis2Placement3D(self.pt(0.0, 0.0, z0), None, None)
        return self.f.createIfcExtrudedAreaSolid(profile, pos, self.direction(0.0, 0.0, 1.0), self.L(depth))

    def shape(self, product, body_items, axis_pts=None) -> None:
        reps = []
        if axis_pts is not None:
            reps.append(self.f.createIfcShapeRepresentation(self.axis_ctx, "Axis", "Curve2D",
                                                            [self.polyline(axis_pts, False)]))
        reps.append(self.f.createIfcShapeRepresentation(self.body_ctx, "Body", "SweptSolid", body_items))
        product.Representation = self.f.createIfcProductDefinitionShape(None, None, reps)

    def rooted(self, ifc_class: str, key: str, name: str | None = None, predefined: str | None = None):
        e = ifcopenshell.api.root.create_entity(self.f, ifc_class=ifc_class, name=name, predefined_type=predefined)
        self.keys[e.id()] = self.key_prefix + key
        return e

    # --- the building --------------------------------------------------------------------
    def build(self) -> ifcopenshell.file:
        lay, f = self.lay, self.f
        org = f.createIfcOrganization(None, "is_graphs", None, None, None)
        self.app = f.createIfcApplication(org, ifcopenshell.version, ORIGINATING_SYSTEM, "is_graphs")
        if f.schema == "IFC2X3":  # owner history is mandatory in IFC2X3 (optional, and omitted, in IFC4)
            person = f.createIfcPerson(None, "is_graphs", None, None, None, None, None, None)
            self.user = f.createIfcPersonAndOrganization(person, org, None)
        project = self.rooted("IfcProject", "project", lay.name)
        self._units()
        model = ifcopenshell.api.context.add_context(f, context_type="Model")
        self.body_ctx = ifcopenshell.api.context.add_context(f, "Model", "Body", "MODEL_VIEW", parent=model)
        self.axis_ctx = ifcopenshell.api.context.add_context(f, "Model", "Axis", "GRAPH_VIEW", parent=model)

        site = self.rooted("IfcSite", "site", "Site")
        self.place(site, None)
        building = self.rooted("IfcBuilding", "building", lay.name)
        rot = math.radians(lay.rotation_deg)
        self.place(building, site, lay.translation, (math.cos(rot), math.sin(rot)))
        if lay.storeys:
            self._storeys(site, building, project)
        else:
            storey = self.rooted("IfcBuildingStorey", "storey", lay.storey_name)
            self.place(storey, building, (0.0, 0.0, lay.elevation))
            storey.Elevation = self.L(lay.elevation)
            for e in (site, building, storey):
                e.CompositionType = "ELEMENT"
            ifcopenshell.api.aggregate.assign_object(f, products=[site], relating_object=project)
            ifcopenshell.api.aggregate.assign_object(f, products=[building], relating_object=site)
            ifcopenshell.api.aggregate.assign_object(f, products=[storey], relating_object=building)
            self.storey = storey
            self._storey_contents()
        for product, parent, origin, xdir in self.places:
            product.ObjectPlacement = self.placement(parent.ObjectPlacement if parent else None, origin, xdir)
        self._finish()
        return f

    def _storey_contents(self, extra=()) -> None:
        """Walls, doors, slabs, spaces (and ``extra`` contained products) of ``self.lay`` in
        ``self.storey``."""
        lay, f, storey = self.lay, self.f, self.storey
        walls = {w.id: self._wall(w) for w in lay.walls}
        doors = {d.id: self._door(d, walls[d.wall]) for d in lay.doors}
        slabs = floors.slabs(self)
        spaces = {rm.name: self._space(rm) for rm in lay.rooms}
        extra = list(extra) + [floors.flight(self, s, "steps") for s in lay.steps]
        extra += [floors.ramp(self, rp) for rp in lay.ramps]
        leaves = [doors[d.id] for d in lay.doors if d.leaf]  # doorless openings are no contained element
        contained = list(walls.values()) + leaves + slabs + extra
        # the api collects related products in sets: put them back in layout order (determinism)
        rel = ifcopenshell.api.spatial.assign_container(f, products=contained, relating_structure=storey)
        rel.RelatedElements = contained
        if spaces:
            rel = ifcopenshell.api.aggregate.assign_object(f, products=list(spaces.values()), relating_object=storey)
            rel.RelatedObjects = list(spaces.values())
        if lay.space_boundaries:
            add_space_boundaries(self, spaces, walls, doors)

    def _storeys(self, site, building, project) -> None:
        """A multi-storey layout: one IfcBuildingStorey per storey, then each storey's contents
        (GlobalId keys prefixed with the storey's index) and its flights up."""
        top, f = self.lay, self.f
        storeys = []
        for i, st in enumerate(top.storeys):
            e = self.rooted("IfcBuildingStorey", f"storey:{i}", st.storey_name)
            self.place(e, building, (0.0, 0.0, st.elevation))
            e.Elevation = self.L(st.elevation)
            storeys.append(e)
        for e in (site, building, *storeys):
            e.CompositionType = "ELEMENT"
        ifcopenshell.api.aggregate.assign_object(f, products=[site], relating_object=project)
        ifcopenshell.api.aggregate.assign_object(f, products=[building], relating_object=site)
        rel = ifcopenshell.api.aggregate.assign_object(f, products=storeys, relating_object=building)
        rel.RelatedObjects = storeys
        for i, st in enumerate(top.storeys):
            self.lay, self.storey, self.key_prefix = st, storeys[i], f"storey:{i}/"
            stairs = [floors.flight(self, s) for s in top.stairs if s.lower == i]
            self._storey_contents(stairs)
        self.lay, self.key_prefix = top, ""

    def _units(self) -> None:
        f = self.f
        length = f.createIfcSIUnit(None, "LENGTHUNIT", "MILLI" if self.lay.units == "mm" else None, "METRE")
        units = [length, f.createIfcSIUnit(None, "AREAUNIT", None, "SQUARE_METRE"),
                 f.createIfcSIUnit(None, "VOLUMEUNIT", None, "CUBIC_METRE"),
                 f.createIfcSIUnit(None, "PLANEANGLEUNIT", None, "RADIAN")]
        ifcopenshell.api.unit.assign_unit(f, units=units)
        f.by_type("IfcUnitAssignment")[0].Units = units  # fixed order (the api uses a set)

    def _wall(self, w):
        ax = w.axis
        d = ax.direction
        wall = self.rooted("IfcWall", f"wall:{w.id}", w.id, None if self.f.schema == "IFC2X3"
                           else ("SOLIDWALL" if w.external else "PARTITIONING"))
        self.place(wall, self.storey, (*w.start, w.bottom), d)   # standing on the lowest floor it bounds
        local = [(ax.param(p), ax.offset(p)) for p in w.footprint]
        self.shape(wall, [self.extrusion(local, w.height - w.bottom)], axis_pts=[(0.0, 0.0), (ax.length, 0.0)])
        pset = ifcopenshell.api.pset.add_pset(self.f, product=wall, name="Pset_WallCommon")
        ifcopenshell.api.pset.edit_pset(self.f, pset=pset, properties={"IsExternal": w.external})
        return wall

    def _door(self, d, wall):
        w = self.lay.wall(d.wall)
        half = 0.5 * w.thickness + OPENING_OVERSHOOT
        opening = self.rooted("IfcOpeningElement", f"opening:{d.id}", f"{d.id} opening" if d.leaf else d.id,
                              None if self.f.schema == "IFC2X3" else "OPENING")
        ifcopenshell.api.feature.add_feature(self.f, feature=opening, element=wall)
        self.place(opening, wall, (d.at - 0.5 * d.width, 0.0, d.sill - w.bottom))  # sill: the lower floor
        box = [(0.0, -half), (d.width, -half), (d.width, half), (0.0, half)]
        self.shape(opening, [self.extrusion(box, d.height)])
        if not d.leaf:  # a doorless opening: named as the layout's door, no IfcDoor
            return opening
        door = self.rooted("IfcDoor", f"door:{d.id}", d.id, None if self.f.schema == "IFC2X3" else "DOOR")
        door.OverallWidth, door.OverallHeight = self.L(d.width), self.L(d.height)
        if hasattr(door, "OperationType"):
            door.OperationType = "SINGLE_SWING_LEFT"
        self.place(door, opening)
        leaf = [(0.0, -0.5 * DOOR_LEAF), (d.width, -0.5 * DOOR_LEAF), (d.width, 0.5 * DOOR_LEAF),
                (0.0, 0.5 * DOOR_LEAF)]
        self.shape(door, [self.extrusion(leaf, d.height)])
        ifcopenshell.api.feature.add_filling(self.f, opening=opening, element=door)
        return door

    def _space(self, rm):
        space = self.rooted("IfcSpace", f"space:{rm.name}", rm.name, None if self.f.schema == "IFC2X3" else "SPACE")
        space.LongName = rm.long_name
        space.CompositionType = "ELEMENT"
        if self.f.schema == "IFC2X3":
            space.InteriorOrExteriorSpace = "INTERNAL"
        self.place(space, self.storey, (0.0, 0.0, rm.floor))   # its bottom at the room's floor
        self.shape(space, [self.extrusion(rm.polygon, self.lay.height - rm.floor)])
        return space

    def _finish(self) -> None:
        """Stable GlobalIds, one fixed owner history (IFC2X3) and a fixed header."""
        f, lay = self.f, self.lay
        history = None
        if f.schema == "IFC2X3":
            history = f.createIfcOwnerHistory(self.user, self.app, "READWRITE", "ADDED", FIXED_EPOCH,
                                              self.user, self.app, FIXED_EPOCH)
        for e in f.by_type("IfcRoot"):
            key = self.keys.get(e.id(), f"{e.is_a()}:{e.id()}")
            e.GlobalId = ifcopenshell.guid.compress(hashlib.md5(f"{lay.name}/{key}".encode()).hexdigest())
            e.OwnerHistory = history
        for h in f.by_type("IfcOwnerHistory"):
            if h != history:
                f.remove(h)
        fn = f.header.file_name
        fn.name = f"{lay.name}.ifc"
        fn.time_stamp = FIXED_TIMESTAMP
        fn.author = ("is_graphs",)
        fn.organization = ("is_graphs",)
        fn.originating_system = ORIGINATING_SYSTEM
        fn.authorization = "none"


def build_ifc(lay: Layout) -> ifcopenshell.file:
    return IfcBuilder(lay).build()


def write_ifc(lay: Layout, out: str | Path) -> None:
    """Writes atomically: a temporary file in the target directory renamed over ``out``."""
    out = Path(out)
    text = build_ifc(lay).to_string()
    out.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{out.name}.", suffix=".tmp", dir=out.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="\n") as fh:
            fh.write(text)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes it 0600
        os.replace(tmp, out)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
