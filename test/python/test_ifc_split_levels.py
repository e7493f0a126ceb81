"""Split-level storeys: each room's floor height, and doorways across a step (converter 7).

The file (split_level_house.py): one storey at -0.6 m with room A's floor at 0.0 and room B's
0.45 m lower, joined by door D_AB in the partition. The floor comes from the slab under each
room, else the space's bottom, else the storey's elevation (warned). A door or doorless opening
across a step of up to 0.6 m joins both rooms; one across more stays a one-room doorway.
"""
import pytest

from conftest import convert_quiet
from split_level_house import build_split_house, floors_by_name


def _convert(run_converter, tmp_path, **options):
    path = tmp_path / "split.ifc"
    ids = build_split_house(path, **options)
    g, err = convert_quiet(run_converter, path, tmp_path / "out")
    return g, err, ids


def _doorway(g, ifc_id):
    return next(d for d in g["doorways"] if d["ifc_id"] == ifc_id)


def _rooms(g, d):
    return sorted(g["rooms"][ri]["name"] for ri in d["rooms"])


def test_each_room_stands_on_its_own_slab(run_converter, tmp_path):
    g, _, _ = _convert(run_converter, tmp_path)
    assert g["source"]["converter_version"] == "7"
    assert g["storeys"][0]["elevation"] == pytest.approx(-0.6)
    floors = floors_by_name(g)
    assert floors["A"] == (pytest.approx(0.0, abs=1e-6), "slab")
    assert floors["B"] == (pytest.approx(-0.45, abs=1e-6), "slab")
    report = {f["name"]: (f["floor_z"], f["source"]) for f in g["report"][0]["room_floors"]}
    assert report == floors


@pytest.mark.parametrize("sill, wall_base", [("upper", None), ("lower", None), ("base", -0.65)])
def test_a_door_across_the_step_joins_both_rooms(run_converter, tmp_path, sill, wall_base):
    """Sill at A's floor, at B's, or (as exports that stand walls on the storey's level do) at
    the walls' base, 0.65 m below A's floor: before converter 7 that door found B only."""
    extra = {"wall_base": wall_base, "storey_elevation": wall_base} if wall_base else {}
    g, _, ids = _convert(run_converter, tmp_path, sill=sill, **extra)
    assert _rooms(g, _doorway(g, ids["D_AB"])) == ["A", "B"]
    assert not [w for w in g["warnings"] if "opens into one room only" in w]


def test_a_doorless_opening_across_the_step_joins_both_rooms(run_converter, tmp_path):
    """The opening starts at A's floor, 0.45 m above the wall's bottom (B's floor): its sill is
    measured from A's floor, so it is a doorway, not a window."""
    g, _, ids = _convert(run_converter, tmp_path, opening_only=True)
    d = _doorway(g, ids["D_AB_op"])
    assert d["kind"] == "opening" and _rooms(g, d) == ["A", "B"]


def test_a_step_higher_than_0_6_m_is_not_joined(run_converter, tmp_path):
    g, _, ids = _convert(run_converter, tmp_path, sill="lower", step=0.7)
    assert _rooms(g, _doorway(g, ids["D_AB"])) == ["B"]
    w = [w for w in g["warnings"] if w.startswith(f"IfcDoor #{ids['D_AB']}: ")]
    assert len(w) == 1 and "opens into one room only" in w[0]


def test_without_a_slab_the_space_bottom_is_the_floor(run_converter, tmp_path):
    g, _, _ = _convert(run_converter, tmp_path, slab_b=False)
    assert floors_by_name(g)["B"] == (pytest.approx(-0.45, abs=1e-6), "space")


def test_without_slab_or_space_bottom_an_upward_face_of_the_mesh_is_the_floor(run_converter,
                                                                             tmp_path):
    g, _, _ = _convert(run_converter, tmp_path, slab_b=False, space_b_bottom=-3.0, proxy_b=True)
    assert floors_by_name(g)["B"] == (pytest.approx(-0.45, abs=1e-6), "mesh")


def test_no_floor_found_takes_the_storey_elevation_and_names_the_room(run_converter, tmp_path):
    g, err, ids = _convert(run_converter, tmp_path, slab_b=False, space_b_bottom=-3.0)
    assert floors_by_name(g)["B"] == (pytest.approx(-0.6, abs=1e-6), "storey")
    tag = f"IfcSpace #{ids['space_B']}: room 'B': no floor found under it"
    w = [w for w in g["warnings"] if w.startswith(tag)]
    assert len(w) == 1 and "the elevation of its storey 'EG' (z = -0.600 m)" in w[0], g["warnings"]
    assert tag in err


def test_a_floor_far_from_the_storey_elevation_is_warned(run_converter, tmp_path):
    """B's space (no slab under it) starts at 1.0 m, 1.6 m above its storey's elevation."""
    g, _, ids = _convert(run_converter, tmp_path, slab_b=False, space_b_bottom=1.0)
    assert floors_by_name(g)["B"] == (pytest.approx(1.0, abs=1e-6), "space")
    w = [w for w in g["warnings"] if w.startswith(f"IfcSpace #{ids['space_B']}: ")
         and "from the elevation of its storey 'EG'" in w]
    assert len(w) == 1, g["warnings"]
    assert "room 'B'" in w[0] and "1.60 m" in w[0] and "z = -0.600 m" in w[0]
    assert not [w for w in g["warnings"] if w.startswith(f"IfcSpace #{ids['space_A']}: ")]


@pytest.mark.parametrize("name, lower, joins", [
    ("test/data/split_two_rooms.ifc", {"Lower"}, {"d_step": ["Lower", "Upper"]}),
    ("bim/split.ifc", {"CorridorE", "Workshop", "Store", "WC", "Studio"},
     {"d_steps": ["CorridorE", "CorridorW"], "d_ramp": ["Living", "Studio"]}),
])
def test_the_generated_split_level_buildings(run_converter, tmp_path, repo, name, lower, joins):
    """make_building's split levels: the rooms 0.45 m down stand on their slab at -0.45 m, the
    rest at the storey's level; the steps' door and the ramp's opening join the two floors."""
    import os
    path = os.path.join(repo, name)
    if not os.path.isfile(path):
        pytest.skip(f"{name} is not in this checkout (made by make_building's split levels)")
    g, _ = convert_quiet(run_converter, path, tmp_path / "out")
    for r in g["rooms"]:
        want = -0.45 if r["name"] in lower else 0.0
        assert (r["floor_z"], r["floor_source"]) == (pytest.approx(want, abs=1e-6), "slab"), r
    by_name = {d["name"]: d for d in g["doorways"]}
    for door, rooms in joins.items():
        assert _rooms(g, by_name[door]) == rooms
    assert not [w for w in g["warnings"] if "opens into one room only" in w]
