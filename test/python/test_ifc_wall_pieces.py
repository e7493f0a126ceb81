"""walls.wall_pieces on synthetic triangle meshes (no IFC file needed)."""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.realpath(__file__)))), "scripts"))
from is_graphs_bim import mesh, walls  # noqa: E402


def _box(lo, hi):
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    v = np.array([[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0],
                  [x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]], dtype=float)
    f = np.array([[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4],
                  [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]])
    return v, f


def _shape(boxes):
    vs, fs, base = [], [], 0
    for lo, hi in boxes:
        v, f = _box(lo, hi)
        vs.append(v)
        fs.append(f + base)
        base += len(v)
    return mesh.Shape(1, "IfcWall", np.vstack(vs), np.vstack(fs))


def _slatted(extra=()):
    """A 0.1 m thick, 2 m long, 2.5 m high screen: its skin plus 60 slats inside it (many
    vertical faces of their own, as Smiley West's mapped-brep privacy walls have)."""
    boxes = [((0.0, 0.0, 0.0), (0.1, 2.0, 2.5))]
    for k in range(60):
        y = 0.01 + k * 0.033
        boxes.append(((0.02, y, 0.05), (0.08, y + 0.012, 2.45)))
    return _shape(boxes + list(extra))


def test_a_straight_wall_with_many_inner_faces_is_one_piece():
    shape = _slatted()
    planes, vertical = walls.vertical_planes(shape)
    big = sorted(p.area for p in planes)[-2:]
    assert sum(big) < 0.4 * vertical      # the old rule alone rejected it as "curved?"
    pieces, problem = walls.wall_pieces(shape)
    assert problem is None and len(pieces) == 1
    p = pieces[0]
    assert abs(p.thickness - 0.1) < 1e-6 and abs(p.length - 2.0) < 1e-6


def test_geometry_outside_the_two_faces_still_rejects_it():
    shape = _slatted(extra=[((0.1, 0.5, 0.0), (0.6, 0.51, 2.5))])   # a fin 0.5 m out
    pieces, problem = walls.wall_pieces(shape)
    assert pieces == [] and "not made of straight pieces" in problem
