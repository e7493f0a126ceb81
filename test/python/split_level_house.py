"""A small split-level IFC built with ifcopenshell.api for the room-floor and step-door tests.

One storey (Elevation -0.6 m, as in the Renga house that showed the problem) with two rooms:
A (x 0.2..3.9, y 0.2..3.8) whose floor is at 0.0 and B (x 4.1..7.8) whose floor is `step` lower
(0.45 m by default). Each room has its own floor slab (top at its floor, 0.2 m thick) and its
space's body runs from its floor to 2.6 m. Walls 0.2 m thick from B's floor to 2.6 m; the
partition (x 3.9..4.1) holds door D_AB (y 1.0..1.9, top at door_top) whose sill is at `sill`
("upper": A's floor, "lower": B's floor, "base": the walls' bottom, or a z); a door D_out in A's
south wall. wall_base: the walls' bottom (default B's floor; the storey's elevation in exports
that stand walls on the level); opening_only: D_AB's opening without its door; slab_b=False drops
B's slab, space_b_bottom moves B's space bottom, proxy_b puts an IfcBuildingElementProxy plate
(top at B's floor) under B (to test the floor sources).
"""
import numpy as np

from conftest import _box, _placement, _spatial_skeleton


def build_split_house(path, step=0.45, sill="upper", storey_elevation=-0.6, slab_b=True,
                      space_b_bottom=None, opening_only=False, wall_base=None, door_top=2.1,
                      proxy_b=False):
    """Writes the file; returns {name: step id}."""
    import ifcopenshell.api.aggregate
    import ifcopenshell.api.feature
    import ifcopenshell.api.geometry
    import ifcopenshell.api.project
    import ifcopenshell.api.root
    import ifcopenshell.api.spatial
    import ifcopenshell.api.unit
    f = ifcopenshell.api.project.create_file(version="IFC4")
    project = ifcopenshell.api.root.create_entity(f, ifc_class="IfcProject", name="Split")
    ifcopenshell.api.unit.assign_unit(
        f, units=[ifcopenshell.api.unit.add_si_unit(f, unit_type="LENGTHUNIT")])
    body, site, building, storey = _spatial_skeleton(f, project, "SplitHouse")
    for p in (site, building):
        _placement(f, p, 0.0, 0.0)
    _placement(f, storey, 0.0, 0.0, storey_elevation)
    storey.Elevation = storey_elevation
    low = -step
    base = low if wall_base is None else wall_base
    ids = {"storey": storey.id()}

    def product(cls, name, rep, x=0.0, y=0.0, z=0.0, angle=0.0, predefined=None):
        e = ifcopenshell.api.root.create_entity(f, ifc_class=cls, name=name,
                                                predefined_type=predefined)
        _placement(f, e, x, y, z, angle)
        ifcopenshell.api.geometry.assign_representation(f, product=e, representation=rep)
        if cls == "IfcSpace":
            ifcopenshell.api.aggregate.assign_object(f, relating_object=storey, products=[e])
        else:
            ifcopenshell.api.spatial.assign_container(f, products=[e], relating_structure=storey)
        ids[name] = e.id()
        return e

    wall_h = 2.6 - base

    def wall(name, x, y, length, angle):
        return product("IfcWall", name, _box(f, body, 1.0, length, 0.2, wall_h), x, y, base,
                       angle)

    south = wall("W_south", 0.0, 0.0, 8.0, 0.0)
    wall("W_north", 8.0, 4.0, 8.0, 180.0)
    wall("W_west", 0.0, 4.0, 4.0, -90.0)
    wall("W_east", 8.0, 0.0, 4.0, 90.0)
    part = wall("W_part", 4.1, 0.0, 4.0, 90.0)

    def door(name, host, lx, z_sill, width=0.9, height=2.1):
        sill_local = z_sill - base          # the host wall's placement is at z = base
        op = ifcopenshell.api.root.create_entity(f, ifc_class="IfcOpeningElement",
                                                 name=name + "_op")
        _placement(f, op, 0.0, 0.0)
        ifcopenshell.api.geometry.assign_representation(
            f, product=op, representation=_box(f, body, 1.0, width, 0.4, height, lx, -0.1,
                                                sill_local))
        op.ObjectPlacement.PlacementRelTo = host.ObjectPlacement
        ifcopenshell.api.feature.add_feature(f, feature=op, element=host)
        ids[name + "_op"] = op.id()
        if opening_only and name == "D_AB":
            return
        d = ifcopenshell.api.root.create_entity(f, ifc_class="IfcDoor", name=name)
        d.OverallWidth, d.OverallHeight = width, height
        _placement(f, d, 0.0, 0.0)
        ifcopenshell.api.geometry.assign_representation(
            f, product=d, representation=_box(f, body, 1.0, width, 0.05, height, lx, 0.075,
                                              sill_local))
        d.ObjectPlacement.PlacementRelTo = host.ObjectPlacement
        ifcopenshell.api.feature.add_filling(f, opening=op, element=d)
        ifcopenshell.api.spatial.assign_container(f, products=[d], relating_structure=storey)
        ids[name] = d.id()

    z_sill = {"upper": 0.0, "lower": low, "base": base}.get(sill, sill)
    door("D_AB", part, 1.0, z_sill, height=door_top - z_sill)
    door("D_out", south, 1.0, 0.0, width=1.0)
    b_bottom = low if space_b_bottom is None else space_b_bottom
    for name, x0, x1, z0 in (("A", 0.2, 3.9, 0.0), ("B", 4.1, 7.8, b_bottom)):
        sp = product("IfcSpace", name, _box(f, body, 1.0, x1 - x0, 3.6, 2.6 - z0, x0, 0.2), 0.0,
                     0.0, z0)
        sp.LongName = "Room " + name
        ids["space_" + name] = sp.id()
    product("IfcSlab", "S_A", _box(f, body, 1.0, 4.0, 4.0, 0.2, 0.0, 0.0, -0.2),
            predefined="FLOOR")
    if proxy_b:     # a floor plate that is not a slab: an IfcBuildingElementProxy under B
        product("IfcBuildingElementProxy", "P_B", _box(f, body, 1.0, 3.7, 3.6, 0.1, 4.1, 0.2,
                                                       low - 0.1))
    if slab_b:
        product("IfcSlab", "S_B", _box(f, body, 1.0, 4.0, 4.0, 0.2, 4.0, 0.0, low - 0.2),
                predefined="FLOOR")
    f.write(str(path))
    return ids


def floors_by_name(graph):
    return {r["name"]: (r.get("floor_z"), r.get("floor_source")) for r in graph["rooms"]}


__all__ = ["build_split_house", "floors_by_name", "np"]
