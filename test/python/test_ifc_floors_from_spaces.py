"""Floors made from space footprints when a storey has no floor slab (issue 24, "IfcSlab missing").

A space that no IfcSlab or IfcCovering FLOORING covers (more than half its footprint, in plan,
within 0.5 m of its bottom; holes cut in the slab count as covered) gets its footprint,
triangulated and facing up at its bottom, in the mesh as `o FloorFromSpace#<space id>`; a
warning per storey names the storey and the count, and the report says it
(kept.floors_from_spaces). Files with slabs get no extra floor.
"""
import json
import os
import sys
from collections import defaultdict

import numpy as np
import pytest

from conftest import REPO

FIXTURES = [os.path.join(REPO, "test", "data", "two_rooms_mm_ifc2x3.ifc"),
            os.path.join(REPO, "bim", "office.ifc")]


def _convert(run_converter, path, out):
    proc = run_converter([path, "-o", out])
    assert proc.returncode == 0, proc.stderr
    with open(proc.stdout.strip().splitlines()[-1], encoding="utf-8") as fh:
        return json.load(fh), proc.stdout, proc.stderr


def _obj_objects(path):
    """{object name: (verts (N,3), faces (M,3) 0-based into verts)} of an OBJ."""
    verts, faces, names, cur = [], defaultdict(list), [], None
    with open(path, encoding="utf-8") as fh:
        for line in fh:
            if line.startswith("o "):
                cur = line[2:].strip()
                names.append(cur)
            elif line.startswith("v "):
                verts.append([float(x) for x in line.split()[1:4]])
            elif line.startswith("f "):
                faces[cur].append([int(i) - 1 for i in line.split()[1:4]])
    verts = np.array(verts)
    return {n: (verts, np.array(faces[n], dtype=int).reshape(-1, 3)) for n in names}


def _floor_objects(obj_path):
    return {int(n.split("#")[1]): vf for n, vf in _obj_objects(obj_path).items()
            if n.startswith("FloorFromSpace#")}


def _tri_areas_normals(verts, faces):
    a, b, c = (verts[faces[:, k]] for k in range(3))
    cross = np.cross(b - a, c - a)
    norm = np.linalg.norm(cross, axis=1)
    return 0.5 * norm, cross / norm[:, None], (a + b + c) / 3.0


def _space_floor_areas(path):
    """{space step id: (area of its downward floor faces, their z)} read with IfcOpenShell."""
    import ifcopenshell
    import ifcopenshell.geom
    import ifcopenshell.util.shape
    f = ifcopenshell.open(path)
    settings = ifcopenshell.geom.settings()
    settings.set("use-world-coords", True)
    out = {}
    for sp in f.by_type("IfcSpace"):
        shape = ifcopenshell.geom.create_shape(settings, sp)   # keep it: it owns the geometry
        g = shape.geometry
        v = np.asarray(ifcopenshell.util.shape.get_vertices(g), dtype=float).reshape(-1, 3)
        t = np.asarray(ifcopenshell.util.shape.get_faces(g), dtype=int).reshape(-1, 3)
        areas, normals, centres = _tri_areas_normals(v, t)
        down = normals[:, 2] < -0.9
        out[sp.id()] = (float(areas[down].sum()), float(centres[down, 2].min()))
    return out


def _without_slabs(src, dst):
    """Copies an IFC file without its IfcSlab entities (removed with IfcOpenShell)."""
    import ifcopenshell
    import ifcopenshell.api.root
    f = ifcopenshell.open(src)
    slabs = f.by_type("IfcSlab")
    assert slabs, f"{src} has no IfcSlab to remove"
    for s in slabs:
        ifcopenshell.api.root.remove_product(f, product=s)
    assert not f.by_type("IfcSlab")
    f.write(str(dst))
    return str(dst)


@pytest.mark.parametrize("src", FIXTURES, ids=os.path.basename)
def test_building_without_slabs_gets_floors_from_its_spaces(src, run_converter, tmp_path):
    path = _without_slabs(src, tmp_path / "no_slabs.ifc")
    g, out, err = _convert(run_converter, path, tmp_path / "m")
    floors = _floor_objects(str(tmp_path / "m.obj"))
    spaces = _space_floor_areas(path)
    rooms = {r["ifc_id"]: r for r in g["rooms"]}
    assert sorted(floors) == sorted(spaces) == sorted(rooms)
    total = 0.0
    for sid, (verts, faces) in floors.items():
        areas, normals, centres = _tri_areas_normals(verts, faces)
        area, z = spaces[sid]
        assert areas.sum() == pytest.approx(area, rel=0.01), rooms[sid]["name"]
        assert np.all(normals[:, 2] > 0.999), "floor triangles face up"
        used = verts[np.unique(faces)]
        assert np.allclose(used[:, 2], z, atol=1e-4), (rooms[sid]["name"], z)
        assert z == pytest.approx(rooms[sid]["z_min"], abs=1e-4)
        poly = np.array(rooms[sid]["polygon"])
        assert np.all(used[:, :2].min(axis=0) >= poly.min(axis=0) - 1e-4)
        assert np.all(used[:, :2].max(axis=0) <= poly.max(axis=0) + 1e-4)
        total += areas.sum()
    assert total == pytest.approx(sum(a for a, _ in spaces.values()), rel=0.01)
    by_storey = defaultdict(int)
    for r in g["rooms"]:
        by_storey[r["storey"]] += 1
    for rep, st in zip(g["report"], g["storeys"]):
        n = by_storey[st["id"]]
        assert rep["kept"]["floors_from_spaces"] == n
        if n:
            hits = [w for w in g["warnings"] if w.startswith(f"IfcBuildingStorey #{st['ifc_id']}: ")
                    and "no IfcSlab or IfcCovering FLOORING" in w]
            assert len(hits) == 1, g["warnings"]
            assert f"under {n} of its {n} space(s)" in hits[0]
            assert f"[GlobalId {st['guid']}]" in hits[0] and "FloorFromSpace" in hits[0]
            assert f"floors from spaces: {n}" in out
    assert "no IfcSlab or IfcCovering FLOORING" in err


@pytest.mark.parametrize("src", FIXTURES, ids=os.path.basename)
def test_file_with_slabs_gets_no_extra_floor(src, run_converter, tmp_path):
    g, out, err = _convert(run_converter, src, tmp_path / "m")
    assert not _floor_objects(str(tmp_path / "m.obj"))
    assert all(rep["kept"]["floors_from_spaces"] == 0 for rep in g["report"])
    assert not any("FloorFromSpace" in w for w in g["warnings"])
    assert "floors from spaces" not in out


def test_house_with_slab_or_floor_covering_gets_no_extra_floor(make_house, run_converter,
                                                               tmp_path):
    for k, kind in enumerate((True, "covering")):
        path, ids = make_house(name=f"h{k}.ifc", floor_slab=kind)
        g, _, _ = _convert(run_converter, path, tmp_path / f"h{k}")
        assert not _floor_objects(str(tmp_path / f"h{k}.obj")), kind
        assert g["report"][0]["kept"]["floors_from_spaces"] == 0
        assert f"IfcSlab#{ids['S_floor']}" in open(tmp_path / f"h{k}.obj").read() or \
            kind == "covering"


def test_only_the_uncovered_room_gets_a_floor(make_house, run_converter, tmp_path):
    """The slab lies under room A only: room B (x 4.1..7.8, y 0.2..3.8) gets a floor at z 0."""
    path, ids = make_house(floor_slab="A")
    g, _, _ = _convert(run_converter, path, tmp_path / "h")
    floors = _floor_objects(str(tmp_path / "h.obj"))
    assert sorted(floors) == [ids["space_B"]]
    verts, faces = floors[ids["space_B"]]
    areas, normals, _ = _tri_areas_normals(verts, faces)
    assert areas.sum() == pytest.approx(3.7 * 3.6, rel=1e-6)
    assert np.allclose(verts[np.unique(faces), 2], 0.0)
    assert g["report"][0]["kept"]["floors_from_spaces"] == 1
    assert any(w.startswith(f"IfcBuildingStorey #{ids['storey']}: storey 'EG' has no IfcSlab")
               and "under 1 of its 2 space(s)" in w for w in g["warnings"]), g["warnings"]


def test_space_without_footprint_on_a_storey_without_slab_is_named(make_house, run_converter,
                                                                   tmp_path):
    path, ids = make_house(floor_slab=False, extras=("space_no_body",))
    g, _, err = _convert(run_converter, path, tmp_path / "h")
    assert sorted(_floor_objects(str(tmp_path / "h.obj"))) == sorted(
        [ids["space_A"], ids["space_B"]])
    hits = [w for w in g["warnings"] if w.startswith(f"IfcSpace #{ids['space_no_body']}: ")
            and "no floor made from it" in w]
    assert len(hits) == 1, g["warnings"]
    assert g["report"][0]["kept"]["floors_from_spaces"] == 2


def test_hole_cut_in_the_slab_counts_as_covered(make_house, run_converter, tmp_path):
    """A stair hole (an IfcOpeningElement voiding the slab) over most of room B is part of the
    floor's design: no floor is made over it."""
    path, ids = make_house(floor_slab="hole")
    g, _, _ = _convert(run_converter, path, tmp_path / "h")
    objects = _obj_objects(str(tmp_path / "h.obj"))
    verts, faces = objects[f"IfcSlab#{ids['S_floor']}"]
    areas, normals, _ = _tri_areas_normals(verts, faces)
    assert areas[normals[:, 2] > 0.9].sum() == pytest.approx(8 * 4 - 9, rel=1e-3)  # hole cut
    assert not _floor_objects(str(tmp_path / "h.obj"))
    assert g["report"][0]["kept"]["floors_from_spaces"] == 0


def test_space_far_below_its_storey_gets_its_floor_at_the_storey_elevation(make_house,
                                                                           run_converter,
                                                                           tmp_path):
    """Space L's bottom (z -5) is more than 1 m below its storey (z 0): unusable, so its floor
    is made at the storey's elevation, and a warning names it."""
    path, ids = make_house(floor_slab=False, extras=("space_low",), storey_elevation=0.0)
    g, _, _ = _convert(run_converter, path, tmp_path / "h")
    floors = _floor_objects(str(tmp_path / "h.obj"))
    assert sorted(floors) == sorted([ids["space_A"], ids["space_B"], ids["space_low"]])
    verts, faces = floors[ids["space_low"]]
    assert np.allclose(verts[np.unique(faces), 2], 0.0)
    assert _tri_areas_normals(verts, faces)[0].sum() == pytest.approx(9.0, rel=1e-6)
    for sid in (ids["space_A"], ids["space_B"]):
        assert np.allclose(floors[sid][0][np.unique(floors[sid][1]), 2], 0.0)
    hits = [w for w in g["warnings"] if w.startswith(f"IfcSpace #{ids['space_low']}: ")
            and "unusable" in w and "z = 0.000 m" in w]
    assert len(hits) == 1, g["warnings"]
    assert any("under 3 of its 3 space(s)" in w for w in g["warnings"]), g["warnings"]


@pytest.mark.parametrize("ring, holes", [
    ([(0, 0), (4, 0), (4, 3), (0, 3)], []),                                      # a rectangle
    ([(0.2, 0.2), (3.9, 0.2), (3.9, 3.8), (0.6, 3.8), (0.6, 3.4), (0.2, 3.4)], []),  # a notch
    ([(0, 0), (6, 0), (6, 1), (1, 1), (1, 4), (6, 4), (6, 5), (0, 5)], []),      # a C
    ([(0, 0), (2, 0), (4, 0), (4, 4), (0, 4), (0, 2)], []),                      # collinear points
    ([(0, 0), (8, 0), (8, 6), (0, 6)], [[(2, 2), (3, 2), (3, 3), (2, 3)],        # two holes
                                        [(5, 1), (7, 1), (6, 4)]]),
])
def test_footprints_triangulate_without_shapely_2_1(monkeypatch, ring, holes):
    """Python 3.9 has shapely 2.0, without constrained_delaunay_triangles: the floors then come
    from ear clipping (holes cut open first), which must cover the footprint exactly."""
    sys.path.insert(0, os.path.join(REPO, "scripts"))
    import shapely
    from shapely.geometry import Polygon
    from is_graphs_bim import floors
    monkeypatch.delattr(shapely, "constrained_delaunay_triangles", raising=False)
    plan = Polygon(ring, holes)
    tris = list(floors._constrained_triangles(plan).geoms)
    assert all(len(t.exterior.coords) == 4 for t in tris)
    assert sum(t.area for t in tris) == pytest.approx(plan.area, rel=1e-9)
    assert shapely.union_all(tris).symmetric_difference(plan).area == pytest.approx(0, abs=1e-9)
    shape = floors.triangulate_footprint(np.array(ring, dtype=float), 1.5, 7) if not holes \
        else None
    if shape is not None:
        a, b, c = (shape.verts[shape.faces[:, k]] for k in range(3))
        up = np.cross(b - a, c - a)[:, 2]
        assert np.all(up > 0) and up.sum() / 2 == pytest.approx(plan.area, rel=1e-9)
        assert np.allclose(shape.verts[:, 2], 1.5)
