#!/usr/bin/env python3
"""Counts the test cases in catkin's JUnit XML results (each <testcase> once) and prints
"test: N passed, N failed, N skipped"; lists the failed ones with their messages and what the
failed test printed (the last lines: a CI log that shows only its tail still says why), and the
time each group of tests took (from the result files' own times). Exit 1 on a failure or no test.

  test_summary.py [RESULTS_DIR] [--wall SECONDS]   (--wall: the whole run, to show the rest)
"""
import argparse
import glob
import os
import re
import sys
import xml.etree.ElementTree as ET

# (group, pattern of the result file's name); the first that matches. rosunit-*.xml are the
# gtests inside a rostest: counted, their time is the rostest's.
GROUPS = [
    ("core gtests (no ROS)", r"^gtest-test_core\.xml$"),
    ("ROS conversion gtests", r"^gtest-"),
    ("BIM scripts, README (pytest)", r"^pytest-bim_scripts\.xml$"),
    ("scenario contracts, replay", r"^pytest-replay_contracts\.xml$"),
    ("scenarios live (rostest)", r"^rostest-test_ros_localize_"),
    ("deviations live (rostest)", r"^rostest-test_ros_deviations_"),
    ("faults live (rostest)", r"^rostest-test_ros_faults_"),
    ("nodes (rostest)", r"^rostest-"),
    ("rviz, make_bag (pytest)", r"^pytest-"),
]


def seconds(root):
    """The run time a result file states (a suite's time, else its suites' sum)."""
    if root.get("time"):
        return float(root.get("time"))
    return sum(float(s.get("time", 0) or 0) for s in root.iter("testsuite"))


def clip(text, width):
    text = " ".join(text.split())
    return text if len(text) <= width else text[:width - 3] + "..."


def describe(file_name, case_name, problem, root, max_lines=12):
    """A failed case: its message and the lines its test printed ("[ ... ]" lines of the file's
    system-out, where the rostest checkers write what they measured)."""
    lines = [f"--- {file_name}: {case_name}",
             "    " + clip(problem.get("message") or problem.text or "(no message)", 1200)]
    out = "\n".join(e.text or "" for e in root.iter("system-out"))
    said = [line for line in out.splitlines() if line.startswith("[ ")]
    lines += ["    " + clip(line, 900) for line in said[-max_lines:]]
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("results_dir", nargs="?", default=".ws/build/test_results")
    parser.add_argument("--wall", type=float, help="the whole run's wall seconds")
    args = parser.parse_args()
    passed, failed, skipped, details = 0, [], 0, []
    times = {g: [0, 0.0] for g, _ in GROUPS}
    for path in sorted(glob.glob(os.path.join(args.results_dir, "**", "*.xml"), recursive=True)):
        name = os.path.basename(path)
        try:
            root = ET.parse(path).getroot()
        except ET.ParseError as error:
            failed.append(f"{name}: unreadable result file ({error})")
            continue
        group = next((g for g, p in GROUPS if re.search(p, name)), None)
        if group:
            times[group][0] += 1
            times[group][1] += seconds(root)
        for case in root.iter("testcase"):
            case_name = f"{case.get('classname', '')}.{case.get('name', '')}"
            problem = case.find("failure")
            problem = case.find("error") if problem is None else problem
            if problem is not None:
                failed.append(f"{name}: {case_name}")
                details.append(describe(name, case_name, problem, root))
            elif case.find("skipped") is not None or case.get("status") == "notrun":
                skipped += 1
            else:
                passed += 1
    print(f"{'test group':34s} {'files':>5s} {'minutes':>8s}")
    total = 0.0
    for group, (files, secs) in times.items():
        if files:
            print(f"{group:34s} {files:5d} {secs / 60:8.1f}")
            total += secs
    if args.wall:
        print(f"{'the rest (builds, bags, catkin)':34s} {'':5s} {(args.wall - total) / 60:8.1f}")
        print(f"{'the whole run':34s} {'':5s} {args.wall / 60:8.1f}")
    for text in details:
        print(text)
    for line in failed:
        print(f"FAILED: {line}")
    print(f"test: {passed} passed, {len(failed)} failed, {skipped} skipped")
    return 1 if failed or passed + skipped == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
