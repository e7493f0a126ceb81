#!/usr/bin/env python3
"""Checks that every dependency key of package.xml resolves with rosdep on the platforms the
project supports (ubuntu focal, ubuntu jammy, debian bookworm).

Without a rosdistro tree it checks package.xml against the facts file (test/data/rosdep_keys.yaml):
every key is either a system key recorded there with a package list on each platform, or a ROS
package of the distribution listed there. A platform that ros/rosdistro leaves unresolved must be
filled by the project's own rosdep source (scripts/rosdep_bookworm.yaml), and that file must
give what the facts say. With --rosdistro DIR (a checkout or an extract of ros/rosdistro holding
rosdep/*.yaml and <distro>/distribution.yaml) it also checks the facts against the real rules,
resolved the way rosdep resolves them, and prints every mismatch.

    scripts/check_rosdep_keys.py [--package-xml FILE] [--facts FILE] [--rosdistro DIR]

Exit status: 0 when everything resolves (and agrees), 1 on any problem, 2 on unreadable input.
Needs only the standard library and PyYAML: no ROS, no rosdep, no network.
"""
import argparse
import os
import sys
import xml.etree.ElementTree as ET

import yaml

REPO = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
DEFAULT_FACTS = os.path.join(REPO, "test", "data", "rosdep_keys.yaml")
DEFAULT_PACKAGE_XML = os.path.join(REPO, "package.xml")

# Every tag of package formats 1-3 that names a rosdep key.
DEPENDENCY_TAGS = ("buildtool_depend", "buildtool_export_depend", "build_depend",
                   "build_export_depend", "depend", "exec_depend", "run_depend", "test_depend",
                   "doc_depend")
# Under an OS, rosdep first reads a key as a package manager, and only then as an OS version.
INSTALLERS = ("apt", "pip", "gem", "npm", "source")
DEFAULT_INSTALLER = "apt"  # debian and ubuntu
# The generic rosdep sources of ros/rosdistro's rosdep/sources.list.d/20-default.list, in order.
ROSDEP_FILES = ("base.yaml", "python.yaml", "ruby.yaml")


class InputError(Exception):
    """A file that cannot be read or has not the expected shape."""


def load_yaml(path):
    loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
    try:
        with open(path, encoding="utf-8") as f:
            return yaml.load(f, Loader=loader)
    except (OSError, yaml.YAMLError) as e:
        raise InputError(f"cannot read {path}: {e}") from e


def package_keys(path):
    """The dependency keys of a package.xml: {key: [tags naming it]}, in document order."""
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as e:
        raise InputError(f"cannot read {path}: {e}") from e
    if root.tag != "package":
        raise InputError(f"{path}: the root element is <{root.tag}>, not <package>")
    keys = {}
    for element in root:
        if element.tag in DEPENDENCY_TAGS:
            key = (element.text or "").strip()
            if not key:
                raise InputError(f"{path}: an empty <{element.tag}>")
            keys.setdefault(key, []).append(element.tag)
    return keys


def split_platform(platform):
    os_name, sep, os_version = platform.partition(":")
    if not sep or not os_name or not os_version:
        raise InputError(f"platform {platform!r} is not OS:VERSION (e.g. ubuntu:focal)")
    return os_name, os_version


def _pick_installer(data):
    for installer in INSTALLERS:
        if installer in data:
            return installer, data[installer]
    return None


def resolve(rule, platform):
    """What rosdep installs for one key's rule on `platform` ("ubuntu:focal"), by the rules of
    REP 111 as rosdep applies them: the OS (or the `*` wildcard OS, which must name a package
    manager), then a package manager or an OS version (an exact version first, then `*`; a
    version mapped to null is "not available"). Returns the list of packages (apt ones by name,
    others as "pip:NAME"), or None when rosdep finds no definition or one marked unavailable.
    An empty list is returned as it is (rosdep accepts it and installs nothing)."""
    os_name, os_version = split_platform(platform)
    if not isinstance(rule, dict):
        return None
    if os_name in rule:
        data = rule[os_name]
    elif "*" in rule:
        data = rule["*"]
    else:
        return None
    installer = DEFAULT_INSTALLER
    if isinstance(data, dict):
        picked = _pick_installer(data)
        if picked:
            installer, data = picked
        else:
            if os_version in data:
                data = data[os_version]
            elif "*" in data:
                data = data["*"]
            else:
                return None
            if isinstance(data, dict):
                picked = _pick_installer(data)
                if picked:
                    installer, data = picked
    if isinstance(data, dict):  # installer arguments: {packages: [...]}
        data = data.get("packages")
    if data is None:
        return None
    if isinstance(data, str):
        data = data.split()
    if not isinstance(data, list) or not all(isinstance(p, str) for p in data):
        return None
    return [p if installer == DEFAULT_INSTALLER else f"{installer}:{p}" for p in data]


def load_rosdep_sources(paths):
    """Merges rosdep source files as rosdep does: per key and OS, the first file that defines
    the OS wins. Returns {key: {"rule": {os: rule}, "origin": {os: file name}}}."""
    db = {}
    for path in paths:
        data = load_yaml(path)
        if not isinstance(data, dict):
            raise InputError(f"{path}: not a mapping of rosdep keys")
        for key, rule in data.items():
            if not isinstance(rule, dict):
                continue
            entry = db.setdefault(key, {"rule": {}, "origin": {}})
            for os_name, os_rule in rule.items():
                if os_name not in entry["rule"]:
                    entry["rule"][os_name] = os_rule
                    entry["origin"][os_name] = os.path.basename(path)
    return db


def distribution_packages(path):
    """The released package names of a rosdistro distribution.yaml (REP 143): a repository's
    release.packages, or the repository's own name when it lists none."""
    data = load_yaml(path)
    if not isinstance(data, dict) or not isinstance(data.get("repositories"), dict):
        raise InputError(f"{path}: no repositories (is it a distribution.yaml?)")
    packages = set()
    for name, repository in data["repositories"].items():
        release = (repository or {}).get("release")
        if isinstance(release, dict):
            packages.update(release.get("packages") or [name])
    return packages


def _facts_sections(facts):
    if not isinstance(facts, dict):
        raise InputError("the facts file is not a mapping")
    platforms = facts.get("platforms")
    system = facts.get("system_keys")
    ros = facts.get("ros_packages")
    if not isinstance(platforms, list) or not platforms:
        raise InputError("the facts file has no platforms list")
    for platform in platforms:
        split_platform(platform)
    if not isinstance(system, dict) or not isinstance(ros, list):
        raise InputError("the facts file needs system_keys (a mapping) and ros_packages (a list)")
    return platforms, system, ros


def _show(packages):
    return "null (no definition)" if packages is None else "[" + ", ".join(packages) + "]"


def check_package(keys, facts, repo=REPO, label="package.xml"):
    """Checks package.xml's keys against the facts. Returns (problems, notes): a problem is a key
    that does not resolve on a platform; a note, a platform filled by the project's source."""
    platforms, system, ros = _facts_sections(facts)
    problems, notes = [], []
    source_rel = facts.get("project_source")
    source_db = None
    if source_rel:
        source_db = load_rosdep_sources([os.path.join(repo, source_rel)])

    for key, tags in keys.items():
        where = f"{label}: <{tags[0]}>{key}</{tags[0]}>"
        if key in ros and key in system:
            problems.append(f"{where}: the facts list it both as a ROS package and a system key")
        elif key in ros:
            continue
        elif key not in system:
            problems.append(f"{where}: not a rosdep key the facts know (neither a system key of "
                            f"rosdep/*.yaml nor a ROS package of {facts.get('ros_distro', '?')}): "
                            "rosdep install stops on it")
            continue
        entry = system[key] or {}
        filled = entry.get("project_source") or {}
        for platform in platforms:
            if platform not in entry:
                problems.append(f"{where}: the facts give no resolution on {platform}")
                continue
            if entry[platform]:
                continue
            if not filled.get(platform):
                problems.append(f"{where}: does not resolve on {platform} "
                                f"(rosdistro gives {_show(entry[platform])})")
                continue
            if source_db is None:
                problems.append(f"{where}: on {platform} the facts rely on a project source, "
                                "but name none (project_source)")
                continue
            got = resolve(source_db.get(key, {}).get("rule"), platform)
            if got != filled[platform]:
                problems.append(f"{where}: on {platform} {source_rel} gives {_show(got)}, the "
                                f"facts say {_show(filled[platform])}")
            else:
                notes.append(f"{key} on {platform}: not in rosdistro; {source_rel} gives "
                             f"{_show(got)}")

    for key in sorted(set(system) | set(ros)):
        if key not in keys:
            problems.append(f"facts: {key} is not a key of {label} (stale entry)")
    if source_db is not None:
        for key in sorted(source_db):
            if not (system.get(key) or {}).get("project_source"):
                problems.append(f"{source_rel}: defines {key}, which the facts do not record as "
                                "filled by it")
    return problems, notes


def check_against_rosdistro(facts, rosdistro_dir):
    """Compares the facts with a ros/rosdistro tree. Returns the list of mismatches."""
    platforms, system, ros = _facts_sections(facts)
    rosdep_dir = os.path.join(rosdistro_dir, "rosdep")
    paths = [os.path.join(rosdep_dir, name) for name in ROSDEP_FILES]
    missing = [p for p in paths if not os.path.isfile(p)]
    if missing:
        raise InputError(f"{rosdistro_dir} is not a rosdistro tree: no {', '.join(missing)}")
    db = load_rosdep_sources(paths)
    mismatches = []
    for key in sorted(system):
        entry = system[key] or {}
        if key not in db:
            mismatches.append(f"{key}: no such key in {', '.join(ROSDEP_FILES)}")
            continue
        origins = sorted(set(db[key]["origin"].values()))
        if entry.get("file") not in origins:
            mismatches.append(f"{key}: the facts say it is in {entry.get('file')}, rosdistro has "
                              f"it in {', '.join(origins)}")
        for platform in platforms:
            got = resolve(db[key]["rule"], platform)
            want = entry.get(platform)
            if got != want:
                hint = ""
                if got and (entry.get("project_source") or {}).get(platform):
                    hint = " (rosdistro resolves it now: the project's own rule can go)"
                mismatches.append(f"{key} on {platform}: rosdistro gives {_show(got)}, the facts "
                                  f"say {_show(want)}{hint}")
    distro = facts.get("ros_distro")
    if not distro:
        raise InputError("the facts file names no ros_distro")
    released = distribution_packages(os.path.join(rosdistro_dir, distro, "distribution.yaml"))
    for key in sorted(ros):
        if key not in released:
            mismatches.append(f"{key}: not a released package of {distro}/distribution.yaml")
        if key in db:
            mismatches.append(f"{key}: listed as a ROS package, but rosdep/*.yaml defines it too")
    return mismatches


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--package-xml", default=DEFAULT_PACKAGE_XML)
    parser.add_argument("--facts", default=DEFAULT_FACTS)
    parser.add_argument("--rosdistro", metavar="DIR",
                        help="a ros/rosdistro tree to check the facts against")
    args = parser.parse_args(argv)
    try:
        facts = load_yaml(args.facts)
        keys = package_keys(args.package_xml)
        problems, notes = check_package(keys, facts, label=os.path.relpath(args.package_xml))
        mismatches = []
        if args.rosdistro:
            mismatches = check_against_rosdistro(facts, args.rosdistro)
    except InputError as e:
        print(f"check_rosdep_keys: {e}", file=sys.stderr)
        return 2
    platforms = ", ".join(facts["platforms"])
    for note in notes:
        print(f"note: {note}")
    for problem in problems:
        print(f"error: {problem}")
    for mismatch in mismatches:
        print(f"mismatch: {mismatch}")
    n_system = sum(1 for k in keys if k in facts["system_keys"])
    n_ros = sum(1 for k in keys if k in facts["ros_packages"])
    print(f"check_rosdep_keys: {len(keys)} keys in {args.package_xml} ({n_system} system keys, "
          f"{n_ros} ROS packages); {len(problems)} problems on {platforms}")
    if args.rosdistro:
        print(f"check_rosdep_keys: facts against {args.rosdistro}: "
              f"{len(facts['system_keys'])} system keys, {len(facts['ros_packages'])} ROS packages "
              f"of {facts['ros_distro']}; {len(mismatches)} mismatches")
    return 1 if problems or mismatches else 0


if __name__ == "__main__":
    sys.exit(main())
