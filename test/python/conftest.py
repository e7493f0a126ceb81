"""Shared fixtures for the IFC -> A-Graph converter tests.

- `repo`, `shared_bim`: paths; tests of the real files skip when ../shared/bim is absent;
- `fzk`, `duplex`: each real file converted once per session (graph dict, paths, stderr);
- `run_converter`: runs scripts/ifc_to_agraph.py as a subprocess (the real CLI);
- `make_house`: writes a small synthetic IFC (two rooms, three doors) with options to break it.
"""
import json
import os
import subprocess
import sys
from types import SimpleNamespace

import numpy as np
import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
SHARED_BIM = os.path.join(os.path.dirname(REPO), "shared", "bim")
CLI = os.path.join(REPO, "scripts", "ifc_to_agraph.py")


@pytest.fixture(scope="session")
def repo():
    return REPO


def _shared_file(name):
    path = os.path.join(SHARED_BIM, name)
    if not os.path.isfile(path):
        pytest.skip(f"../shared/bim not found: {path} is absent (the real IFC test models live "
                    "beside the repository, see the design notes)")
    return path


def _run(args, timeout=300):
    env = dict(os.environ, PATH="/usr/bin:" + os.environ.get("PATH", ""))
    return subprocess.run([sys.executable, CLI] + [str(a) for a in args], capture_output=True,
                          text=True, timeout=timeout, env=env)


def fails(proc, *words):
    """The converter stopped with exit 2 and one error line (no traceback) holding `words`."""
    assert proc.returncode == 2, (proc.stdout, proc.stderr)
    assert "Traceback" not in proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert lines and lines[-1].startswith("ifc_to_agraph: error: "), proc.stderr
    for w in words:
        assert w in lines[-1], lines[-1]
    return lines[-1]


def convert_quiet(run_converter, path, out):
    """Converts `path` into `out` (--quiet): (the A-Graph as a dict, the converter's stderr)."""
    proc = run_converter([path, "-o", out, "--quiet"])
    assert proc.returncode == 0, proc.stderr
    with open(proc.stdout.strip().splitlines()[-1], encoding="utf-8") as fh:
        return json.load(fh), proc.stderr


@pytest.fixture(scope="session")
def run_converter():
    return _run


def _convert_once(tmp_path_factory, name):
    src = _shared_file(name)
    out = tmp_path_factory.mktemp(name.split(".")[0])
    proc = _run([src, "-o", out / "model"])
    assert proc.returncode == 0, proc.stderr
    json_path = proc.stdout.strip().splitlines()[-1]
    with open(json_path, encoding="utf-8") as fh:
        graph = json.load(fh)
    return SimpleNamespace(src=src, json_path=json_path, obj_path=str(out / "model.obj"),
                           graph=graph, stdout=proc.stdout, stderr=proc.stderr)


@pytest.fixture(scope="session")
def fzk(tmp_path_factory):
    return _convert_once(tmp_path_factory, "AC20-FZK-Haus.ifc")


@pytest.fixture(scope="session")
def duplex(tmp_path_factory):
    return _convert_once(tmp_path_factory, "duplex.ifc")


# --------------------------------------------------------------------------- synthetic IFC
UNITS = {"m": 1.0, "mm": 0.001, "ft": 0.3048, "none": 1.0}


def _placement(f, product, x, y, z=0.0, angle_deg=0.0):
    import ifcopenshell.api.geometry
    a = np.radians(angle_deg)
    m = np.eye(4)
    m[:2, :2] = [[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]]
    m[:3, 3] = [x, y, z]
    ifcopenshell.api.geometry.edit_object_placement(f, product=product, matrix=m, is_si=True)


def _box(f, ctx, k, sx, sy, sz, x0=0.0, y0=0.0, z0=0.0):
    """A box representation in the product's local frame (arguments in metres)."""
    from ifcopenshell.util.shape_builder import ShapeBuilder
    b = ShapeBuilder(f)
    rect = b.polyline([((x0) * k, (y0) * k), ((x0 + sx) * k, (y0) * k),
                       ((x0 + sx) * k, (y0 + sy) * k), ((x0) * k, (y0 + sy) * k)], closed=True)
    solid = b.extrude(b.profile(rect), magnitude=sz * k, position=np.array([0.0, 0.0, z0 * k]))
    return b.get_representation(ctx, [solid])


def _prism(f, ctx, k, points, sz):
    """An extruded polygon (points in metres, local frame) from z 0 to sz."""
    from ifcopenshell.util.shape_builder import ShapeBuilder
    b = ShapeBuilder(f)
    rect = b.polyline([(x * k, y * k) for x, y in points], closed=True)
    return b.get_representation(ctx, [b.extrude(b.profile(rect), magnitude=sz * k)])


def build_house(path, unit="m", schema="IFC4", spaces=True, walls=True, zero_wall=False,
                lonely_door=False, external_pset=True, south_external=True, partition="door",
                window_opening=False, virtual_element=False, curtain_wall=None,
                storey_elevation=0.0, storey_placement=True, extras=(), floor_slab=True):
    """Two rooms A (x 0.2..3.9) and B (x 4.1..7.8), y 0.2..3.8, walls 0.2 m thick, 2.6 m high;
    door D_AB in the partition (x 4.0, y 1.0..1.9), door D_out in the south wall of A
    (y 0.1, x 1.0..2.0). Options add a zero-length wall, a door in a free-standing wall far away,
    drop the spaces or the walls (and doors), use another unit. partition="opening" leaves D_AB's
    opening (OP_AB) without its door; "none" drops the partition and its door, and the spaces
    then meet at x 4.0 (virtual_element adds an IfcVirtualElement V_AB there, bounding both by
    VIRTUAL space boundaries). window_opening adds an unfilled opening OP_win in B's north wall,
    sill 1.0 m, 1.2 m high. curtain_wall="panels" replaces the east wall by an IfcCurtainWall
    CW_east (x 7.8..8.0) of three mullions (IfcMember, 0.1 x 0.2 m) and two glass panels
    (IfcPlate, 0.02 m thick, in the middle) aggregated to it; "empty" gives it no parts.
    storey_elevation=None leaves the storey's Elevation unset, storey_placement=False drops its
    placement. extras: "space_C" adds a space C far from every wall (x 20..23, y 0..3);
    "orphan_opening" an IfcOpeningElement OP_orphan that voids nothing; "dup_opening" an unfilled
    opening OP_dup in the partition where door D_AB is; "columns" (issue 24) an IfcColumn C_corner
    in A's north-west corner (x 0.2..0.6, y 3.4..3.8, 2.6 m high; A's footprint goes round it, so
    its faces x = 0.6 and y = 3.4 are on A's outline), an IfcColumn C_free standing in A
    (x 2.0..2.4, y 1.8..2.2) and an IfcBuildingElementProxy P_low in B's south-east corner
    (x 7.4..7.8, y 0.2..0.6, only 1.0 m high; B's footprint goes round it), each named by a
    PHYSICAL IfcRelSpaceBoundary of its space. Returns {name: step id}."""
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
    k = 1.0 / UNITS[unit]
    f = ifcopenshell.api.project.create_file(version=schema)
    if schema == "IFC2X3":      # IFC2X3 requires an owner history on every rooted entity
        import ifcopenshell.api.owner
        import ifcopenshell.api.owner.settings as owner_settings
        user = ifcopenshell.api.owner.add_person_and_organisation(
            f, person=ifcopenshell.api.owner.add_person(f),
            organisation=ifcopenshell.api.owner.add_organisation(f))
        app = ifcopenshell.api.owner.add_application(f)
        saved = (owner_settings.get_user, owner_settings.get_application)
        owner_settings.get_user = lambda _f: user
        owner_settings.get_application = lambda _f: app
        try:
            return _build_house_body(f, path, k, unit, spaces, walls, zero_wall, lonely_door,
                                     external_pset, south_external, partition, window_opening,
                                     virtual_element, curtain_wall, storey_elevation,
                                     storey_placement, extras, floor_slab=floor_slab)
        finally:
            owner_settings.get_user, owner_settings.get_application = saved
    return _build_house_body(f, path, k, unit, spaces, walls, zero_wall, lonely_door,
                             external_pset, south_external, partition, window_opening,
                             virtual_element, curtain_wall, storey_elevation, storey_placement,
                             extras, floor_slab=floor_slab)


def _spatial_skeleton(f, project, building_name):
    """The Model and Body contexts and IfcSite > IfcBuilding `building_name` > IfcBuildingStorey
    'EG' under `project` (not placed): (body, site, building, storey)."""
    import ifcopenshell.api.aggregate
    import ifcopenshell.api.context
    import ifcopenshell.api.root
    model = ifcopenshell.api.context.add_context(f, context_type="Model")
    body = ifcopenshell.api.context.add_context(f, context_type="Model", context_identifier="Body",
                                                target_view="MODEL_VIEW", parent=model)
    site = ifcopenshell.api.root.create_entity(f, ifc_class="IfcSite", name="Site")
    building = ifcopenshell.api.root.create_entity(f, ifc_class="IfcBuilding", name=building_name)
    storey = ifcopenshell.api.root.create_entity(f, ifc_class="IfcBuildingStorey", name="EG")
    ifcopenshell.api.aggregate.assign_object(f, relating_object=project, products=[site])
    ifcopenshell.api.aggregate.assign_object(f, relating_object=site, products=[building])
    ifcopenshell.api.aggregate.assign_object(f, relating_object=building, products=[storey])
    return body, site, building, storey


def _build_house_body(f, path, k, unit, spaces, walls, zero_wall, lonely_door, external_pset,
                      south_external, partition="door", window_opening=False,
                      virtual_element=False, curtain_wall=None, storey_elevation=0.0,
                      storey_placement=True, extras=(), floor_slab=True):
    import ifcopenshell.guid
    import ifcopenshell.api.aggregate
    import ifcopenshell.api.feature
    import ifcopenshell.api.geometry
    import ifcopenshell.api.pset
    import ifcopenshell.api.root
    import ifcopenshell.api.spatial
    import ifcopenshell.api.unit
    project = ifcopenshell.api.root.create_entity(f, ifc_class="IfcProject", name="Test")
    if unit != "none":
        if unit == "ft":
            lu = ifcopenshell.api.unit.add_conversion_based_unit(f, name="foot")
        else:
            lu = ifcopenshell.api.unit.add_si_unit(f, unit_type="LENGTHUNIT",
                                                   prefix="MILLI" if unit == "mm" else None)
        ifcopenshell.api.unit.assign_unit(f, units=[lu])
    body, site, building, storey = _spatial_skeleton(f, project, "TestHouse")
    for p in (site, building, storey):
        _placement(f, p, 0.0, 0.0)
    ids = {}

    def wall(name, x, y, length, angle, external):
        w = ifcopenshell.api.root.create_entity(f, ifc_class="IfcWall", name=name)
        _placement(f, w, x, y, 0.0, angle)
        ifcopenshell.api.geometry.assign_representation(
            f, product=w, representation=_box(f, body, k, length, 0.2, 2.6))
        ifcopenshell.api.spatial.assign_container(f, products=[w], relating_structure=storey)
        if external_pset:
            pset = ifcopenshell.api.pset.add_pset(f, product=w, name="Pset_WallCommon")
            ifcopenshell.api.pset.edit_pset(f, pset=pset, properties={"IsExternal": external})
        ids[name] = w.id()
        return w

    # Local x along the wall, local y across: [0, 0.2]. Outer walls, then the partition.
    if not walls:       # a slab only, so that the file still has some geometry
        slab = ifcopenshell.api.root.create_entity(f, ifc_class="IfcSlab", name="S")
        _placement(f, slab, 0.0, 0.0)
        ifcopenshell.api.geometry.assign_representation(
            f, product=slab, representation=_box(f, body, k, 8.0, 4.0, 0.2, 0.0, 0.0, -0.2))
        ifcopenshell.api.spatial.assign_container(f, products=[slab], relating_structure=storey)
    south = wall("W_south", 0.0, 0.0, 8.0, 0.0, south_external)
    wall("W_north", 8.0, 4.0, 8.0, 180.0, True)
    wall("W_west", 0.0, 4.0, 4.0, -90.0, True)
    if curtain_wall is None:
        wall("W_east", 8.0, 0.0, 4.0, 90.0, True)
    else:
        cw = ifcopenshell.api.root.create_entity(f, ifc_class="IfcCurtainWall", name="CW_east")
        _placement(f, cw, 8.0, 0.0, 0.0, 90.0)
        ifcopenshell.api.spatial.assign_container(f, products=[cw], relating_structure=storey)
        ids["CW_east"] = cw.id()
        parts = []
        if curtain_wall == "panels":
            for i, x0 in enumerate((0.0, 1.95, 3.9)):
                parts.append(("IfcMember", f"CW_m{i}", (0.1, 0.2, 2.6, x0, 0.0)))
            for i, (x0, x1) in enumerate(((0.1, 1.95), (2.05, 3.9))):
                parts.append(("IfcPlate", f"CW_p{i}", (x1 - x0, 0.02, 2.6, x0, 0.09)))
        elif curtain_wall == "bent":     # a second panel turned 90 degrees, 1 m deep
            parts.append(("IfcPlate", "CW_p0", (3.8, 0.02, 2.6, 0.1, 0.09)))
            parts.append(("IfcPlate", "CW_p1", (0.02, 1.0, 2.6, 3.9, 0.0)))
        for cls, name, (sx, sy, sz, x0, y0) in parts:
            p = ifcopenshell.api.root.create_entity(f, ifc_class=cls, name=name)
            _placement(f, p, 8.0, 0.0, 0.0, 90.0)
            ifcopenshell.api.geometry.assign_representation(
                f, product=p, representation=_box(f, body, k, sx, sy, sz, x0, y0))
            ifcopenshell.api.aggregate.assign_object(f, relating_object=cw, products=[p])
            ids[name] = p.id()
    part = wall("W_part", 4.1, 0.0, 4.0, 90.0, False) if partition != "none" else None
    if zero_wall:
        wall("W_zero", 2.0, 2.0, 0.0, 0.0, False)
    lonely = wall("W_lonely", 20.0, 20.0, 3.0, 0.0, False) if lonely_door else None

    def opening(name, host, lx, width, height, sill=0.0, register=True):
        op = ifcopenshell.api.root.create_entity(f, ifc_class="IfcOpeningElement", name=name)
        _placement(f, op, 0.0, 0.0)
        ifcopenshell.api.geometry.assign_representation(
            f, product=op, representation=_box(f, body, k, width, 0.4, height, lx, -0.1, sill))
        op.ObjectPlacement.PlacementRelTo = host.ObjectPlacement
        ifcopenshell.api.feature.add_feature(f, feature=op, element=host)
        if register:
            ids[name] = op.id()
        return op

    def door(name, host, lx, width=0.9, height=2.1):
        """A door at local x = lx..lx+width of the host wall."""
        op = opening(name + "_op", host, lx, width, height, register=False)
        d = ifcopenshell.api.root.create_entity(f, ifc_class="IfcDoor", name=name)
        d.OverallWidth, d.OverallHeight = width * k, height * k
        _placement(f, d, 0.0, 0.0)
        ifcopenshell.api.geometry.assign_representation(
            f, product=d, representation=_box(f, body, k, width, 0.05, height, lx, 0.075, 0.0))
        d.ObjectPlacement.PlacementRelTo = host.ObjectPlacement
        ifcopenshell.api.feature.add_filling(f, opening=op, element=d)
        ifcopenshell.api.spatial.assign_container(f, products=[d], relating_structure=storey)
        ids[name] = d.id()

    if partition == "door":
        door("D_AB", part, 1.0)     # partition: local x runs along +y from y=0
        if "dup_opening" in extras:
            opening("OP_dup", part, 1.1, 0.8, 2.1)
    elif partition == "opening":
        opening("OP_AB", part, 1.0, 0.9, 2.1)
    if window_opening:
        opening("OP_win", f.by_id(ids["W_north"]), 1.5, 1.2, 1.2, sill=1.0)
    door("D_out", south, 1.0, 1.0)
    if not walls:
        for name in [n for n in ids if n.startswith(("W_", "D_"))]:
            ifcopenshell.api.root.remove_product(f, product=f.by_id(ids.pop(name)))
    if lonely is not None:
        door("D_lonely", lonely, 1.0)
    if spaces:
        split = (4.0, 4.0) if partition == "none" else (3.9, 4.1)
        notched = {"A": [(0.2, 0.2), (split[0], 0.2), (split[0], 3.8), (0.6, 3.8), (0.6, 3.4),
                         (0.2, 3.4)],
                   "B": [(split[1], 0.2), (7.4, 0.2), (7.4, 0.6), (7.8, 0.6), (7.8, 3.8),
                         (split[1], 3.8)]}
        for name, x0, x1 in (("A", 0.2, split[0]), ("B", split[1], 7.8)):
            sp = ifcopenshell.api.root.create_entity(f, ifc_class="IfcSpace", name=name,
                                                     )
            sp.LongName = "Room " + name
            _placement(f, sp, 0.0, 0.0)
            ifcopenshell.api.aggregate.assign_object(f, relating_object=storey, products=[sp])
            rep = _prism(f, body, k, notched[name], 2.6) if "columns" in extras else \
                _box(f, body, k, x1 - x0, 3.6, 2.6, x0, 0.2, 0.0)
            ifcopenshell.api.geometry.assign_representation(f, product=sp, representation=rep)
            ids["space_" + name] = sp.id()
        if "columns" in extras:
            for cls, name, (x0, y0, sz), room in (
                    ("IfcColumn", "C_corner", (0.2, 3.4, 2.6), "A"),
                    ("IfcColumn", "C_free", (2.0, 1.8, 2.6), "A"),
                    ("IfcBuildingElementProxy", "P_low", (7.4, 0.2, 1.0), "B")):
                c = ifcopenshell.api.root.create_entity(f, ifc_class=cls, name=name)
                _placement(f, c, 0.0, 0.0)
                ifcopenshell.api.geometry.assign_representation(
                    f, product=c, representation=_box(f, body, k, 0.4, 0.4, sz, x0, y0))
                ifcopenshell.api.spatial.assign_container(f, products=[c],
                                                          relating_structure=storey)
                ids[name] = c.id()
                f.create_entity("IfcRelSpaceBoundary", GlobalId=ifcopenshell.guid.new(),
                                RelatingSpace=f.by_id(ids["space_" + room]),
                                RelatedBuildingElement=c, PhysicalOrVirtualBoundary="PHYSICAL",
                                InternalOrExternalBoundary="INTERNAL")
        if virtual_element:
            ve = ifcopenshell.api.root.create_entity(f, ifc_class="IfcVirtualElement", name="V_AB")
            ifcopenshell.api.spatial.assign_container(f, products=[ve], relating_structure=storey)
            ids["V_AB"] = ve.id()
            for name in ("A", "B"):
                f.create_entity("IfcRelSpaceBoundary", GlobalId=ifcopenshell.guid.new(),
                                RelatingSpace=f.by_id(ids["space_" + name]),
                                RelatedBuildingElement=ve, PhysicalOrVirtualBoundary="VIRTUAL",
                                InternalOrExternalBoundary="INTERNAL")
    if "space_C" in extras:
        sp = ifcopenshell.api.root.create_entity(f, ifc_class="IfcSpace", name="C")
        _placement(f, sp, 0.0, 0.0)
        ifcopenshell.api.aggregate.assign_object(f, relating_object=storey, products=[sp])
        ifcopenshell.api.geometry.assign_representation(
            f, product=sp, representation=_box(f, body, k, 3.0, 3.0, 2.6, 20.0, 0.0, 0.0))
        ids["space_C"] = sp.id()
    if "orphan_opening" in extras:
        op = ifcopenshell.api.root.create_entity(f, ifc_class="IfcOpeningElement",
                                                 name="OP_orphan")
        _placement(f, op, 0.0, 0.0)
        ifcopenshell.api.geometry.assign_representation(
            f, product=op, representation=_box(f, body, k, 1.0, 0.4, 2.1, 2.0, 3.7, 0.0))
        ids["OP_orphan"] = op.id()
    if "space_low" in extras:       # a space 5 m below its storey (x 20..23, y 0..3)
        sp = ifcopenshell.api.root.create_entity(f, ifc_class="IfcSpace", name="L")
        _placement(f, sp, 0.0, 0.0)
        ifcopenshell.api.aggregate.assign_object(f, relating_object=storey, products=[sp])
        ifcopenshell.api.geometry.assign_representation(
            f, product=sp, representation=_box(f, body, k, 3.0, 3.0, 2.6, 20.0, 0.0, -5.0))
        ids["space_low"] = sp.id()
    if "space_no_body" in extras:
        sp = ifcopenshell.api.root.create_entity(f, ifc_class="IfcSpace", name="N")
        _placement(f, sp, 0.0, 0.0)
        ifcopenshell.api.aggregate.assign_object(f, relating_object=storey, products=[sp])
        ids["space_no_body"] = sp.id()
    if walls and floor_slab:
        covering = floor_slab == "covering"
        slab = ifcopenshell.api.root.create_entity(
            f, ifc_class="IfcCovering" if covering else "IfcSlab",
            predefined_type="FLOORING" if covering else "FLOOR", name="S_floor")
        _placement(f, slab, 0.0, 0.0)
        length = 4.0 if floor_slab == "A" else 23.0 if "space_C" in extras else 8.0
        ifcopenshell.api.geometry.assign_representation(
            f, product=slab, representation=_box(f, body, k, length, 4.0, 0.2, 0.0, 0.0, -0.2))
        ifcopenshell.api.spatial.assign_container(f, products=[slab], relating_structure=storey)
        ids["S_floor"] = slab.id()
        if floor_slab == "hole":        # a stair hole in room B: x 4.5..7.5, y 0.5..3.5
            op = ifcopenshell.api.root.create_entity(f, ifc_class="IfcOpeningElement",
                                                     name="OP_floor")
            _placement(f, op, 0.0, 0.0)
            ifcopenshell.api.geometry.assign_representation(
                f, product=op, representation=_box(f, body, k, 3.0, 3.0, 0.4, 4.5, 0.5, -0.3))
            op.ObjectPlacement.PlacementRelTo = slab.ObjectPlacement
            ifcopenshell.api.feature.add_feature(f, feature=op, element=slab)
            ids["OP_floor"] = op.id()
    if storey_elevation is not None:
        storey.Elevation = storey_elevation * k
    if not storey_placement:
        storey.ObjectPlacement = None
    ids["storey"] = storey.id()
    f.write(str(path))
    return ids


@pytest.fixture
def make_house(tmp_path):
    def make(name="house.ifc", **options):
        path = tmp_path / name
        ids = build_house(path, **options)
        return path, ids
    return make
