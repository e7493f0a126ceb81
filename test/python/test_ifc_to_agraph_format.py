"""Invariants of docs/agraph_format.md, checked on every converted model."""
import filecmp
import math

import numpy as np
import pytest

TOP_KEYS = ["format", "version", "source", "building", "mesh", "storeys", "wall_surfaces",
            "walls", "rooms", "doorways", "warnings", "report"]
FIELDS = {
    "storeys": {"id", "ifc_id", "guid", "name", "elevation", "height"},
    "wall_surfaces": {"id", "ifc_id", "guid", "wall", "storey", "normal", "d", "orientation",
                      "start", "end", "z_min", "z_max", "rooms"},
    "walls": {"id", "ifc_id", "guid", "name", "kind", "ifc_class", "storey", "surfaces",
              "thickness", "start", "center", "length", "height", "external"},
    "rooms": {"id", "ifc_id", "guid", "name", "long_name", "storey", "polygon", "z_min", "z_max",
              "floor_z", "floor_source", "center", "area", "surfaces", "walls", "doorways"},
    "doorways": {"id", "ifc_id", "guid", "name", "storey", "wall", "position", "width", "height",
                 "rooms", "kind"},
}


@pytest.fixture(params=["fzk", "duplex", "house", "columns"])
def graph(request, make_house, run_converter, tmp_path):
    if request.param in ("house", "columns"):
        path, _ = make_house(extras=("columns",) if request.param == "columns" else ())
        proc = run_converter([path, "-o", tmp_path / "house", "--quiet"])
        assert proc.returncode == 0, proc.stderr
        import json
        with open(proc.stdout.strip().splitlines()[-1]) as fh:
            return json.load(fh)
    return request.getfixturevalue(request.param).graph


def test_schema(graph):
    assert list(graph) == TOP_KEYS
    assert graph["format"] == "is_graphs.agraph" and graph["version"] == 1
    assert set(graph["source"]) == {"file", "sha256", "schema", "application", "length_unit_m",
                                    "converter_version"}
    for key, fields in FIELDS.items():
        for k, e in enumerate(graph[key]):
            assert set(e) == fields, key
            assert e["id"] == k
            assert isinstance(e["ifc_id"], int) and isinstance(e["guid"], str)


def test_report_counts_what_was_kept(graph):
    g = graph
    assert [r["storey"] for r in g["report"]] == [s["id"] for s in g["storeys"]]
    for r, s in zip(g["report"], g["storeys"]):
        k = s["id"]
        assert r["name"] == s["name"]
        kept = r["kept"]
        walls = [w for w in g["walls"] if w["kind"] != "flush_element"]   # walls proper
        flush = [w for w in g["walls"] if w["kind"] == "flush_element" and w["storey"] == k]
        assert kept["wall_pieces"] == sum(1 for w in walls if w["storey"] == k)
        assert kept["walls"] == len({w["ifc_id"] for w in walls if w["storey"] == k})
        assert kept["flush_elements"] == len({w["ifc_id"] for w in flush})
        assert kept["flush_surfaces"] == sum(1 for w in flush for s in w["surfaces"]
                                             if g["wall_surfaces"][s]["rooms"])
        assert kept["wall_surfaces"] == sum(1 for x in g["wall_surfaces"] if x["storey"] == k)
        assert kept["rooms"] == sum(1 for x in g["rooms"] if x["storey"] == k)
        assert kept["doorways"] == {kind: sum(1 for d in g["doorways"] if d["storey"] == k
                                              and d["kind"] == kind)
                                    for kind in ("door", "opening", "virtual")}
        for d in r["dropped"]:
            assert set(d) == {"ifc_class", "reason", "count"} and d["count"] >= 1
            assert d["ifc_class"].startswith("Ifc") and d["reason"]


def test_references_are_consistent(graph):
    g = graph
    ns = len(g["storeys"])
    for s in g["wall_surfaces"]:
        assert 0 <= s["storey"] < ns and g["walls"][s["wall"]]["ifc_id"] == s["ifc_id"]
        assert s["id"] in g["walls"][s["wall"]]["surfaces"]
        for r in s["rooms"]:
            assert s["id"] in g["rooms"][r]["surfaces"]
    for r in g["rooms"]:
        assert sorted({g["wall_surfaces"][s]["wall"] for s in r["surfaces"]}) == r["walls"]
        for d in r["doorways"]:
            assert r["id"] in g["doorways"][d]["rooms"]
    for d in g["doorways"]:
        assert 1 <= len(d["rooms"]) <= 2 and len(set(d["rooms"])) == len(d["rooms"])
        assert -1 <= d["wall"] < len(g["walls"])
        assert d["kind"] in ("door", "opening", "virtual")
        if d["kind"] == "virtual":
            assert d["wall"] == -1 and len(d["rooms"]) == 2
        for r in d["rooms"]:
            assert d["id"] in g["rooms"][r]["doorways"]


def test_surfaces(graph):
    c10 = math.cos(math.radians(10))
    for s in graph["wall_surfaces"]:
        n = np.array(s["normal"])
        assert np.linalg.norm(n) == pytest.approx(1.0, abs=1e-6) and n[2] == 0.0
        t = np.array([-n[1], n[0]])
        start, end = np.array(s["start"]), np.array(s["end"])
        assert (end - start) @ t > 0
        for p in (start, end):
            assert p @ n[:2] == pytest.approx(s["d"], abs=2e-3)
        want = "x" if abs(n[0]) >= c10 else "y" if abs(n[1]) >= c10 else "other"
        assert s["orientation"] == want
        assert s["z_max"] > s["z_min"]


def test_walls_normals_point_out_and_centre_between_faces(graph):
    for w in graph["walls"]:
        a, b = (graph["wall_surfaces"][s] for s in w["surfaces"])
        na, nb = np.array(a["normal"]), np.array(b["normal"])
        assert na @ nb < -0.99                                        # opposed
        c = np.array(w["center"])
        # The centre is inside the material: behind both faces, half the thickness deep.
        assert na @ c - a["d"] == pytest.approx(-w["thickness"] / 2, abs=2e-3)
        assert nb @ c - b["d"] == pytest.approx(-w["thickness"] / 2, abs=2e-3)
        # Each face lies beyond the other along its own normal: the normals point out.
        assert na @ np.r_[b["start"], 0.0] - a["d"] < 0 and nb @ np.r_[a["start"], 0.0] - b["d"] < 0
        ws = np.array(w["start"])
        assert ws[2] == pytest.approx(min(a["z_min"], b["z_min"]), abs=1e-6)
        assert w["thickness"] > 0 and w["length"] > w["thickness"] * 0.5 and w["height"] > 0


def test_rooms_polygons_ccw_and_surfaces_face_inside(graph):
    for r in graph["rooms"]:
        p = np.array(r["polygon"])
        assert len(p) >= 3 and not np.allclose(p[0], p[-1])
        x, y = p[:, 0], p[:, 1]
        area = 0.5 * (x @ np.roll(y, -1) - np.roll(x, -1) @ y)
        assert area > 0 and area == pytest.approx(r["area"], rel=1e-5)
        assert r["center"][2] == pytest.approx(0.5 * (r["z_min"] + r["z_max"]), abs=1e-6)
        for sid in r["surfaces"]:
            s = graph["wall_surfaces"][sid]
            n = np.array(s["normal"][:2])
            # The room's area centroid is on the side the surface's normal points to, for the
            # convex rooms (the L-shaped ones may have it elsewhere).
            hull_area = _convex_hull_area(p)
            if hull_area - area < 1e-6:
                assert n @ np.array(r["center"][:2]) - s["d"] > 0


def _convex_hull_area(p):
    pts = sorted(map(tuple, p))

    def half(points):
        h = []
        for q in points:
            while len(h) >= 2 and ((h[-1][0] - h[-2][0]) * (q[1] - h[-2][1])
                                   - (h[-1][1] - h[-2][1]) * (q[0] - h[-2][0])) <= 0:
                h.pop()
            h.append(q)
        return h
    hull = np.array(half(pts)[:-1] + half(pts[::-1])[:-1])
    x, y = hull[:, 0], hull[:, 1]
    return 0.5 * (x @ np.roll(y, -1) - np.roll(x, -1) @ y)


def test_fzk_conversion_is_deterministic(fzk, run_converter, tmp_path):
    proc = run_converter([fzk.src, "-o", tmp_path / "model", "--quiet"])
    assert proc.returncode == 0, proc.stderr
    assert filecmp.cmp(proc.stdout.strip(), fzk.json_path, shallow=False)
    assert filecmp.cmp(tmp_path / "model.obj", fzk.obj_path, shallow=False)
