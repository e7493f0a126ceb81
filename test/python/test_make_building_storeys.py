"""Multi-storey layouts and stairs (issue 22): bim/layouts/tower.yaml and tower_twin.yaml.

  * the storeys and flights parsed from the layout, and every invalid storey or flight refused
    with an error naming the file and the field;
  * the IFC: one IfcBuildingStorey per storey with its own walls, spaces, doors and slabs, an
    IfcStair > IfcStairFlight per flight in its lower storey that triangulates into a staircase
    reaching the next floor, openings voiding the slab over each flight;
  * the converter lists the three storeys with their rooms;
  * the single-storey layouts are untouched (their files byte-identical: test_make_building.py).
"""
from __future__ import annotations

import copy
import hashlib
import json
import subprocess
import sys
from pathlib import Path

import ifcopenshell
import ifcopenshell.guid
import ifcopenshell.util.element
import numpy as np
import pytest
import yaml

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))

from is_graphs_bim.building_layout import LayoutError, load_layout, parse_layout  # noqa: E402
from test_make_building import PYTHON, CONVERTER, MAKE, open_ifc, shapes  # noqa: E402

TOWERS = ["tower", "tower_twin"]


def tower_data() -> dict:
    return yaml.safe_load((ROOT / "bim" / "layouts" / "tower.yaml").read_text())


def plan(st):
    """A storey's plan: its wall footprints (rounded), for comparing storeys."""
    return sorted(tuple(sorted((round(x, 6), round(y, 6)) for x, y in w.footprint)) for w in st.walls)


# --- the layouts -------------------------------------------------------------------------------
@pytest.mark.parametrize("name", TOWERS)
def test_tower_storeys_and_flights(name):
    lay = load_layout(ROOT / "bim" / "layouts" / f"{name}.yaml")
    assert not lay.walls and not lay.rooms  # the plans are per storey
    assert [st.storey_name for st in lay.storeys] == ["Ground floor", "First floor", "Second floor"]
    assert [st.elevation for st in lay.storeys] == [0.0, 3.0, 6.0]
    for k, st in enumerate(lay.storeys):
        assert 6 <= len(st.rooms) <= 10
        assert any(r.long_name.startswith("Stairwell") for r in st.rooms)
        assert all(r.name.startswith(f"{k}.") for r in st.rooms)
    assert [(s.lower, s.risers, s.riser_height, s.tread) for s in lay.stairs] == [(0, 20, 0.15, 0.25), (1, 20, 0.15, 0.25)]
    for s in lay.stairs:
        assert s.rise == pytest.approx(lay.storeys[s.lower + 1].elevation - lay.storeys[s.lower].elevation)
    # the upper storey's floor slab has an opening over the flight below it; the lowest none
    assert lay.storeys[0].floor_openings == []
    assert [sid for sid, _ in lay.storeys[1].floor_openings] == ["flight_0_1"]
    assert [sid for sid, _ in lay.storeys[2].floor_openings] == ["flight_1_2"]
    assert not any(st.ceiling_openings for st in lay.storeys)  # no ceiling slab under a storey


def test_tower_floor_plans_differ():
    lay = load_layout(ROOT / "bim" / "layouts" / "tower.yaml")
    plans = [plan(st) for st in lay.storeys]
    assert plans[0] != plans[1] and plans[1] != plans[2] and plans[0] != plans[2]
    areas = [sorted(round(r.area, 3) for r in st.rooms) for st in lay.storeys]
    assert len({tuple(a) for a in areas}) == 3


def test_tower_twin_repeats_one_plan_but_for_the_entrance_hall():
    lay = load_layout(ROOT / "bim" / "layouts" / "tower_twin.yaml")
    g, f1, f2 = (plan(st) for st in lay.storeys)
    assert f1 == f2  # the first and second floors are wall-for-wall twins
    assert len(set(f1) - set(g)) == 1 and set(g) <= set(f1)  # ground: one partition fewer
    assert len(lay.storeys[0].rooms) == len(lay.storeys[1].rooms) - 1
    assert [d.id for d in lay.storeys[0].doors if d.id == "d_entrance"] == ["d_entrance"]
    assert not any(d.id == "d_entrance" for st in lay.storeys[1:] for d in st.doors)


# --- the IFC -----------------------------------------------------------------------------------
@pytest.mark.parametrize("name", TOWERS)
def test_tower_ifc_structure(name):
    lay, f = load_layout(ROOT / "bim" / "layouts" / f"{name}.yaml"), open_ifc(name)
    storeys = f.by_type("IfcBuildingStorey")
    assert [s.Name for s in storeys] == [st.storey_name for st in lay.storeys]
    assert [s.Elevation for s in storeys] == [st.elevation for st in lay.storeys]
    for e, st in zip(storeys, lay.storeys):
        assert ifcopenshell.util.element.get_aggregate(e).is_a("IfcBuilding")
        contained = [x for rel in e.ContainsElements for x in rel.RelatedElements]
        assert sorted(x.Name for x in contained if x.is_a("IfcWall")) == sorted(w.id for w in st.walls)
        assert sorted(x.Name for x in contained if x.is_a("IfcDoor")) == sorted(d.id for d in st.doors)
        spaces = [x for rel in e.IsDecomposedBy for x in rel.RelatedObjects if x.is_a("IfcSpace")]
        assert sorted(x.Name for x in spaces) == sorted(r.name for r in st.rooms)
        stairs = [x for x in contained if x.is_a("IfcStair")]
        assert [x.Name for x in stairs] == [s.id for s in lay.stairs if lay.storeys[s.lower] is st]
    assert len({e.GlobalId for e in f.by_type("IfcRoot")}) == len(f.by_type("IfcRoot"))
    # GlobalIds: hashes of the building name and the storey-qualified key
    wall = next(w for w in f.by_type("IfcWall") if w.Name == "cor_s"
                and ifcopenshell.util.element.get_container(w).Name == "First floor")
    assert wall.GlobalId == ifcopenshell.guid.compress(hashlib.md5(f"{name}/storey:1/wall:cor_s".encode()).hexdigest())


@pytest.mark.parametrize("name", TOWERS)
def test_tower_flights_are_staircases_reaching_the_next_floor(name):
    lay, f = load_layout(ROOT / "bim" / "layouts" / f"{name}.yaml"), open_ifc(name)
    for stair in f.by_type("IfcStair"):
        spec = next(s for s in lay.stairs if s.id == stair.Name)
        (flight,) = [x for rel in stair.IsDecomposedBy for x in rel.RelatedObjects]
        assert flight.is_a("IfcStairFlight") and flight.NumberOfRisers == spec.risers
        v, tris = shapes(f, [flight])[flight.id()]
        lo_z = lay.storeys[spec.lower].elevation
        # every tread's top is a horizontal face at k risers up; the last tread one riser below the floor
        tops = sorted({round(z, 6) for z in v[:, 2]})
        for k in range(1, spec.risers):
            assert round(lo_z + k * spec.riser_height, 6) in tops
        assert max(tops) == pytest.approx(lay.storeys[spec.lower + 1].elevation - spec.riser_height)
        xy = v[:, :2] - np.array(spec.start)
        along = xy @ np.array(spec.direction)
        assert along.min() == pytest.approx(0.0, abs=1e-6) and along.max() == pytest.approx(spec.run, abs=1e-6)
        assert ifcopenshell.util.element.get_container(stair).Name == lay.storeys[spec.lower].storey_name
    # the slab over each flight is voided by an opening over the flight's footprint
    for slab in f.by_type("IfcSlab"):
        st = ifcopenshell.util.element.get_container(slab)
        k = [s.storey_name for s in lay.storeys].index(st.Name)
        want = lay.storeys[k].floor_openings if slab.PredefinedType == "FLOOR" else lay.storeys[k].ceiling_openings
        got = [rel.RelatedOpeningElement.Name for rel in slab.HasOpenings]
        assert got == [f"{sid} stairwell" for sid, _ in want]


@pytest.mark.parametrize("name", TOWERS)
def test_tower_converter_lists_three_storeys_with_their_rooms(name, tmp_path):
    if not CONVERTER.is_file():
        pytest.skip("scripts/ifc_to_agraph.py missing")
    lay = load_layout(ROOT / "bim" / "layouts" / f"{name}.yaml")
    r = subprocess.run([PYTHON, str(CONVERTER), str(ROOT / "bim" / f"{name}.ifc"), "-o", str(tmp_path / name)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    a = json.loads(Path(r.stdout.strip().splitlines()[-1]).read_text())
    assert [s["name"] for s in a["storeys"]] == [st.storey_name for st in lay.storeys]
    assert [s["elevation"] for s in a["storeys"]] == pytest.approx([st.elevation for st in lay.storeys])
    for k, st in enumerate(lay.storeys):
        got = sorted(room["name"] for room in a["rooms"] if room["storey"] == k)
        assert got == sorted(r.name for r in st.rooms)


# --- invalid storeys and flights ---------------------------------------------------------------
def _edit(path, value):
    def edit(d):
        cur = d
        for k in path[:-1]:
            cur = cur[k]
        if value is _DELETE:
            del cur[path[-1]]
        else:
            cur[path[-1]] = value
        return d
    return edit


_DELETE = object()
S = "stairs"
INVALID = {
    "one_storey": (lambda d: {**d, "storeys": d["storeys"][:1], "stairs": []},
                   "storeys: a layout with storeys needs at least two"),
    "storey_and_top_walls": (lambda d: {**d, "walls": d["storeys"][0]["walls"]}, "walls: unknown key"),
    "storey_unknown_key": (_edit(["storeys", 1, "colour"], "red"), "storeys[1].colour: unknown key"),
    "storey_no_elevation": (_edit(["storeys", 1, "elevation"], _DELETE), "storeys[1].elevation: missing"),
    "storey_below": (_edit(["storeys", 2, "elevation"], 2.0), "storeys[2].elevation: 2 must be above the storey below"),
    "storey_duplicate_name": (_edit(["storeys", 1, "name"], "Ground floor"), "storeys[1].name: duplicate storey name"),
    "storey_wall_error": (_edit(["storeys", 1, "doors", 0, "wall"], "w17"), "storeys[1].doors[0].wall: no wall 'w17'"),
    "storey_slab_into_walls": (_edit(["storeys", 1, "floor_slab"], {"thickness": 0.4}),
                               "storeys[1].floor_slab.thickness: the floor slab (0.4 m)"),
    "stair_unknown_key": (_edit([S, 0, "landing"], 1.0), "stairs[0].landing: unknown key"),
    "stair_no_storey": (_edit([S, 0, "storey"], _DELETE), "stairs[0].storey: missing"),
    "stair_bad_storey": (_edit([S, 0, "storey"], "Roof"), "stairs[0].storey: no storey 'Roof'"),
    "stair_bad_index": (_edit([S, 0, "storey"], 7), "stairs[0].storey: no storey 7"),
    "stair_from_top": (_edit([S, 1, "storey"], 2), "stairs[1].storey: 'Second floor' is the top storey"),
    "stair_duplicate_id": (_edit([S, 1, "id"], "flight_0_1"), "stairs[1].id: duplicate stair id"),
    "stair_short": (_edit([S, 0, "risers"], 18), "stairs[0].riser_height: flight 'flight_0_1' rises 18 x 0.15 = 2.7 m, "
                    "not the 3 m from 'Ground floor' up to 'First floor'"),
    "stair_bad_risers": (_edit([S, 0, "risers"], 1.5), "stairs[0].risers: expected a whole number >= 2"),
    "stair_steep": (_edit([S, 0, "risers"], 10), "stairs[0].riser_height: flight 'flight_0_1' rises 10 x 0.15"),
    "stair_too_high_risers": (lambda d: _edit([S, 0, "riser_height"], _DELETE)(_edit([S, 0, "risers"], 10)(d)),
                              "stairs[0].riser_height: 0.3 m risers are too high"),
    "stair_zero_direction": (_edit([S, 0, "direction"], [0, 0]), "stairs[0].direction: must not be zero"),
    "stair_no_width": (_edit([S, 0, "width"], _DELETE), "stairs[0].width: missing"),
    "stair_bad_tread": (_edit([S, 0, "tread"], -0.25), "stairs[0].tread: -0.25 must be > 0"),
    "stair_through_wall": (_edit([S, 0, "start"], [19.5, 6.0]),
                           "stairs[0].start: flight 'flight_0_1' is not inside one room of storey 'Ground floor'"),
    "stair_no_arrival": (_edit([S, 0, "start"], [20.75, 9.0]),
                         "stairs[0].start: flight 'flight_0_1' does not arrive in a room of storey 'First floor'"),
    "stair_over_opening": (_edit([S, 1, "start"], [20.75, 11.5]),
                           "stairs[1].start: flight 'flight_1_2' stands over the floor opening for flight 'flight_0_1'"),
    "stair_overlap": (lambda d: {**d, S: d[S] + [{**d[S][0], "id": "again", "start": [21.0, 6.0]}]},
                      "stairs[2].start: flight 'again' overlaps flight 'flight_0_1'"),
}


@pytest.mark.parametrize("case", sorted(INVALID))
def test_invalid_storeys_and_stairs_are_refused(case):
    edit, expected = INVALID[case]
    with pytest.raises(LayoutError) as e:
        parse_layout(edit(copy.deepcopy(tower_data())), "bad.yaml")
    assert str(e.value).startswith(f"layout bad.yaml: {expected}"), str(e.value)


def test_invalid_stair_cli_writes_nothing(tmp_path):
    src = tmp_path / "bad.yaml"
    src.write_text(yaml.safe_dump(_edit([S, 0, "risers"], 18)(tower_data()), sort_keys=False))
    out = tmp_path / "bad.ifc"
    r = subprocess.run([PYTHON, str(MAKE), str(src), "-o", str(out)], capture_output=True, text=True)
    assert r.returncode == 2 and "layout bad.yaml: stairs[0].riser_height:" in r.stderr
    assert not out.exists()


def test_single_storey_layout_refuses_stairs():
    d = yaml.safe_load((ROOT / "bim" / "layouts" / "office.yaml").read_text())
    d["stairs"] = []
    with pytest.raises(LayoutError, match="stairs: unknown key"):
        parse_layout(d, "bad.yaml")


def test_without_riser_height_the_rise_is_split_evenly():
    d = _edit([S, 0, "riser_height"], _DELETE)(_edit([S, 0, "risers"], 18)(tower_data()))
    lay = parse_layout(d, "t.yaml")
    assert lay.stairs[0].riser_height == pytest.approx(3.0 / 18)


def test_ifc2x3_in_millimetres_writes_the_flights():
    d = {**tower_data(), "schema": "IFC2X3", "units": "mm"}
    from is_graphs_bim.building_ifc import build_ifc
    f = build_ifc(parse_layout(d, "t.yaml"))
    assert len(f.by_type("IfcBuildingStorey")) == 3
    flights = f.by_type("IfcStairFlight")
    assert [fl.NumberOfRiser for fl in flights] == [20, 20]
    assert all(st.ShapeType == "STRAIGHT_RUN_STAIR" for st in f.by_type("IfcStair"))
    assert [fl.RiserHeight for fl in flights] == [150.0, 150.0]
    v, _ = shapes(f, flights[:1])[flights[0].id()]
    assert v[:, 2].max() == pytest.approx(2.85, abs=1e-6)  # world coordinates in metres
