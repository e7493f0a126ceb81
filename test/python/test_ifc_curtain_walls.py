"""IfcCurtainWall: its panels (IfcPlate) and mullions (IfcMember) taken together are one straight
wall with two wall-surfaces, bounding the rooms it faces like any IfcWall (issue 24). No file in
../shared/bim has one (grep -c IFCCURTAINWALL: 0 in all six): synthetic house only."""

import pytest

from conftest import convert_quiet


def _convert(run_converter, path, out):
    return convert_quiet(run_converter, path, out)[0]


def test_curtain_wall_is_a_wall_bounding_its_room(make_house, run_converter, tmp_path):
    path, ids = make_house(curtain_wall="panels")
    g = _convert(run_converter, path, tmp_path / "h")
    (w,) = [w for w in g["walls"] if w["ifc_id"] == ids["CW_east"]]
    assert w["name"] == "CW_east" and w["guid"]
    assert w["thickness"] == pytest.approx(0.2, abs=1e-6)
    assert w["length"] == pytest.approx(4.0, abs=1e-6) and w["height"] == pytest.approx(2.6)
    a, b = (g["wall_surfaces"][s] for s in w["surfaces"])
    assert {round(a["d"] * a["normal"][0], 6), round(b["d"] * b["normal"][0], 6)} == {7.8, 8.0}
    room_b = next(r for r in g["rooms"] if r["name"] == "B")
    inner = a if a["normal"][0] < 0 else b
    assert inner["normal"] == pytest.approx([-1.0, 0.0, 0.0])
    assert inner["rooms"] == [room_b["id"]] and inner["id"] in room_b["surfaces"]
    assert w["external"]        # one face bounds a room, the other none (no pset)
    assert not [x for x in g["warnings"] if "CurtainWall" in x]


def test_curtain_wall_without_panels_warns(make_house, run_converter, tmp_path):
    path, ids = make_house(curtain_wall="empty")
    g = _convert(run_converter, path, tmp_path / "h")
    assert ids["CW_east"] not in [w["ifc_id"] for w in g["walls"]]
    (w,) = [x for x in g["warnings"] if x.startswith(f"IfcCurtainWall #{ids['CW_east']}: ")]
    assert "without panels" in w and "[GlobalId " in w
    dropped = g["report"][0]["dropped"]
    assert {"ifc_class": "IfcCurtainWall", "reason": "curtain wall without panels",
            "count": 1} in dropped


def test_bent_curtain_wall_warns(make_house, run_converter, tmp_path):
    path, ids = make_house(curtain_wall="bent")
    g = _convert(run_converter, path, tmp_path / "h")
    assert ids["CW_east"] not in [w["ifc_id"] for w in g["walls"]]
    (w,) = [x for x in g["warnings"] if x.startswith(f"IfcCurtainWall #{ids['CW_east']}: ")]
    assert "not one straight slab" in w and "1.00 m across" in w and "skipped" in w
