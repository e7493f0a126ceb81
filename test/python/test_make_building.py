"""Tests of the procedural building generator (scripts/make_building.py) and its IFC output.

  * the committed IFC files (bim/, test/data/) are exactly what their layouts generate;
  * the IFC content read back with ifcopenshell: counts, structure, units, areas, placement;
  * round trip through the IFC -> A-Graph converter (skipped while it does not exist);
  * the deliberately broken fixtures through the converter;
  * invalid layouts: an error naming the field, exit status 2, no output file.
"""
from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import ifcopenshell
import ifcopenshell.geom
import ifcopenshell.util.element
import ifcopenshell.util.unit
import numpy as np
import pytest
import yaml

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))

from is_graphs_bim import building_geometry as geo  # noqa: E402
from is_graphs_bim.building_ifc import build_ifc  # noqa: E402
from is_graphs_bim.building_layout import load_layout  # noqa: E402

PYTHON = sys.executable
MAKE = ROOT / "scripts" / "make_building.py"
CONVERTER = ROOT / "scripts" / "ifc_to_agraph.py"
BIM_LAYOUTS = sorted((ROOT / "bim" / "layouts").glob("*.yaml"))
FIXTURE_LAYOUTS = sorted((ROOT / "test" / "data" / "layouts").glob("*.yaml"))
BUILDINGS = [p.stem for p in BIM_LAYOUTS]
# multi-storey layouts (issue 22): their own tests in test_make_building_storeys.py
MULTI_STOREY = [p.stem for p in BIM_LAYOUTS if "storeys" in yaml.safe_load(p.read_text())]
SINGLE_STOREY = [b for b in BUILDINGS if b not in MULTI_STOREY]
VALID_FIXTURES = ["two_rooms_mm_ifc2x3"]  # fixtures that are complete, valid buildings


def layout_of(name: str):
    bim = ROOT / "bim" / "layouts" / f"{name}.yaml"
    if bim.is_file():
        return load_layout(bim)
    return load_layout(ROOT / "test" / "data" / "layouts" / f"{name}.yaml", allow_invalid=True)


def ifc_path(name: str) -> Path:
    bim = ROOT / "bim" / f"{name}.ifc"
    return bim if bim.is_file() else ROOT / "test" / "data" / f"{name}.ifc"


_opened: dict[str, ifcopenshell.file] = {}


def open_ifc(name: str) -> ifcopenshell.file:
    if name not in _opened:
        _opened[name] = ifcopenshell.open(str(ifc_path(name)))
    return _opened[name]


def shapes(f: ifcopenshell.file, products) -> dict[int, tuple[np.ndarray, np.ndarray]]:
    """World-coordinate triangulation (metres) of the given products, by STEP id."""
    settings = ifcopenshell.geom.settings()
    settings.set("use-world-coords", True)
    it = ifcopenshell.geom.iterator(settings, f, 1, include=list(products))
    out = {}
    if it.initialize():
        while True:
            sh = it.get()
            out[sh.id] = (np.array(sh.geometry.verts).reshape(-1, 3), np.array(sh.geometry.faces).reshape(-1, 3))
            if not it.next():
                break
    return out


# --- the committed files are up to date ------------------------------------------------------
@pytest.mark.parametrize("layout", BIM_LAYOUTS + FIXTURE_LAYOUTS, ids=lambda p: p.stem)
def test_committed_ifc_is_regenerated_byte_identical(layout):
    fixture = layout.parent.parent.name == "data"
    out = (ROOT / "test" / "data" if fixture else ROOT / "bim") / f"{layout.stem}.ifc"
    assert out.is_file(), f"{out} missing: run scripts/make_building.py {'--fixtures' if fixture else '--all'}"
    text = build_ifc(load_layout(layout, allow_invalid=fixture)).to_string()
    assert out.read_text(encoding="utf-8") == text, \
        f"{out} is stale: run scripts/make_building.py {'--fixtures' if fixture else '--all'}"


def test_cli_check_all_up_to_date_and_sizes():
    r = subprocess.run([PYTHON, str(MAKE), "--all", "--fixtures", "--check"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    for name in BUILDINGS:
        assert ifc_path(name).stat().st_size < 2_000_000


def test_cli_writes_one_layout(tmp_path):
    out = tmp_path / "sub" / "office.ifc"
    r = subprocess.run([PYTHON, str(MAKE), str(ROOT / "bim/layouts/office.yaml"), "-o", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip().splitlines()[-1] == str(out)
    assert out.read_bytes() == (ROOT / "bim" / "office.ifc").read_bytes()
    assert [p.name for p in out.parent.iterdir()] == ["office.ifc"]  # no temporary left behind


# --- what the buildings must be ----------------------------------------------------------------
def test_required_buildings_exist_with_their_character():
    assert {"office", "rotated", "large", "symmetric"} <= set(BUILDINGS)
    office, rotated, large = layout_of("office"), layout_of("rotated"), layout_of("large")
    assert office.space_boundaries and not rotated.space_boundaries
    offices = [round(r.area, 6) for r in office.rooms if r.long_name.startswith("Office")]
    assert len(offices) >= 6 and len(set(offices)) == 1  # identical offices, both sides
    assert abs(rotated.rotation_deg - 30.0) < 1e-9 and rotated.translation[:2] == (12.3, -4.7)
    assert any(len(r.polygon) == 6 for r in rotated.rooms)  # the L-shaped room
    assert any(any(abs(geo.dot(geo.unit(geo.sub(r.polygon[i], r.polygon[i - 1])),
                               geo.unit(geo.sub(r.polygon[(i + 1) % len(r.polygon)], r.polygon[i])))) > 1e-6
                   for i in range(len(r.polygon))) for r in rotated.rooms)  # a corner not at 90 degrees
    assert len(large.rooms) >= 20


def test_symmetric_building_is_symmetric_but_for_one_place():
    lay = layout_of("symmetric")
    xs = [p[0] for w in lay.walls for p in w.footprint]
    ys = [p[1] for w in lay.walls for p in w.footprint]
    cx, cy = (min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2

    def twin(poly):
        return sorted((round(2 * cx - x, 6), round(2 * cy - y, 6)) for x, y in poly)

    def key(poly):
        return sorted((round(x, 6), round(y, 6)) for x, y in poly)
    walls = {w.id: key(w.footprint) for w in lay.walls}
    lonely_walls = [w.id for w in lay.walls if twin(w.footprint) not in walls.values()]
    rooms = [key(r.polygon) for r in lay.rooms]
    lonely_rooms = [r.name for r in lay.rooms if twin(r.polygon) not in rooms]
    assert lonely_walls == ["n2_split"]
    assert sorted(lonely_rooms) == ["N2a", "N2b", "S2"]


@pytest.mark.parametrize("name", SINGLE_STOREY + VALID_FIXTURES)
def test_every_room_reachable_through_doors(name):
    lay = layout_of(name)
    seen, todo = {lay.rooms[0].name}, [lay.rooms[0].name]
    while todo:
        cur = todo.pop()
        for d in lay.doors:
            if cur in d.rooms:
                for other in d.rooms:
                    if other not in seen:
                        seen.add(other)
                        todo.append(other)
    assert seen == {r.name for r in lay.rooms}
    assert any(len(d.rooms) == 1 for d in lay.doors), "no exterior door"


# --- the IFC content ---------------------------------------------------------------------------
@pytest.mark.parametrize("name", SINGLE_STOREY + [p.stem for p in FIXTURE_LAYOUTS])
def test_ifc_structure_matches_layout(name):
    lay, f = layout_of(name), open_ifc(name)
    assert f.schema == lay.schema
    assert len(f.by_type("IfcWall")) == len(lay.walls)
    assert len(f.by_type("IfcSpace")) == len(lay.rooms)
    assert len(f.by_type("IfcDoor")) == len([d for d in lay.doors if d.leaf])  # leaf: false is an opening only
    (storey,) = f.by_type("IfcBuildingStorey")
    assert storey.Name == lay.storey_name
    assert ifcopenshell.util.element.get_aggregate(storey).is_a("IfcBuilding")
    for wall in f.by_type("IfcWall"):
        assert ifcopenshell.util.element.get_container(wall) == storey
        spec = lay.wall(wall.Name)
        assert ifcopenshell.util.element.get_pset(wall, "Pset_WallCommon")["IsExternal"] is spec.external
    for space in f.by_type("IfcSpace"):
        assert ifcopenshell.util.element.get_aggregate(space) == storey
    for door in f.by_type("IfcDoor"):
        assert ifcopenshell.util.element.get_container(door) == storey
        (fills,) = door.FillsVoids
        (voids,) = fills.RelatingOpeningElement.VoidsElements
        assert voids.RelatingBuildingElement.Name == next(d.wall for d in lay.doors if d.id == door.Name)
    assert bool(f.by_type("IfcRelSpaceBoundary")) == (lay.space_boundaries and bool(lay.rooms))
    if lay.space_boundaries:  # one boundary per stretch of wall face, one per door in it
        got = sorted((b.RelatingSpace.Name, b.RelatedBuildingElement.Name) for b in f.by_type("IfcRelSpaceBoundary")
                     if b.RelatedBuildingElement.is_a("IfcWall"))
        assert got == sorted((r.name, bd.wall) for r in lay.rooms for bd in r.boundaries)
        doors = sorted((b.RelatingSpace.Name, b.RelatedBuildingElement.Name) for b in f.by_type("IfcRelSpaceBoundary")
                       if b.RelatedBuildingElement.is_a("IfcDoor"))
        assert doors == sorted((r, d.id) for d in lay.doors if d.leaf for r in d.rooms)
    assert len({e.GlobalId for e in f.by_type("IfcRoot")}) == len(f.by_type("IfcRoot"))


@pytest.mark.parametrize("name", BUILDINGS + VALID_FIXTURES)
def test_every_element_triangulates(name):
    f = open_ifc(name)
    products = [p for p in f.by_type("IfcProduct") if p.Representation and not p.is_a("IfcOpeningElement")]
    got = shapes(f, products)
    bad = [f"{p.is_a()} #{p.id()} {p.Name}" for p in products if p.id() not in got or not len(got[p.id()][1])]
    assert not bad


def test_millimetre_fixture_units():
    f = open_ifc("two_rooms_mm_ifc2x3")
    assert f.schema == "IFC2X3"
    assert ifcopenshell.util.unit.calculate_unit_scale(f) == pytest.approx(0.001)
    (storey,) = f.by_type("IfcBuildingStorey")
    assert storey.Elevation == pytest.approx(500.0)
    assert all(h.CreationDate == f.by_type("IfcOwnerHistory")[0].CreationDate for h in f.by_type("IfcOwnerHistory"))


@pytest.mark.parametrize("name", SINGLE_STOREY + VALID_FIXTURES)
def test_space_footprint_areas_from_geometry(name):
    lay, f = layout_of(name), open_ifc(name)
    spaces = f.by_type("IfcSpace")
    got = shapes(f, spaces)
    for space in spaces:
        v, tris = got[space.id()]
        z0 = v[:, 2].min()
        area = 0.0
        for t in tris:
            p = v[t]
            if np.all(np.abs(p[:, 2] - z0) < 1e-6):
                area += 0.5 * abs(np.cross(p[1] - p[0], p[2] - p[0])[2])
        room = next(r for r in lay.rooms if r.name == space.Name)
        assert area == pytest.approx(room.area, abs=1e-4), space.Name
        assert z0 == pytest.approx(lay.elevation + room.floor + lay.translation[2], abs=1e-6)  # its own level


def test_rotated_building_is_really_rotated_and_translated():
    lay, f = layout_of("rotated"), open_ifc("rotated")
    walls = {w.Name: w for w in f.by_type("IfcWall")}
    got = shapes(f, walls.values())
    for spec in lay.walls:
        v = got[walls[spec.id].id()][0]
        for p in spec.footprint:  # each plan corner, moved to the world, is a vertex of the solid
            w = lay.to_world(p)
            assert np.min(np.hypot(v[:, 0] - w[0], v[:, 1] - w[1])) < 1e-6, (spec.id, p)
    v, tris = got[walls["ext_s"].id()]
    normals = np.cross(v[tris[:, 1]] - v[tris[:, 0]], v[tris[:, 2]] - v[tris[:, 0]])
    big = normals[np.argmax(np.linalg.norm(normals, axis=1))]  # a triangle of a long face
    angle = math.degrees(math.atan2(big[1], big[0])) % 180.0
    assert abs(big[2]) < 1e-9 and angle == pytest.approx(120.0, abs=1e-6)  # face normal of a 30 deg wall
    assert v[:, 0].min() > 5.0  # translated well away from the origin


# --- round trip through the converter ----------------------------------------------------------
_converted: dict[str, tuple] = {}


def convert(name: str, tmp_dir: Path):
    if not CONVERTER.is_file():
        pytest.skip("scripts/ifc_to_agraph.py does not exist yet: round-trip tests skipped")
    if name not in _converted:
        r = subprocess.run([PYTHON, str(CONVERTER), str(ifc_path(name)), "-o", str(tmp_dir / name)],
                           capture_output=True, text=True)
        data = None
        if r.returncode == 0:
            data = json.loads(Path(r.stdout.strip().splitlines()[-1]).read_text())
        _converted[name] = (r, data)
    return _converted[name]


@pytest.fixture(scope="module")
def agraph_dir(tmp_path_factory):
    return tmp_path_factory.mktemp("agraph")


def wall_step_id(name: str, wall_name: str) -> int:
    return next(w.id() for w in open_ifc(name).by_type("IfcWall") if w.Name == wall_name)


@pytest.mark.parametrize("name", SINGLE_STOREY + VALID_FIXTURES + ["degenerate_wall"])
def test_converter_round_trip(name, agraph_dir):
    lay = layout_of(name)
    r, a = convert(name, agraph_dir)
    assert r.returncode == 0, r.stderr
    real_walls = [w for w in lay.walls if w.length > 1e-6 and w.thickness > 0]
    assert len(a["rooms"]) == len(lay.rooms)
    assert len(a["walls"]) == len(real_walls)
    assert len(a["doorways"]) == len(lay.doors)
    assert a["source"]["length_unit_m"] == pytest.approx(0.001 if lay.units == "mm" else 1.0)
    assert a["storeys"][0]["elevation"] == pytest.approx(lay.elevation + lay.translation[2], abs=1e-6)
    rooms = {room["id"]: room for room in a["rooms"]}
    for room in a["rooms"]:
        spec = next(x for x in lay.rooms if x.name == room["name"])
        assert room["area"] == pytest.approx(spec.area, abs=1e-3), room["name"]
        want = {bd.wall for bd in spec.boundaries}
        assert {a["walls"][w]["name"] for w in room["walls"]} == want, room["name"]
    for dw in a["doorways"]:
        spec = next(d for d in lay.doors if d.id == dw["name"])
        assert sorted(rooms[i]["name"] for i in dw["rooms"]) == sorted(spec.rooms), dw["name"]
        assert a["walls"][dw["wall"]]["name"] == spec.wall
        assert dw["width"] == pytest.approx(spec.width, abs=1e-6)
    # every wall's two faces: the planes n.p = d the layout predicts, in the world frame, to 1 mm
    c, s = math.cos(math.radians(lay.rotation_deg)), math.sin(math.radians(lay.rotation_deg))
    for spec in real_walls:
        wall = next(w for w in a["walls"] if w["name"] == spec.id)
        assert wall["external"] is spec.external
        assert wall["thickness"] == pytest.approx(spec.thickness, abs=1e-3)
        n_plan = geo.left(spec.axis.direction)
        for side in (1.0, -1.0):
            n = (side * (c * n_plan[0] - s * n_plan[1]), side * (s * n_plan[0] + c * n_plan[1]))
            on_face = lay.to_world(geo.add(spec.start, n_plan, side * 0.5 * spec.thickness))
            d = n[0] * on_face[0] + n[1] * on_face[1]
            match = [surf for surf in (a["wall_surfaces"][k] for k in wall["surfaces"])
                     if surf["normal"][0] * n[0] + surf["normal"][1] * n[1] > 1 - 1e-6]
            assert len(match) == 1, (spec.id, side)
            assert match[0]["d"] == pytest.approx(d, abs=1e-3), (spec.id, side)


def test_converter_refuses_file_without_spaces(agraph_dir):
    r, _ = convert("no_spaces", agraph_dir)
    assert r.returncode == 2
    assert "IfcSpace" in r.stderr


def test_converter_warns_about_degenerate_wall(agraph_dir):
    r, a = convert("degenerate_wall", agraph_dir)
    assert r.returncode == 0, r.stderr
    tag = f"IfcWall #{wall_step_id('degenerate_wall', 'zero')}"
    assert any(tag in w for w in a["warnings"]), a["warnings"]
    assert tag in r.stderr
    assert {w["name"] for w in a["walls"]} == {"ext_s", "ext_e", "ext_n", "ext_w", "mid"}


def test_converter_door_with_one_room(agraph_dir):
    r, a = convert("door_one_room", agraph_dir)
    assert r.returncode == 0, r.stderr
    (dw,) = [d for d in a["doorways"] if d["name"] == "d_mid"]
    assert [a["rooms"][i]["name"] for i in dw["rooms"]] == ["West"]
    door_id = next(d.id() for d in open_ifc("door_one_room").by_type("IfcDoor") if d.Name == "d_mid")
    assert any(f"#{door_id}" in w for w in a["warnings"]), a["warnings"]


def test_converter_scales_millimetres_to_metres(agraph_dir):
    r, a = convert("two_rooms_mm_ifc2x3", agraph_dir)
    assert r.returncode == 0, r.stderr
    lay = layout_of("two_rooms_mm_ifc2x3")
    assert a["source"]["schema"] == "IFC2X3"
    assert max(max(abs(x) for x in room["polygon"][0]) for room in a["rooms"]) < 100.0
    assert max(w["height"] for w in a["walls"]) == pytest.approx(lay.height, abs=1e-6)


# --- invalid layouts ---------------------------------------------------------------------------
def _office() -> dict:
    return yaml.safe_load((ROOT / "bim" / "layouts" / "office.yaml").read_text())


def _set(path, value):
    def edit(d):
        cur = d
        for k in path[:-1]:
            cur = cur[k]
        cur[path[-1]] = value
        return d
    return edit


def _drop_door(door_id):
    def edit(d):
        d["doors"] = [x for x in d["doors"] if x["id"] != door_id]
        return d
    return edit


INVALID = {
    "unknown_wall": (_set(["doors", 3, "wall"], "w17"), "doors[3].wall: no wall 'w17'"),
    "unknown_key": (_set(["colour"], "red"), "colour: unknown key"),
    "bad_units": (_set(["units"], "cm"), "units: 'cm' is not one of m, mm"),
    "bad_schema": (_set(["schema"], "IFC5"), "schema: 'IFC5' is not one of"),
    "negative_thickness": (_set(["walls", 4, "thickness"], -0.1), "walls[4].thickness: -0.1 must be > 0"),
    "not_a_number": (_set(["walls", 4, "height"], "tall"), "walls[4].height: expected a number"),
    "bad_point": (_set(["walls", 0, "to"], [1, 2, 3]), "walls[0].to: expected [x, y]"),
    "room_off_axes": (_set(["rooms", 1, "corners", 2], [3.5, 12.15]), "rooms[1].corners: edge"),
    "door_off_wall": (_set(["doors", 0, "at"], 17.9), "doors[0].at: door 'd101'"),
    "door_into_junction": (_set(["doors", 0, "at"], 3.675), "doors[0].at: door 'd101' runs into wall 'p_n1'"),
    "door_too_high": (_set(["doors", 0, "height"], 3.5), "doors[0].height"),
    "wrong_connects": (_set(["doors", 0, "connects"], ["Corridor", "102"]), "doors[0].connects"),
    "unreachable_room": (_drop_door("d103"), "rooms[3]: room '103' is not reachable"),
    "duplicate_wall": (_set(["walls", 1, "id"], "ext_s"), "walls[1].id: duplicate wall id 'ext_s'"),
    "crossing_walls": (_set(["walls", 6, "to"], [3.675, 4.0]), "walls[6]: wall 'p_n1' crosses wall 'cor_s'"),
}


@pytest.mark.parametrize("case", sorted(INVALID))
def test_invalid_layout_is_refused(case, tmp_path):
    edit, expected = INVALID[case]
    src = tmp_path / "bad.yaml"
    src.write_text(yaml.safe_dump(edit(_office()), sort_keys=False))
    out = tmp_path / "bad.ifc"
    r = subprocess.run([PYTHON, str(MAKE), str(src), "-o", str(out)], capture_output=True, text=True)
    assert r.returncode == 2, r.stderr
    assert f"layout bad.yaml: {expected}" in r.stderr
    assert not out.exists()
    assert [p.name for p in tmp_path.iterdir()] == ["bad.yaml"]
