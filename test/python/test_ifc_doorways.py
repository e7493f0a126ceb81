"""Doorways without doors (issue 24): doorless wall openings and virtual separations.

Each doorway has a "kind": "door" (IfcDoor), "opening" (an IfcOpeningElement through a wall that
no door or window fills, at floor level and door-high) or "virtual" (two spaces of a storey that
share a wall-free boundary the file marks as open: IfcVirtualElement or VIRTUAL space boundaries).
"""
import json
import os

import pytest

from conftest import SHARED_BIM, convert_quiet as _convert


def _room(g, name):
    return next(r["id"] for r in g["rooms"] if r["name"] == name)


def test_doors_are_kind_door(make_house, run_converter, tmp_path):
    path, ids = make_house()
    g, _ = _convert(run_converter, path, tmp_path / "h")
    assert sorted((d["ifc_id"], d["kind"]) for d in g["doorways"]) == sorted(
        [(ids["D_AB"], "door"), (ids["D_out"], "door")])


def test_doorless_opening_joins_its_rooms(make_house, run_converter, tmp_path):
    path, ids = make_house(partition="opening")
    g, _ = _convert(run_converter, path, tmp_path / "h")
    ops = [d for d in g["doorways"] if d["kind"] == "opening"]
    assert len(ops) == 1
    d = ops[0]
    assert d["ifc_id"] == ids["OP_AB"] and d["guid"]
    assert sorted(d["rooms"]) == sorted([_room(g, "A"), _room(g, "B")])
    assert g["walls"][d["wall"]]["ifc_id"] == ids["W_part"]
    assert d["width"] == pytest.approx(0.9, abs=0.01)
    assert d["height"] == pytest.approx(2.1, abs=0.01)
    assert d["position"][0] == pytest.approx(4.0, abs=0.01)
    assert d["position"][1] == pytest.approx(1.45, abs=0.01)
    for r in d["rooms"]:
        assert d["id"] in g["rooms"][r]["doorways"]


def test_window_like_opening_is_no_doorway_and_says_so(make_house, run_converter, tmp_path):
    path, ids = make_house(window_opening=True)
    g, err = _convert(run_converter, path, tmp_path / "h")
    assert ids["OP_win"] not in [d["ifc_id"] for d in g["doorways"]]
    tag = f"IfcOpeningElement #{ids['OP_win']}: "
    w = [w for w in g["warnings"] if w.startswith(tag)]
    assert len(w) == 1 and "window-like" in w[0] and "not a doorway" in w[0]
    assert "[GlobalId " in w[0] and tag in err


def test_virtual_element_joins_two_touching_spaces(make_house, run_converter, tmp_path):
    path, ids = make_house(partition="none", virtual_element=True)
    g, _ = _convert(run_converter, path, tmp_path / "h")
    virt = [d for d in g["doorways"] if d["kind"] == "virtual"]
    assert len(virt) == 1
    d = virt[0]
    assert d["ifc_id"] == ids["V_AB"] and d["wall"] == -1
    assert sorted(d["rooms"]) == sorted([_room(g, "A"), _room(g, "B")])
    # The shared edge x = 4.0, y 0.2..3.8, less the 2 cm kept clear of the outer walls.
    assert d["position"][0] == pytest.approx(4.0, abs=0.01)
    assert d["position"][1] == pytest.approx(2.0, abs=0.05)
    assert 3.4 <= d["width"] <= 3.6


def test_touching_spaces_without_space_boundaries_are_joined(make_house, run_converter,
                                                             tmp_path):
    path, _ = make_house(partition="none")
    g, _ = _convert(run_converter, path, tmp_path / "h")
    virt = [d for d in g["doorways"] if d["kind"] == "virtual"]
    assert len(virt) == 1 and virt[0]["ifc_id"] == -1 and virt[0]["guid"] == ""


def test_spaces_across_a_wall_are_not_virtually_joined(make_house, run_converter, tmp_path):
    path, _ = make_house()
    g, _ = _convert(run_converter, path, tmp_path / "h")
    assert [d for d in g["doorways"] if d["kind"] == "virtual"] == []


def _shared(name):
    path = os.path.join(SHARED_BIM, name)
    if not os.path.isfile(path):
        pytest.skip(f"../shared/bim not found: {path} is absent")
    return path


def test_osh_flat_raum2_is_reached_through_a_doorless_opening(run_converter, tmp_path):
    # Raum 2 has no door; IfcOpeningElement #8401 (2.4 m wide, 2.03 m high, from the floor) in
    # wall #972 joins it to Raum 3. Opening #813 lies beside its host wall #785 (not through it).
    g, _ = _convert(run_converter, _shared("OSH_Flat.ifc"), tmp_path / "osh")
    raum2 = next(r for r in g["rooms"] if r["long_name"] == "Raum 2")
    assert len(raum2["doorways"]) == 1
    d = g["doorways"][raum2["doorways"][0]]
    assert d["kind"] == "opening" and d["ifc_id"] == 8401
    assert sorted(g["rooms"][r]["long_name"] for r in d["rooms"]) == ["Raum 2", "Raum 3"]
    assert d["width"] == pytest.approx(2.4, abs=0.01)
    assert any(w.startswith("IfcOpeningElement #813: ") and "does not go through" in w
               for w in g["warnings"])
    assert 813 not in [d["ifc_id"] for d in g["doorways"]]


def test_fzk_kitchen_living_and_hall_are_open_to_each_other(fzk):
    # Three IfcVirtualElements, each bounding two spaces by VIRTUAL space boundaries (checked with
    # IfcOpenShell): #77324 Flur|Wohnen, #77395 Kueche|Wohnen, #77636 Kueche|Flur. They are
    # virtual separations, not openings in walls (FZK-Haus' only unfilled opening is in a slab).
    g = fzk.graph
    names = {r["id"]: r["long_name"] for r in g["rooms"]}
    virt = {d["ifc_id"]: sorted(names[r] for r in d["rooms"])
            for d in g["doorways"] if d["kind"] == "virtual"}
    assert virt == {77324: ["Flur", "Wohnen"], 77395: ["Küche", "Wohnen"],
                    77636: ["Flur", "Küche"]}
    doors = [d for d in g["doorways"] if d["kind"] == "door"]
    assert len(doors) == 5


def test_report_says_what_was_dropped_and_why(make_house, run_converter, tmp_path):
    path, ids = make_house(window_opening=True, zero_wall=True, partition="opening")
    proc = run_converter([path, "-o", tmp_path / "h"])
    assert proc.returncode == 0, proc.stderr
    with open(proc.stdout.strip().splitlines()[-1], encoding="utf-8") as fh:
        g = json.load(fh)
    (rep,) = g["report"]
    assert rep["kept"]["doorways"] == {"door": 1, "opening": 1, "virtual": 0}
    assert rep["kept"]["walls"] == 5 and rep["kept"]["rooms"] == 2
    dropped = {(d["ifc_class"], d["reason"]): d["count"] for d in rep["dropped"]}
    assert dropped[("IfcOpeningElement", "window-like")] == 1
    assert sum(n for (cls, _), n in dropped.items() if cls == "IfcWall") == 1
    # ... and the converter prints it under the storey's summary line.
    assert "    doorways: 1 door, 1 opening, 0 virtual" in proc.stdout
    assert "    dropped: 1 IfcOpeningElement: window-like" in proc.stdout
    assert "    dropped: 1 IfcWall: " in proc.stdout


def test_unfilled_opening_where_a_door_is_is_not_a_second_doorway(make_house, run_converter,
                                                                  tmp_path):
    path, ids = make_house(extras=("dup_opening",))
    g, _ = _convert(run_converter, path, tmp_path / "h")
    assert sorted(d["ifc_id"] for d in g["doorways"]) == sorted([ids["D_AB"], ids["D_out"]])
    (w,) = [w for w in g["warnings"] if w.startswith(f"IfcOpeningElement #{ids['OP_dup']}: ")]
    assert f"overlapping IfcDoor #{ids['D_AB']}" in w and "not a second doorway" in w
