#!/usr/bin/env python3
"""Converts an IFC building model into an A-Graph (docs/agraph_format.md) and a triangle mesh.

  ifc_to_agraph.py INPUT.ifc -o OUT_PREFIX        writes OUT_PREFIX.agraph.json and OUT_PREFIX.obj
  ifc_to_agraph.py INPUT.ifc --cache-dir DIR      converts once per IFC content, reuses after

The last line on stdout is the absolute path of the .agraph.json. Warnings go to stderr as
`ifc_to_agraph: warning: <file>: <IfcClass> #<id>: <what>`; fatal problems as
`ifc_to_agraph: error: <file>: ...` with exit status 2 (a path that is not a readable file:
`ifc_to_agraph: error: <what>: <path>`). Before IfcOpenShell reads the file, every `#N` it
references must be defined: dangling references that touch walls, spaces, storeys, doors or their
placements and geometry are an error (--allow-dangling: a warning), others a warning.
"""
import argparse
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

try:
    import ifcopenshell  # noqa: F401
except ImportError:
    # Started with a Python that lacks IfcOpenShell: use the project's venv (scripts/setup.sh).
    VENV_PY = os.path.join(os.path.dirname(HERE), ".venv", "bin", "python3")
    VENV = os.path.dirname(os.path.dirname(VENV_PY))
    if os.path.exists(VENV_PY) and os.path.realpath(sys.prefix) != os.path.realpath(VENV) \
            and not os.environ.get("IS_GRAPHS_NO_REEXEC"):
        os.environ["IS_GRAPHS_NO_REEXEC"] = "1"
        os.execv(VENV_PY, [VENV_PY, os.path.abspath(__file__)] + sys.argv[1:])
    print("ifc_to_agraph: error: IfcOpenShell is not installed for this Python; run "
          "scripts/setup.sh (it creates .venv with it)", file=sys.stderr)
    sys.exit(2)

from is_graphs_bim import agraph_writer, cache, converter, ifc_model, integrity  # noqa: E402

PROG = ifc_model.PROG


def _parse_args(argv):
    p = argparse.ArgumentParser(prog=PROG, description=__doc__.split("\n\n")[0])
    p.add_argument("input", help="IFC file (IFC2X3 or IFC4, STEP physical file)")
    out = p.add_mutually_exclusive_group(required=True)
    out.add_argument("-o", dest="out_prefix", metavar="OUT_PREFIX",
                     help="write OUT_PREFIX.agraph.json and OUT_PREFIX.obj")
    out.add_argument("--cache-dir", metavar="DIR",
                     help="keep results in DIR keyed by the IFC's sha256; reuse them")
    p.add_argument("--quiet", action="store_true", help="no per-storey summary")
    p.add_argument("--allow-dangling", action="store_true",
                   help="convert a file whose references to missing entities touch walls, "
                        "spaces, storeys or doors (a warning instead of an error)")
    return p.parse_args(argv)


def _report(json_path, quiet, warnings_from_cache=False):
    with open(json_path, encoding="utf-8") as fh:
        graph = json.load(fh)
    if warnings_from_cache:
        for w in graph["warnings"]:
            print(f"{PROG}: warning: {graph['source']['file']}: {w}", file=sys.stderr)
    if not quiet:
        for line in agraph_writer.summary_lines(graph):
            print(line)
    print(json_path)


def main(argv=None):
    args = _parse_args(argv)
    name = os.path.basename(args.input)
    diag = ifc_model.Diagnostics(name)

    def convert_into(prefix):
        result = converter.convert(args.input, diag, args.allow_dangling)
        return agraph_writer.write(result, prefix)

    try:
        try:
            integrity.check_path(args.input)    # before the cache reads it, or the output
        except integrity.PathError as exc:
            raise ifc_model.ConversionError(str(exc), names_path=True) from None
        if args.cache_dir:
            json_path, hit = cache.lookup(args.cache_dir, args.input)
            if hit:
                _report(json_path, args.quiet, warnings_from_cache=True)
                return 0
            json_path = cache.store(args.cache_dir, args.input, convert_into)
        else:
            json_path = convert_into(args.out_prefix)
    except ifc_model.ConversionError as exc:
        print(exc.line(name), file=sys.stderr)
        return 2
    except OSError as exc:
        where = args.out_prefix or args.cache_dir
        why = exc.strerror or str(exc)
        if exc.filename and os.path.abspath(exc.filename) != os.path.abspath(where):
            why = f"{exc.filename}: {why}"
        print(f"{PROG}: error: {name}: cannot write the output {where}: {why}", file=sys.stderr)
        return 2
    except MemoryError:
        print(f"{PROG}: error: {name}: out of memory", file=sys.stderr)
        return 2
    except Exception as exc:  # malformed input the checks above did not catch
        if os.environ.get("IS_GRAPHS_DEBUG"):
            raise
        print(f"{PROG}: error: {name}: cannot convert this model ({type(exc).__name__}: {exc}); "
              "the file may be damaged (set IS_GRAPHS_DEBUG=1 for details)", file=sys.stderr)
        return 2
    _report(json_path, args.quiet)
    return 0


if __name__ == "__main__":
    sys.exit(main())
