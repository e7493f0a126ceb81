#!/usr/bin/env python3
"""Runs one test suite of the package when the interpreters it needs have their modules, or
reports it skipped.

CMake's test targets call this (catkin_make run_tests, catkin build, colcon test), so that a
workspace built without `make setup` (no .venv: rosdep, catkin or colcon in the user's own
workspace) runs what it can and names what is missing instead of failing:

  run_pytest.py --python PY --needs pytest,yaml [--requires PY2=M1,M2]... --xml OUT.xml -- ARGS
  run_pytest.py --requires PY2=ifcopenshell [--xml OUT.xml] --command -- CMD ARGS...

When PY imports every module of --needs, and each PY2 of --requires every one of its modules
(IS_GRAPHS_PYTHON and IfcOpenShell: the tests that convert the project's IFC buildings), the
first form is `PY -m pytest ARGS --junit-xml=OUT.xml` and the second runs CMD ARGS (a rostest, or
make_bag for a test's bag), each with its exit code. Otherwise it prints which interpreter lacks
which modules, writes OUT.xml (when given) with one skipped test saying so (catkin_test_results
and the summary count it as skipped) and exits 0. Standard library only, Python 3.8+.
"""
import argparse
import os
import subprocess
import sys
from xml.sax.saxutils import quoteattr


def missing_modules(python, modules):
    """The modules of `modules` that `python` cannot import (all of them when it cannot run),
    found by one run of `python`."""
    if not (os.path.isfile(python) and os.access(python, os.X_OK)):
        return list(modules)
    probe = ("import importlib, sys\n"
             "for m in sys.argv[1:]:\n"
             "    try:\n"
             "        importlib.import_module(m)\n"
             "    except Exception:\n"
             "        print(m)\n")
    proc = subprocess.run([python, "-c", probe, *modules], stdout=subprocess.PIPE,
                          stderr=subprocess.DEVNULL, text=True)
    if proc.returncode != 0:
        return list(modules)
    return proc.stdout.split()


def write_skipped(xml, suite, message):
    os.makedirs(os.path.dirname(os.path.abspath(xml)), exist_ok=True)
    with open(xml, "w") as f:
        f.write('<?xml version="1.0" encoding="utf-8"?>\n'
                f'<testsuite name={quoteattr(suite)} tests="1" errors="0" failures="0" '
                'skipped="1">\n'
                f'  <testcase classname={quoteattr(suite)} name="interpreter">\n'
                f'    <skipped message={quoteattr(message)}/>\n'
                '  </testcase>\n</testsuite>\n')


def unmet(requirements):
    """'PY cannot import M1, M2' for each (python, modules) of `requirements` missing some."""
    lacks = []
    for python, modules in requirements:
        missing = missing_modules(python, modules)
        if missing:
            where = python if os.path.exists(python) else f"{python} (absent)"
            lacks.append(f"{where} cannot import {', '.join(missing)}")
    return lacks


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if "--" not in argv:
        print("run_pytest: usage: run_pytest.py --python PY --needs M1,M2 [--requires PY=M1,M2] "
              "--xml OUT -- ARGS, or run_pytest.py --requires PY=M1,M2 [--xml OUT] --command "
              "-- CMD ARGS", file=sys.stderr)
        return 2
    split = argv.index("--")
    parser = argparse.ArgumentParser(prog="run_pytest")
    parser.add_argument("--python", help="the interpreter that runs pytest")
    parser.add_argument("--needs", default="pytest", help="modules --python must import")
    parser.add_argument("--requires", action="append", default=[], metavar="PY=M1,M2",
                        help="another interpreter and the modules it must import (repeatable)")
    parser.add_argument("--command", action="store_true",
                        help="run the command after -- instead of pytest")
    parser.add_argument("--xml", help="the JUnit result file (required for pytest)")
    parser.add_argument("--suite", default=None, help="name in the report (default: the XML's)")
    args = parser.parse_args(argv[:split])
    rest = argv[split + 1:]
    if not args.command and not (args.python and args.xml):
        parser.error("pytest needs --python and --xml")
    if args.command and not rest:
        parser.error("--command needs a command after --")
    requirements = []
    if args.python:
        requirements.append((args.python, [m for m in args.needs.split(",") if m]))
    for spec in args.requires:
        python, _, modules = spec.rpartition("=")
        if not python:
            parser.error(f"--requires {spec}: expected PY=M1,M2")
        requirements.append((python, [m for m in modules.split(",") if m]))
    suite = args.suite or (os.path.splitext(os.path.basename(args.xml))[0] if args.xml
                           else os.path.basename(rest[0]))
    lacks = unmet(requirements)
    if lacks:
        message = (f"{suite} skipped: {'; '.join(lacks)}; `make setup` makes the project's .venv "
                   "with them (docs/platforms.md), or configure with "
                   "-DIS_GRAPHS_PYTHON=/path/to/python3")
        print(f"run_pytest: {message}")
        if args.xml:
            write_skipped(args.xml, suite, message)
        return 0
    if args.command:
        return subprocess.call(rest)
    return subprocess.call([args.python, "-m", "pytest", *rest, f"--junit-xml={args.xml}"])


if __name__ == "__main__":
    sys.exit(main())
