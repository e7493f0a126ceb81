#!/usr/bin/env python3
"""Runs one pytest suite of the package with the interpreter it needs, or reports it skipped.

CMake's pytest targets call this (catkin_make run_tests, catkin build, colcon test), so that a
workspace built without `make setup` (no .venv: rosdep, catkin or colcon in the user's own
workspace) runs what it can and names what is missing instead of failing:

  run_pytest.py --python PY --needs pytest,ifcopenshell --xml OUT.xml -- PYTEST_ARGS...

When PY exists and imports every module of --needs, this is `PY -m pytest PYTEST_ARGS
--junit-xml=OUT.xml`, with its exit code. Otherwise it prints which interpreter lacks which
modules, writes OUT.xml with one skipped test saying so (catkin_test_results and the summary
count it as skipped) and exits 0. Standard library only, Python 3.8+.
"""
import argparse
import os
import subprocess
import sys
from xml.sax.saxutils import quoteattr


def missing_modules(python, modules):
    """The modules of `modules` that `python` cannot import (all of them when it cannot run)."""
    if not (os.path.isfile(python) and os.access(python, os.X_OK)):
        return list(modules)
    missing = []
    for m in modules:
        proc = subprocess.run([python, "-c", f"import {m}"], stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL)
        if proc.returncode != 0:
            missing.append(m)
    return missing


def write_skipped(xml, suite, message):
    os.makedirs(os.path.dirname(os.path.abspath(xml)), exist_ok=True)
    with open(xml, "w") as f:
        f.write('<?xml version="1.0" encoding="utf-8"?>\n'
                f'<testsuite name={quoteattr(suite)} tests="1" errors="0" failures="0" '
                'skipped="1">\n'
                f'  <testcase classname={quoteattr(suite)} name="interpreter">\n'
                f'    <skipped message={quoteattr(message)}/>\n'
                '  </testcase>\n</testsuite>\n')


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if "--" not in argv:
        print("run_pytest: usage: run_pytest.py --python PY --needs M1,M2 --xml OUT -- ARGS",
              file=sys.stderr)
        return 2
    split = argv.index("--")
    parser = argparse.ArgumentParser(prog="run_pytest")
    parser.add_argument("--python", required=True)
    parser.add_argument("--needs", default="pytest")
    parser.add_argument("--xml", required=True)
    parser.add_argument("--suite", default=None, help="name in the report (default: the XML's)")
    args = parser.parse_args(argv[:split])
    pytest_args = argv[split + 1:]
    modules = [m for m in args.needs.split(",") if m]
    suite = args.suite or os.path.splitext(os.path.basename(args.xml))[0]
    missing = missing_modules(args.python, modules)
    if missing:
        where = args.python if os.path.exists(args.python) else f"{args.python} (absent)"
        message = (f"{suite} skipped: {where} cannot import {', '.join(missing)}; `make setup` "
                   "makes the project's .venv with them (docs/platforms.md), or configure with "
                   "-DIS_GRAPHS_PYTHON=/path/to/python3")
        print(f"run_pytest: {message}")
        write_skipped(args.xml, suite, message)
        return 0
    cmd = [args.python, "-m", "pytest", *pytest_args, f"--junit-xml={args.xml}"]
    return subprocess.call(cmd)


if __name__ == "__main__":
    sys.exit(main())
