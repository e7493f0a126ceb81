#!/usr/bin/env python3
"""Writes IFC files of procedural buildings from plan layouts (YAML; format in bim/README.md).

A layout is one storey, or several (`storeys:`) joined by straight stair flights (`stairs:`).
Rooms of a storey may stand at floor levels of their own (`floor:`), joined by steps (`steps:`)
and ramps (`ramps:`) in doors or doorless openings between them.

  make_building.py LAYOUT.yaml -o OUT.ifc     one layout
  make_building.py --all                      bim/layouts/*.yaml -> bim/<stem>.ifc
  make_building.py --fixtures                 test/data/layouts/*.yaml -> test/data/<stem>.ifc
  make_building.py --all --check              only report stale or missing files (exit 1)

An invalid layout prints an error naming the file and the field and exits with status 2;
no output file is written (files are written to a temporary name and renamed). The output is
deterministic: the same layout gives a byte-identical IFC file. Test fixtures are deliberately
broken in places, so --fixtures (and --allow-invalid for one layout) turn the checks that would
refuse them (zero-size walls, doors with a room on one side only, unreachable rooms, no rooms)
into warnings; never use it for the buildings in bim/.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from is_graphs_bim.building_ifc import build_ifc, write_ifc  # noqa: E402
from is_graphs_bim.building_layout import LayoutError, load_layout  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
BIM_DIR = ROOT / "bim"
FIXTURE_DIR = ROOT / "test" / "data"


def _jobs(args) -> list[tuple[Path, Path, bool]]:
    """(layout, output, allow_invalid) for each file to make."""
    if args.all or args.fixtures:
        jobs = []
        if args.all:
            jobs += [(y, BIM_DIR / f"{y.stem}.ifc", False) for y in sorted((BIM_DIR / "layouts").glob("*.yaml"))]
        if args.fixtures:
            jobs += [(y, FIXTURE_DIR / f"{y.stem}.ifc", True)
                     for y in sorted((FIXTURE_DIR / "layouts").glob("*.yaml"))]
        return jobs
    return [(Path(args.layout), Path(args.output), args.allow_invalid)]


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("layout", nargs="?", help="layout YAML file")
    p.add_argument("-o", "--output", help="IFC file to write")
    p.add_argument("--all", action="store_true", help="make every bim/layouts/*.yaml into bim/")
    p.add_argument("--fixtures", action="store_true", help="make every test/data/layouts/*.yaml into test/data/")
    p.add_argument("--check", action="store_true", help="write nothing; exit 1 if an output is stale or missing")
    p.add_argument("--allow-invalid", action="store_true",
                   help="turn layout problems into warnings (test fixtures only)")
    args = p.parse_args(argv)
    if (args.all or args.fixtures) == bool(args.layout):
        p.error("give either one LAYOUT (with -o) or --all / --fixtures")
    if args.layout and not args.output:
        p.error("-o/--output is required with a LAYOUT")

    stale = 0
    for layout_path, out, allow_invalid in _jobs(args):
        try:
            lay = load_layout(layout_path, allow_invalid=allow_invalid)
        except LayoutError as e:
            print(f"make_building: error: {e}", file=sys.stderr)
            return 2
        for w in lay.warnings:
            print(f"make_building: warning: layout {layout_path.name}: {w}", file=sys.stderr)
        if args.check:
            same = out.is_file() and out.read_text(encoding="utf-8") == build_ifc(lay).to_string()
            if not same:
                print(f"make_building: stale or missing: {out} (from {layout_path})", file=sys.stderr)
                stale += 1
            continue
        write_ifc(lay, out)
        print(out)
    return 1 if stale else 0


if __name__ == "__main__":
    sys.exit(main())
