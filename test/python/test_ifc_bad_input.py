"""Bad input (issue 24): each odd element is named by a warning (IfcClass #id ... [GlobalId ..])
that says what was done instead; never a silent loss, never a crash."""
import re

from conftest import convert_quiet as _convert


def _one(g, tag):
    hits = [w for w in g["warnings"] if w.startswith(tag)]
    assert len(hits) == 1, (tag, g["warnings"])
    assert re.search(r"\[GlobalId [0-9A-Za-z_$]{22}\]$", hits[0]), hits[0]
    return hits[0]


def test_storey_without_elevation_takes_its_placement(make_house, run_converter, tmp_path):
    path, ids = make_house(storey_elevation=None)
    g, err = _convert(run_converter, path, tmp_path / "h")
    w = _one(g, f"IfcBuildingStorey #{ids['storey']}: ")
    assert "without Elevation" in w and "taken from its placement (z = 0.000 m)" in w
    assert g["storeys"][0]["elevation"] == 0.0 and w in err


def test_storey_without_elevation_or_placement_takes_its_spaces(make_house, run_converter,
                                                                tmp_path):
    path, ids = make_house(storey_elevation=None, storey_placement=False)
    g, _ = _convert(run_converter, path, tmp_path / "h")
    w = _one(g, f"IfcBuildingStorey #{ids['storey']}: ")
    assert "bottom of its 2 space(s) (z = 0.000 m)" in w
    assert g["storeys"][0]["elevation"] == 0.0 and len(g["rooms"]) == 2


def test_storey_with_elevation_is_not_warned(make_house, run_converter, tmp_path):
    path, _ = make_house()
    g, _ = _convert(run_converter, path, tmp_path / "h")
    assert g["warnings"] == []


def test_space_without_walls_or_boundaries_is_named(make_house, run_converter, tmp_path):
    path, ids = make_house(partition="none", virtual_element=True, extras=("space_C",))
    g, _ = _convert(run_converter, path, tmp_path / "h")
    tag = f"IfcSpace #{ids['space_C']}: "
    hits = [w for w in g["warnings"] if w.startswith(tag)]
    assert len(hits) == 2 and all("[GlobalId " in w for w in hits)
    assert any("no wall-surface along its outline" in w and "kept as a room without walls" in w
               for w in hits)
    assert any("no IfcRelSpaceBoundary" in w and "geometry alone" in w for w in hits)
    assert "C" in [r["name"] for r in g["rooms"]]
    # A and B have space boundaries and walls: not warned.
    for name in ("space_A", "space_B"):
        assert not [w for w in g["warnings"] if w.startswith(f"IfcSpace #{ids[name]}: ")]


def test_opening_in_no_wall_is_named_and_counted(make_house, run_converter, tmp_path):
    path, ids = make_house(extras=("orphan_opening",))
    g, _ = _convert(run_converter, path, tmp_path / "h")
    w = _one(g, f"IfcOpeningElement #{ids['OP_orphan']}: ")
    assert "opening in no element" in w and "not a doorway" in w
    assert {"ifc_class": "IfcOpeningElement", "reason": "in no element", "count": 1} in \
        g["report"][0]["dropped"]
    assert len(g["doorways"]) == 2
