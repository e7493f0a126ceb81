"""package.xml declares every dependency with a key that rosdep resolves on ubuntu focal, ubuntu
jammy and debian bookworm: scripts/check_rosdep_keys.py against the facts of
test/data/rosdep_keys.yaml, and the facts against a real ros/rosdistro tree when ROSDISTRO_DIR
names one (a checkout or an extract with rosdep/*.yaml and noetic/distribution.yaml)."""
import copy
import os
import subprocess
import sys

import pytest
import yaml

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
SCRIPT = os.path.join(REPO, "scripts", "check_rosdep_keys.py")
sys.path.insert(0, os.path.join(REPO, "scripts"))

import check_rosdep_keys as check  # noqa: E402

PACKAGE_XML = os.path.join(REPO, "package.xml")
FACTS = os.path.join(REPO, "test", "data", "rosdep_keys.yaml")


@pytest.fixture(scope="module")
def facts():
    with open(FACTS, encoding="utf-8") as f:
        return yaml.safe_load(f)


def run_cli(*args):
    return subprocess.run([sys.executable, SCRIPT, *args], capture_output=True, text=True,
                          timeout=120)


def package_xml_with(tmp_path, old, new):
    with open(PACKAGE_XML, encoding="utf-8") as f:
        text = f.read()
    assert old in text, f"package.xml no longer has {old}"
    path = tmp_path / "package.xml"
    path.write_text(text.replace(old, new), encoding="utf-8")
    return str(path)


# --- package.xml against the facts ---------------------------------------------------------

def test_every_key_of_package_xml_resolves_on_each_platform(facts):
    problems, _ = check.check_package(check.package_keys(PACKAGE_XML), facts)
    assert not problems, "rosdep keys that do not resolve:\n" + "\n".join(problems)


def test_the_supported_platforms_are_focal_jammy_and_bookworm(facts):
    assert facts["platforms"] == ["ubuntu:focal", "ubuntu:jammy", "debian:bookworm"]
    assert facts["ros_distro"] == "noetic"


def test_the_cli_passes_on_the_repository():
    proc = run_cli()
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "0 problems" in proc.stdout


def test_a_key_rosdep_does_not_know_is_reported(tmp_path, facts):
    # The key the package used to declare: rosdep stopped with "Cannot locate rosdep
    # definition for [ceres-solver]" (the key is libceres-dev).
    bogus = package_xml_with(tmp_path, "<depend>libceres-dev</depend>",
                             "<depend>ceres-solver</depend>")
    problems, _ = check.check_package(check.package_keys(bogus), facts)
    assert any("ceres-solver" in p and "not a rosdep key" in p for p in problems), problems
    proc = run_cli("--package-xml", bogus)
    assert proc.returncode == 1
    assert "<depend>ceres-solver</depend>" in proc.stdout


def test_a_key_dropped_from_package_xml_leaves_a_stale_fact(tmp_path, facts):
    path = package_xml_with(tmp_path, "<test_depend>xvfb</test_depend>", "")
    problems, _ = check.check_package(check.package_keys(path), facts)
    assert any("xvfb" in p and "stale" in p for p in problems), problems


def test_a_platform_without_a_resolution_is_reported(facts):
    changed = copy.deepcopy(facts)
    del changed["system_keys"]["embree"]["project_source"]
    problems, _ = check.check_package(check.package_keys(PACKAGE_XML), changed)
    assert any("embree" in p and "debian:bookworm" in p for p in problems), problems


def test_the_project_source_fills_the_bookworm_gap_as_recorded(facts):
    _, notes = check.check_package(check.package_keys(PACKAGE_XML), facts)
    assert notes == ["embree on debian:bookworm: not in rosdistro; "
                     "scripts/rosdep_bookworm.yaml gives [libembree-dev]"]
    changed = copy.deepcopy(facts)
    changed["system_keys"]["embree"]["project_source"]["debian:bookworm"] = ["libembree3-dev"]
    problems, _ = check.check_package(check.package_keys(PACKAGE_XML), changed)
    assert any("rosdep_bookworm.yaml gives [libembree-dev]" in p for p in problems), problems


def test_every_dependency_tag_is_read(tmp_path):
    path = tmp_path / "package.xml"
    path.write_text('<?xml version="1.0"?>\n<package format="3"><name>p</name>'
                    "<buildtool_depend>catkin</buildtool_depend><depend>a</depend>"
                    "<build_depend>b</build_depend><build_export_depend>c</build_export_depend>"
                    "<exec_depend>d</exec_depend><test_depend>e</test_depend>"
                    "<build_depend>a</build_depend><doc_depend>f</doc_depend></package>",
                    encoding="utf-8")
    keys = check.package_keys(str(path))
    assert list(keys) == ["catkin", "a", "b", "c", "d", "e", "f"]
    assert keys["a"] == ["depend", "build_depend"]


# --- rosdep's resolution rules --------------------------------------------------------------

@pytest.mark.parametrize("rule, platform, expected", [
    ({"ubuntu": ["a"]}, "ubuntu:focal", ["a"]),                      # every version
    ({"ubuntu": ["a"]}, "ubuntu:jammy", ["a"]),
    ({"ubuntu": "a b"}, "ubuntu:focal", ["a", "b"]),
    ({"ubuntu": {"focal": ["a"]}}, "ubuntu:focal", ["a"]),           # named versions only
    ({"ubuntu": {"focal": ["a"]}}, "ubuntu:jammy", None),
    ({"debian": {"bullseye": ["x"]}}, "debian:bookworm", None),
    ({"ubuntu": {"*": ["b"], "bionic": None}}, "ubuntu:jammy", ["b"]),  # wildcard version
    ({"ubuntu": {"*": ["b"], "bionic": None}}, "ubuntu:bionic", None),  # null: unavailable
    ({"ubuntu": {"*": ["new"], "bionic": ["old"]}}, "ubuntu:bionic", ["old"]),
    ({"ubuntu": {"focal": []}}, "ubuntu:focal", []),                 # installs nothing
    ({"ubuntu": {"focal": {"apt": {"packages": ["a", "b"]}}}}, "ubuntu:focal", ["a", "b"]),
    ({"ubuntu": {"pip": {"packages": ["evo"]}}}, "ubuntu:focal", ["pip:evo"]),
    ({"ubuntu": {"*": {"pip": {"packages": ["x"]}}, "jammy": ["python3-x"]}},
     "ubuntu:focal", ["pip:x"]),
    ({"ubuntu": {"*": {"pip": {"packages": ["x"]}}, "jammy": ["python3-x"]}},
     "ubuntu:jammy", ["python3-x"]),
    ({"*": {"pip": {"packages": ["x"]}}}, "debian:bookworm", ["pip:x"]),  # wildcard OS
    ({"fedora": ["x"]}, "ubuntu:focal", None),
])
def test_resolve_follows_rosdep(rule, platform, expected):
    assert check.resolve(rule, platform) == expected


def test_sources_merge_per_key_and_os_first_wins(tmp_path):
    first, second = tmp_path / "first.yaml", tmp_path / "second.yaml"
    first.write_text("embree:\n  debian:\n    bookworm: [libembree-dev]\n", encoding="utf-8")
    second.write_text("embree:\n  debian:\n    bullseye: [old]\n  ubuntu:\n    '*': [u]\n",
                      encoding="utf-8")
    db = check.load_rosdep_sources([str(first), str(second)])
    assert check.resolve(db["embree"]["rule"], "debian:bookworm") == ["libembree-dev"]
    assert check.resolve(db["embree"]["rule"], "debian:bullseye") is None  # debian: first's
    assert check.resolve(db["embree"]["rule"], "ubuntu:jammy") == ["u"]
    assert db["embree"]["origin"] == {"debian": "first.yaml", "ubuntu": "second.yaml"}


# --- the facts against a rosdistro tree -----------------------------------------------------

def write_rosdistro(root, facts, edit=None):
    """A small rosdistro tree that gives exactly what the facts say (then `edit` changes it)."""
    files = {name: {} for name in check.ROSDEP_FILES}
    for key, entry in facts["system_keys"].items():
        rule = {}
        for platform in facts["platforms"]:
            os_name, version = check.split_platform(platform)
            rule.setdefault(os_name, {})[version] = entry[platform]
        files[entry["file"]][key] = rule
    distribution = {"release_platforms": {"ubuntu": ["focal"]},
                    "repositories": {"all": {"release": {"packages":
                                                         list(facts["ros_packages"])}}}}
    if edit:
        edit(files, distribution)
    os.makedirs(root / "rosdep")
    os.makedirs(root / facts["ros_distro"])
    for name, data in files.items():
        (root / "rosdep" / name).write_text(yaml.safe_dump(data), encoding="utf-8")
    (root / facts["ros_distro"] / "distribution.yaml").write_text(yaml.safe_dump(distribution),
                                                                  encoding="utf-8")
    return str(root)


def test_facts_agree_with_a_tree_made_from_them(tmp_path, facts):
    assert check.check_against_rosdistro(facts, write_rosdistro(tmp_path, facts)) == []


def test_every_change_in_rosdistro_is_reported(tmp_path, facts):
    def edit(files, distribution):
        files["base.yaml"]["embree"]["debian"]["bookworm"] = ["libembree-dev"]
        files["base.yaml"]["libceres-dev"]["ubuntu"]["jammy"] = ["libceres2-dev"]
        del files["base.yaml"]["xvfb"]
        files["python.yaml"]["gtest"] = files["base.yaml"].pop("gtest")
        distribution["repositories"]["all"]["release"]["packages"].remove("rviz")

    mismatches = check.check_against_rosdistro(facts, write_rosdistro(tmp_path, facts, edit))
    text = "\n".join(mismatches)
    assert len(mismatches) == 5, text
    assert "embree on debian:bookworm: rosdistro gives [libembree-dev]" in text
    assert "the project's own rule can go" in text
    assert "libceres-dev on ubuntu:jammy: rosdistro gives [libceres2-dev]" in text
    assert "xvfb: no such key" in text
    assert "gtest: the facts say it is in base.yaml, rosdistro has it in python.yaml" in text
    assert "rviz: not a released package of noetic/distribution.yaml" in text
    proc = run_cli("--rosdistro", str(tmp_path))
    assert proc.returncode == 1
    assert proc.stdout.count("mismatch: ") == 5, proc.stdout


def test_facts_agree_with_the_real_rosdistro(facts):
    """ROSDISTRO_DIR: a ros/rosdistro checkout, or its rosdep/ and noetic/distribution.yaml
    extracted (docs/platforms.md, section rosdep, shows how)."""
    root = os.environ.get("ROSDISTRO_DIR")
    if not root:
        pytest.skip("ROSDISTRO_DIR not set: the facts were not compared with a ros/rosdistro tree "
                    "(set it to a checkout of ros/rosdistro to do so)")
    mismatches = check.check_against_rosdistro(facts, root)
    assert not mismatches, (f"test/data/rosdep_keys.yaml disagrees with {root}:\n"
                            + "\n".join(mismatches))
