"""Invalid split levels, steps and ramps (bim/layouts/split.yaml edited): each refused with one
error naming the file and the field; from the command line exit status 2 and no file written."""
from __future__ import annotations

import copy
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))

from is_graphs_bim.building_layout import LayoutError, parse_layout  # noqa: E402
from test_make_building import MAKE, PYTHON  # noqa: E402
from test_make_building_storeys import _DELETE, _edit as _edit_one  # noqa: E402


def split_data() -> dict:
    return yaml.safe_load((ROOT / "bim" / "layouts" / "split.yaml").read_text())


def _edit(*changes):
    """Edits (path, value) of the layout, in turn; value _DELETE removes the key."""
    edits = [_edit_one(path, value) for path, value in changes]

    def edit(d):
        for one in edits:
            d = one(d)
        return d
    return edit


def _steps(**kw):
    return {"id": "s", "direction": [-1, 0], "width": 0.9, "risers": 3, "tread": 0.3, **kw}


ST, RA = ("steps", 0), ("ramps", 0)
INVALID = {
    "riser_too_high": (_edit((ST + ("riser_height",), 0.225)),
                       "steps[0].riser_height: 0.225 m risers are too high (at most 0.2 m)"),
    "riser_too_high_by_default": (_edit((ST + ("riser_height",), _DELETE), (ST + ("risers",), 2)),
                                  "steps[0].risers: 2 risers up 0.45 m are 0.225 m high (at most 0.2 m)"),
    "ramp_too_steep": (_edit((RA + ("length",), 2.0)), "ramps[0].rise: ramp 'ramp_l' rises 0.45 m over 2 m: a slope "
                       "of 12.7 deg (1:4.4), steeper than 10 deg"),
    "ramp_too_steep_by_default": (_edit((RA + ("rise",), _DELETE), (RA + ("length",), 2.0)),
                                  "ramps[0].length: ramp 'ramp_l' rises 0.45 m over 2 m: a slope of 12.7 deg"),
    "steps_short": (_edit((ST + ("riser_height",), 0.14)), "steps[0].riser_height: steps 'steps_c' rise 3 x 0.14 = "
                    "0.42 m and do not reach the floor of 'CorridorW': it is 0.45 m above 'CorridorE'"),
    "ramp_short": (_edit((RA + ("rise",), 0.4)), "ramps[0].rise: ramp 'ramp_l' rises 0.4 m and does not reach the "
                   "floor of 'Living': it is 0.45 m above 'Studio'"),
    "storey_change_below": (_edit((("rooms", 9, "floor"), -0.7)), "rooms[9].floor: room 'Studio' at -0.7 m is 0.7 m "
                            "from the storey's own level (0 m): more than 0.6 m inside one storey is a storey change"),
    "storey_change_between_rooms": (_edit((("rooms", 0, "floor"), 0.2)), "rooms[5].floor: room 'CorridorE' at -0.45 m "
                                    "is 0.65 m from room 'Hall' (0.2 m): more than 0.6 m inside one storey is a "
                                    "storey change"),
    "steps_on_one_level": (_edit((ST, _steps(start=[5.0, 8.075], direction=[0, 1]))),
                           "steps[0].start: steps 's': door 'd_living' is not between rooms of different levels "
                           "(both at 0 m)"),
    "steps_to_outdoors": (_edit((ST, _steps(start=[19.85, 7.0]))),
                          "steps[0].start: steps 's': door 'd_east' is not between rooms of different levels "
                          "(to outdoors)"),
    "steps_in_no_door": (_edit((ST + ("start",), [8.0, 7.0])), "steps[0].start: steps 'steps_c': not between rooms "
                         "of different levels: its foot (centre (8, 7)) must lie on a wall face of room 'CorridorW' "
                         "within a door or opening to a lower room"),
    "steps_in_the_lower_room": (_edit((ST, _steps(start=[11.1, 7.0], direction=[1, 0]))),
                                "steps[0].start: steps 's': in room 'CorridorE' (-0.45 m), the lower side of door "
                                "'d_steps'"),
    "ramp_through_wall": (_edit((RA + ("length",), 8.0)),
                          "ramps[0].start: ramp 'ramp_l': not inside one room (it would cross a wall)"),
    "steps_wider_than_door": (_edit((ST + ("width",), 1.2)), "steps[0].start: steps 'steps_c': not between rooms"),
    "steps_unknown_key": (_edit((ST + ("colour",), "red")), "steps[0].colour: unknown key"),
    "ramp_duplicate_id": (_edit((RA + ("id",), "steps_c")), "ramps[0].id: duplicate id 'steps_c'"),
    "steps_overlap": (lambda d: {**d, "steps": d["steps"] + [{**d["steps"][0], "id": "again"}]},
                      "steps[1].start: 'again' overlaps 'steps_c'"),
    "slab_outline_with_levels": (_edit((("floor_slab", "outline"), [[0, 0], [20, 0], [20, 14], [0, 14]])),
                                 "floor_slab.outline: not with rooms at floor levels of their own"),
    "bad_floor": (_edit((("rooms", 5, "floor"), "low")), "rooms[5].floor: expected a number"),
    "bad_leaf": (_edit((("doors", 6, "leaf"), "no")), "doors[6].leaf: expected true or false"),
    "unreachable_without_steps_or_ramp": (lambda d: {**d, "steps": [], "ramps": []},
                                          "rooms[5]: room 'CorridorE' is not reachable from room 'Hall' through "
                                          "doors (a door between floor levels needs steps or a ramp in it)"),
}


@pytest.mark.parametrize("case", sorted(INVALID))
def test_invalid_levels_steps_and_ramps_are_refused(case):
    edit, expected = INVALID[case]
    with pytest.raises(LayoutError) as e:
        parse_layout(edit(copy.deepcopy(split_data())), "bad.yaml")
    assert str(e.value).startswith(f"layout bad.yaml: {expected}"), str(e.value)


@pytest.mark.parametrize("case", ["riser_too_high", "ramp_too_steep", "storey_change_below", "steps_in_no_door"])
def test_cli_exits_2_naming_the_field_and_writes_nothing(case, tmp_path):
    edit, expected = INVALID[case]
    src = tmp_path / "bad.yaml"
    src.write_text(yaml.safe_dump(edit(split_data()), sort_keys=False))
    out = tmp_path / "bad.ifc"
    r = subprocess.run([PYTHON, str(MAKE), str(src), "-o", str(out)], capture_output=True, text=True)
    assert r.returncode == 2 and f"layout bad.yaml: {expected.split(':')[0]}:" in r.stderr, r.stderr
    assert list(tmp_path.iterdir()) == [src]


def test_flights_between_storeys_keep_to_the_storeys_level():
    d = yaml.safe_load((ROOT / "bim" / "layouts" / "tower.yaml").read_text())
    st = next(rm for rm in d["storeys"][1]["rooms"] if rm["name"] == "1.ST")
    st["floor"] = 0.2   # the stairwell raised: the flight from the ground floor would arrive too low
    with pytest.raises(LayoutError, match=r"stairs\[0\]\.start: flight 'flight_0_1' arrives in room '1.ST', at a "
                       r"floor level of its own \(0.2 m\)"):
        parse_layout(d, "bad.yaml")


def test_one_level_layouts_take_floor_zero_and_doors_with_leaves():
    d = yaml.safe_load((ROOT / "bim" / "layouts" / "office.yaml").read_text())
    plain = parse_layout(copy.deepcopy(d), "o.yaml")
    for rm in d["rooms"]:
        rm["floor"] = 0.0
    for dr in d["doors"]:
        dr["leaf"] = True
    from is_graphs_bim.building_ifc import build_ifc
    assert build_ifc(parse_layout(d, "o.yaml")).to_string() == build_ifc(plain).to_string()


def _two_storeys_with_steps(flight_start):
    """split_two_rooms twice, 3.5 m apart, a flight between them starting at ``flight_start``."""
    d = yaml.safe_load((ROOT / "test" / "data" / "layouts" / "split_two_rooms.yaml").read_text())
    plan = {k: d.pop(k) for k in ("floor_slab", "ceiling_slab", "walls", "rooms", "doors", "steps")}
    d.pop("space_boundaries")
    d["storeys"] = [{"name": "G", "elevation": 0.0, **copy.deepcopy(plan)},
                    {"name": "F1", "elevation": 3.5, **copy.deepcopy(plan)}]
    d["stairs"] = [{"id": "steps", "storey": 0, "start": flight_start, "direction": [1, 0], "width": 0.8,
                    "risers": 20, "riser_height": 0.175, "tread": 0.18}]
    return d


def test_steps_on_the_storeys_of_a_multi_storey_layout():
    from is_graphs_bim.building_ifc import build_ifc
    f = build_ifc(parse_layout(_two_storeys_with_steps([0.8, 0.6]), "m.yaml"))
    ids = [e.GlobalId for e in f.by_type("IfcRoot")]
    assert len(ids) == len(set(ids))   # a flight between storeys may share its id with steps
    assert len(f.by_type("IfcStair")) == 3
    holes = [[o.RelatedOpeningElement.Name for o in s.HasOpenings] for s in f.by_type("IfcSlab")]
    assert holes == [[], ["steps opening"], [], ["steps stairwell", "steps opening"]]
    with pytest.raises(LayoutError, match=r"stairs\[0\]\.start: flight 'steps' overlaps 'steps' \(steps or ramp\) "
                       r"of storey 'G'"):
        parse_layout(_two_storeys_with_steps([1.2, 2.0]), "m.yaml")
