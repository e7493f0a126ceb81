"""Issue 24: a column (or member, plate, proxy) that a PHYSICAL IfcRelSpaceBoundary names as
bounding a space and whose face lies on that space's outline gives that face as a wall-surface of
the room (a pseudo-wall of kind "flush_element"); a free-standing one, or one whose flush face is
not wall-high or is narrower than 0.3 m, gives none and is warned about. Synthetic house with
extras=("columns",) (see conftest.build_house): C_corner in room A's north-west corner, C_free
standing in A, P_low (1.0 m high) in B's south-east corner."""
import json

import pytest


@pytest.fixture
def graph(make_house, run_converter, tmp_path):
    path, ids = make_house(extras=("columns",))
    proc = run_converter([path, "-o", tmp_path / "h", "--quiet"])
    assert proc.returncode == 0, proc.stderr
    with open(proc.stdout.strip().splitlines()[-1], encoding="utf-8") as fh:
        return json.load(fh), ids


def test_flush_column_faces_bound_its_room(graph):
    g, ids = graph
    room_a = next(r for r in g["rooms"] if r["name"] == "A")
    ws = [w for w in g["walls"] if w["ifc_id"] == ids["C_corner"]]
    assert len(ws) == 2
    assert all(w["kind"] == "flush_element" and w["ifc_class"] == "IfcColumn"
               and w["name"] == "C_corner" and w["guid"] and not w["external"] for w in ws)
    faces = {}
    for w in ws:
        assert w["thickness"] == pytest.approx(0.4) and w["height"] == pytest.approx(2.6)
        a, b = (g["wall_surfaces"][s] for s in w["surfaces"])
        assert a["rooms"] == [room_a["id"]] and b["rooms"] == []     # the back is in the walls
        assert [x + y for x, y in zip(a["normal"], b["normal"])] == pytest.approx([0, 0, 0])
        assert a["ifc_id"] == ids["C_corner"] and a["guid"] == w["guid"]
        assert a["id"] in room_a["surfaces"] and w["id"] in room_a["walls"]
        faces[a["orientation"]] = a
    east, south = faces["x"], faces["y"]
    # The face x = 0.6 looks east into A; the face y = 3.4 looks south into A.
    assert east["normal"] == pytest.approx([1.0, 0.0, 0.0]) and east["d"] == pytest.approx(0.6)
    assert east["start"] == pytest.approx([0.6, 3.4]) and east["end"] == pytest.approx([0.6, 3.8])
    assert south["normal"] == pytest.approx([0.0, -1.0, 0.0])
    assert south["d"] == pytest.approx(-3.4)
    assert south["start"] == pytest.approx([0.2, 3.4]) and south["end"] == pytest.approx([0.6, 3.4])
    for f in (east, south):
        assert (f["z_min"], f["z_max"]) == pytest.approx((0.0, 2.6))
    rep = g["report"][0]["kept"]
    assert rep["flush_elements"] == 1 and rep["flush_surfaces"] == 2
    assert rep["walls"] == 5 and rep["wall_pieces"] == 5     # walls proper, as before
    assert rep["wall_surfaces"] == 14


def test_free_column_and_low_proxy_are_not_wall_surfaces(graph):
    g, ids = graph
    for name in ("C_free", "P_low"):
        assert ids[name] not in {w["ifc_id"] for w in g["walls"]}
        assert ids[name] not in {s["ifc_id"] for s in g["wall_surfaces"]}
    (free,) = [w for w in g["warnings"] if w.startswith(f"IfcColumn #{ids['C_free']}: ")]
    assert "not flush with the outline" in free and "[GlobalId " in free
    (low,) = [w for w in g["warnings"]
              if w.startswith(f"IfcBuildingElementProxy #{ids['P_low']}: ")]
    assert "not wall-high" in low
    dropped = g["report"][0]["dropped"]
    assert {"ifc_class": "IfcColumn", "count": 1,
            "reason": "it is not flush with the outline of any room it bounds"} in dropped
    assert {"ifc_class": "IfcBuildingElementProxy", "count": 1,
            "reason": "its face flush with the room outline is not wall-high"} in dropped
    # Room B keeps its four wall faces only.
    room_b = next(r for r in g["rooms"] if r["name"] == "B")
    assert {g["walls"][w]["kind"] for w in room_b["walls"]} == {"wall"}


def test_walls_proper_keep_their_kind(make_house, run_converter, tmp_path):
    path, ids = make_house(curtain_wall="panels")
    proc = run_converter([path, "-o", tmp_path / "h", "--quiet"])
    with open(proc.stdout.strip().splitlines()[-1], encoding="utf-8") as fh:
        g = json.load(fh)
    kinds = {w["name"]: (w["kind"], w["ifc_class"]) for w in g["walls"]}
    assert kinds["CW_east"] == ("curtain_wall", "IfcCurtainWall")
    assert kinds["W_south"] == ("wall", "IfcWall")
    assert g["source"]["converter_version"] == "7"
    assert all(r["kept"]["flush_elements"] == 0 for r in g["report"])


def test_flush_rule_needs_a_space_boundary(run_converter, tmp_path):
    """The same corner column without its IfcRelSpaceBoundary: not a wall-surface (the rule
    follows what the space boundaries say), and no warning either."""
    import ifcopenshell
    from conftest import build_house
    path = tmp_path / "h.ifc"
    ids = build_house(path, extras=("columns",))
    f = ifcopenshell.open(str(path))
    for rel in f.by_type("IfcRelSpaceBoundary"):
        f.remove(rel)
    f.write(str(path))
    proc = run_converter([path, "-o", tmp_path / "h", "--quiet"])
    assert proc.returncode == 0, proc.stderr
    with open(proc.stdout.strip().splitlines()[-1], encoding="utf-8") as fh:
        g = json.load(fh)
    assert not [w for w in g["walls"] if w["kind"] == "flush_element"]
    assert not [w for w in g["warnings"] if f"#{ids['C_corner']}:" in w]
