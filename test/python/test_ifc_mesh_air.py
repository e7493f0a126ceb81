"""Spatial elements and openings are air in the building mesh, with their IFC4 subtypes.

KIT-EDC_with_SB.ifc (IFC4) put an IfcExternalSpatialElement (a box around the whole site) and
every door's IfcOpeningStandardCase (a solid across the doorway) into the mesh: the simulated
robot could not walk through the doors, and its LiDAR would have seen the site box."""
import os
import sys

import pytest

from conftest import REPO, _convert_once

sys.path.insert(0, os.path.join(REPO, "scripts"))
from is_graphs_bim import mesh  # noqa: E402


def _objects(obj_path):
    with open(obj_path, encoding="utf-8") as fh:
        return [line[2:].split("#")[0] for line in fh if line.startswith("o ")]


def test_kit_mesh_has_no_site_box_and_no_opening_solids(tmp_path_factory):
    kit = _convert_once(tmp_path_factory, "KIT-EDC_with_SB.ifc")  # skips without ../shared/bim
    classes = set(_objects(kit.obj_path))
    assert "IfcExternalSpatialElement" not in classes
    assert "IfcOpeningStandardCase" not in classes
    assert "IfcOpeningElement" not in classes
    assert "IfcSpace" not in classes
    # The building itself is still there.
    assert {"IfcWallStandardCase", "IfcSlabStandardCase"} <= classes


def test_in_mesh_knows_the_subtypes():
    import ifcopenshell
    f4 = ifcopenshell.file(schema="IFC4")
    assert not mesh.in_mesh(f4.createIfcExternalSpatialElement())
    assert not mesh.in_mesh(f4.createIfcOpeningStandardCase())
    assert not mesh.in_mesh(f4.createIfcSpatialZone())
    assert not mesh.in_mesh(f4.createIfcVirtualElement())
    assert mesh.in_mesh(f4.createIfcWallStandardCase())
    f2 = ifcopenshell.file(schema="IFC2X3")
    assert not mesh.in_mesh(f2.createIfcSpace())  # IFC2X3 has no IfcSpatialElement
    assert not mesh.in_mesh(f2.createIfcOpeningElement())
    assert mesh.in_mesh(f2.createIfcWall())
