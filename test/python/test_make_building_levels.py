"""Split levels inside one storey: bim/layouts/split.yaml and test/data/layouts/split_two_rooms.yaml.

  * rooms at their own floor level (``floor:``), walls standing on the lowest floor they bound,
    door sills on the lower floor, doorless openings (``leaf: false``);
  * the IFC read back: a FLOOR slab at each level, each space's bottom at its room's floor, the
    steps' risers and the ramp's slope as laid out, the higher slab cut over them;
  * every invalid level, step or ramp refused naming the file and the field (exit 2, no file);
  * deterministic output; the converter sees every doorway, the one across the step included.
"""
from __future__ import annotations

import copy
import json
import math
import subprocess
import sys
from pathlib import Path

import ifcopenshell.util.element
import numpy as np
import pytest
import yaml

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))

from is_graphs_bim.building_ifc import build_ifc  # noqa: E402
from is_graphs_bim.building_layout import LayoutError, load_layout, parse_layout  # noqa: E402
from test_make_building import CONVERTER, MAKE, PYTHON, open_ifc, shapes  # noqa: E402

LOWER = {"CorridorE", "Workshop", "Store", "WC", "Studio"}


def split_data() -> dict:
    return yaml.safe_load((ROOT / "bim" / "layouts" / "split.yaml").read_text())


def by_name(f, cls):
    return {e.Name: e for e in f.by_type(cls)}


# --- the layout --------------------------------------------------------------------------------
def test_split_layout_levels_walls_and_sills():
    lay = load_layout(ROOT / "bim" / "layouts" / "split.yaml")
    assert 8 <= len(lay.rooms) <= 10 and lay.has_levels
    assert {r.name: r.floor for r in lay.rooms} == {r.name: (-0.45 if r.name in LOWER else 0.0) for r in lay.rooms}
    walls = {w.id: w for w in lay.walls}
    assert {w for w in walls if walls[w].bottom == -0.45} == {
        "ext_s_e", "ext_e", "ext_n_e", "cor_s_e", "cor_n_e", "split_s", "split_c", "split_n", "p_ws", "p_wc"}
    assert all(w.bottom == 0.0 for w in lay.walls if w.id.endswith("_w") or w.id in ("p_hall", "p_study"))
    doors = {d.id: d for d in lay.doors}
    assert doors["d_steps"].sill == doors["d_ramp"].sill == doors["d_east"].sill == -0.45
    assert doors["d_hall"].sill == doors["d_entrance"].sill == 0.0
    assert not doors["d_ramp"].leaf and all(d.leaf for d in lay.doors if d.id != "d_ramp")
    (st,) = lay.steps
    assert (st.risers, st.riser_height, st.tread, st.base, st.door) == (3, 0.15, 0.3, -0.45, "d_steps")
    (rp,) = lay.ramps
    assert (rp.length, rp.rise, rp.base, rp.door) == (3.5, 0.45, -0.45, "d_ramp")
    assert rp.slope_deg == pytest.approx(math.degrees(math.atan(0.45 / 3.5))) and rp.slope_deg <= 8.0
    # the two halves are no mirror images: no room area repeats
    areas = [round(r.area, 6) for r in lay.rooms]
    assert len(set(areas)) == len(areas)


def test_steps_and_ramp_are_the_links_across_the_step():
    d = split_data()
    without_steps = {**copy.deepcopy(d), "steps": []}
    parse_layout(without_steps, "s.yaml")               # the ramp alone still joins the halves
    with pytest.raises(LayoutError, match=r"rooms\[5\]: room 'CorridorE' is not reachable from room 'Hall' "
                       r"through doors \(a door between floor levels needs steps or a ramp in it\)"):
        parse_layout({**without_steps, "ramps": []}, "s.yaml")


# --- the IFC -----------------------------------------------------------------------------------
def test_floor_slab_at_each_level_spaces_at_their_floors():
    f = open_ifc("split")
    lay = load_layout(ROOT / "bim" / "layouts" / "split.yaml")
    slabs = [s for s in f.by_type("IfcSlab") if s.PredefinedType == "FLOOR"]
    assert sorted(s.Name for s in slabs) == ["Floor slab", "Floor slab -0.45 m"]
    got = shapes(f, slabs)
    for s in slabs:
        level = -0.45 if "-0.45" in s.Name else 0.0
        v = got[s.id()][0]
        assert v[:, 2].max() == pytest.approx(level) and v[:, 2].min() == pytest.approx(level - 0.25)
        # the pieces meet at the split walls' west face (x 10.9): the lower floor runs under the
        # walls between the levels and through their doorways, the higher one stops at its face
        assert (v[:, 0].max() if level == 0 else v[:, 0].min()) == pytest.approx(10.9)
        assert v[:, 1].min() == pytest.approx(-0.15) and v[:, 1].max() == pytest.approx(14.15)
        assert ifcopenshell.util.element.get_container(s).is_a("IfcBuildingStorey")
        # one body item per room on that level; the higher slab is cut over the steps and the ramp
        assert len(s.Representation.Representations[0].Items) == sum(r.floor == level for r in lay.rooms)
        holes = sorted(rel.RelatedOpeningElement.Name for rel in s.HasOpenings)
        assert holes == ([] if level else ["ramp_l opening", "steps_c opening"])
    spaces = by_name(f, "IfcSpace")
    got = shapes(f, spaces.values())
    for rm in lay.rooms:
        v = got[spaces[rm.name].id()][0]
        assert v[:, 2].min() == pytest.approx(rm.floor) and v[:, 2].max() == pytest.approx(2.8)
        assert spaces[rm.name].ObjectPlacement.RelativePlacement.Location.Coordinates[2] == pytest.approx(rm.floor)


def test_walls_stand_on_the_lower_floor_and_doors_on_it():
    f = open_ifc("split")
    walls = by_name(f, "IfcWall")
    got = shapes(f, walls.values())
    for name, bottom in (("split_c", -0.45), ("ext_e", -0.45), ("ext_w", 0.0), ("cor_s_w", 0.0)):
        v = got[walls[name].id()][0]
        assert (v[:, 2].min(), v[:, 2].max()) == pytest.approx((bottom, 2.8)), name
    openings = by_name(f, "IfcOpeningElement")
    got = shapes(f, [openings["d_steps opening"], openings["d_ramp"], openings["d_hall opening"]])
    assert got[openings["d_steps opening"].id()][0][:, 2].min() == pytest.approx(-0.45)
    assert got[openings["d_hall opening"].id()][0][:, 2].min() == pytest.approx(0.0)
    ramp_hole = openings["d_ramp"]   # doorless: named as the layout's door, filled by nothing
    assert not ramp_hole.HasFillings and ramp_hole.VoidsElements[0].RelatingBuildingElement.Name == "split_n"
    assert got[ramp_hole.id()][0][:, 2].min() == pytest.approx(-0.45)
    assert "d_ramp" not in by_name(f, "IfcDoor")


def test_steps_risers_and_ramp_slope_as_laid_out():
    f = open_ifc("split")
    (stair,) = f.by_type("IfcStair")
    (fl,) = f.by_type("IfcStairFlight")
    assert (stair.Name, stair.PredefinedType, fl.PredefinedType) == ("steps_c", "STRAIGHT_RUN_STAIR", "STRAIGHT")
    assert (fl.NumberOfRisers, fl.NumberOfTreads, fl.RiserHeight, fl.TreadLength) == (3, 2, 0.15, 0.3)
    v, tris = shapes(f, [fl])[fl.id()]
    up = _up_faces(v, tris)
    assert sorted({round(z, 6) for z, _ in up}) == [-0.3, -0.15]   # two treads above the lower floor
    assert v[:, 2].min() == pytest.approx(-0.45)                      # solid down to it
    assert v[:, 0].min() == pytest.approx(10.3) and v[:, 0].max() == pytest.approx(10.9)
    (ramp,) = f.by_type("IfcRamp")
    (rf,) = f.by_type("IfcRampFlight")
    assert (ramp.PredefinedType, rf.PredefinedType) == ("STRAIGHT_RUN_RAMP", "STRAIGHT")
    assert ifcopenshell.util.element.get_aggregate(rf) == ramp
    v, tris = shapes(f, [rf])[rf.id()]
    n = np.cross(v[tris[:, 1]] - v[tris[:, 0]], v[tris[:, 2]] - v[tris[:, 0]])
    n = n / np.linalg.norm(n, axis=1)[:, None]
    slopes = {round(math.degrees(math.acos(min(1.0, nz))), 4) for nz in n[:, 2] if 0.5 < nz < 0.9999}
    assert slopes == {round(math.degrees(math.atan(0.45 / 3.5)), 4)}
    assert (v[:, 2].min(), v[:, 2].max()) == pytest.approx((-0.45, 0.0))
    slope = ifcopenshell.util.element.get_pset(rf, "Pset_RampFlightCommon")["Slope"]
    assert slope == pytest.approx(math.atan(0.45 / 3.5))   # radians, the file's angle unit
    for e in (stair, ramp):
        assert ifcopenshell.util.element.get_container(e).is_a("IfcBuildingStorey")


def _up_faces(v, tris):
    """(z, area) of the triangles facing straight up."""
    out = []
    for t in tris:
        p = v[t]
        n = np.cross(p[1] - p[0], p[2] - p[0])
        if n[2] > 0 and abs(n[0]) + abs(n[1]) < 1e-9:
            out.append((float(p[0, 2]), 0.5 * float(n[2])))
    return out


def test_fixture_two_rooms_with_three_steps():
    lay = load_layout(ROOT / "test" / "data" / "layouts" / "split_two_rooms.yaml")
    assert [(r.name, r.floor) for r in lay.rooms] == [("Upper", 0.0), ("Lower", -0.45)]
    f = open_ifc("split_two_rooms")
    (fl,) = f.by_type("IfcStairFlight")
    assert (fl.NumberOfRisers, fl.RiserHeight) == (3, 0.15)
    assert sorted(s.Name for s in f.by_type("IfcSlab")) == ["Floor slab", "Floor slab -0.45 m"]
    # space boundaries in each space's own frame (z = 0 at its floor): the door's sill is on the
    # lower floor, so in Upper's boundary the door runs from its floor up to 2.1 - 0.45 m
    heights = {}
    for b in f.by_type("IfcRelSpaceBoundary"):
        if b.RelatedBuildingElement.Name == "d_step":
            zs = [p.Coordinates[1] for p in b.ConnectionGeometry.SurfaceOnRelatingElement.OuterBoundary.Points]
            heights[b.RelatingSpace.Name] = (min(zs), max(zs))
    assert heights == {"Upper": pytest.approx((0.0, 1.65)), "Lower": pytest.approx((0.0, 2.1))}


@pytest.mark.parametrize("name", ["split", "split_two_rooms"])
def test_converter_sees_every_doorway_and_the_room_floors(name, tmp_path):
    if not CONVERTER.is_file():
        pytest.skip("scripts/ifc_to_agraph.py missing")
    path = ROOT / ("bim" if name == "split" else "test/data") / f"{name}.ifc"
    r = subprocess.run([PYTHON, str(CONVERTER), str(path), "-o", str(tmp_path / name)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    a = json.loads(Path(r.stdout.strip().splitlines()[-1]).read_text())
    lay = load_layout(ROOT / ("bim/layouts" if name == "split" else "test/data/layouts") / f"{name}.yaml")
    rooms = [room["name"] for room in a["rooms"]]
    got = {d["name"]: sorted(rooms[i] for i in d["rooms"]) for d in a["doorways"]}
    assert got == {d.id: sorted(d.rooms) for d in lay.doors}


# --- determinism -------------------------------------------------------------------------------
def test_split_output_is_deterministic(tmp_path):
    text = build_ifc(load_layout(ROOT / "bim" / "layouts" / "split.yaml")).to_string()
    assert text == build_ifc(load_layout(ROOT / "bim" / "layouts" / "split.yaml")).to_string()
    out = tmp_path / "split.ifc"
    r = subprocess.run([PYTHON, str(MAKE), str(ROOT / "bim/layouts/split.yaml"), "-o", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert out.read_bytes() == (ROOT / "bim" / "split.ifc").read_bytes()


def test_ifc2x3_in_millimetres_writes_steps_and_ramp():
    d = {**split_data(), "schema": "IFC2X3", "units": "mm"}
    f = build_ifc(parse_layout(d, "s.yaml"))
    (ramp,), (rf,), (fl,) = f.by_type("IfcRamp"), f.by_type("IfcRampFlight"), f.by_type("IfcStairFlight")
    assert ramp.ShapeType == "STRAIGHT_RUN_RAMP" and (fl.NumberOfRiser, fl.RiserHeight) == (3, 150.0)
    v = shapes(f, [rf])[rf.id()][0]
    assert (v[:, 2].min(), v[:, 2].max()) == pytest.approx((-0.45, 0.0))   # world coordinates in metres
