#!/usr/bin/env python3
"""Counts the test cases in catkin's JUnit XML results (each <testcase> once) and prints
"test: N passed, N failed, N skipped"; lists the failed ones. Exit 1 on a failure or no test."""
import glob
import os
import sys
import xml.etree.ElementTree as ET


def main(results_dir):
    passed, failed, skipped = 0, [], 0
    for path in sorted(glob.glob(os.path.join(results_dir, "**", "*.xml"), recursive=True)):
        try:
            root = ET.parse(path).getroot()
        except ET.ParseError as error:
            failed.append(f"{os.path.basename(path)}: unreadable result file ({error})")
            continue
        for case in root.iter("testcase"):
            name = f"{case.get('classname', '')}.{case.get('name', '')}"
            if case.find("failure") is not None or case.find("error") is not None:
                failed.append(f"{os.path.basename(path)}: {name}")
            elif case.find("skipped") is not None or case.get("status") == "notrun":
                skipped += 1
            else:
                passed += 1
    for line in failed:
        print(f"FAILED: {line}")
    print(f"test: {passed} passed, {len(failed)} failed, {skipped} skipped")
    return 1 if failed or passed + skipped == 0 else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else ".ws/build/test_results"))
