"""The README stays a complete manual: every parameter a node reads is in its node's table, every
relative link points at a file, the pictures it shows exist and are small, and `make screenshot`
(which makes them) has its pieces."""
import os
import re

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
# The files that read a node's parameters, and the README heading of the node's section.
NODES = {
    "agraph_node": ["src/ros/agraph_node.cpp"],
    "sgraph_node": ["src/ros/sgraph_node.cpp", "src/ros/sgraph_params.cpp"],
    "matcher_node": ["src/ros/matcher_node.cpp"],
    "merger_node": ["src/ros/merger_params.cpp"],
    "deviation_node": ["src/ros/deviation_node.cpp"],
}
READ = re.compile(r'(?:Read|RequireString|ReadParam\w*)\(\s*pnh\s*,\s*"([a-z0-9_]+)"')


def text(path):
    with open(os.path.join(REPO, path), encoding="utf-8") as f:
        return f.read()


def section(readme, node):
    start = readme.index(f"### {node}\n")
    end = readme.find("\n## ", start)
    following = readme.find("\n### ", start + 1)
    ends = [e for e in (end, following) if e != -1]
    return readme[start:min(ends) if ends else len(readme)]


@pytest.mark.parametrize("node", sorted(NODES))
def test_every_parameter_the_node_reads_is_in_its_table(node):
    params = {name for path in NODES[node] for name in READ.findall(text(path))}
    assert params, f"no parameters found in {NODES[node]} (has the reading changed?)"
    rows = [line for line in section(text("README.md"), node).splitlines() if line.startswith("| `")]
    documented = {name for row in rows for name in re.findall(r"`([a-z0-9_]+)`", row.split("|")[1])}
    missing = sorted(params - documented)
    assert not missing, f"README, {node}: parameters without a table row: {missing}"


def test_relative_links_point_at_files():
    readme = text("README.md")
    for target in re.findall(r"\]\(([^)#]+)(?:#[^)]*)?\)", readme):
        if "://" in target:
            continue
        assert os.path.exists(os.path.join(REPO, target)), f"README links to missing {target}"


def test_the_pictures_exist_and_are_small():
    for image in re.findall(r"!\[[^\]]*\]\(([^)]+)\)", text("README.md")):
        path = os.path.join(REPO, image)
        assert os.path.isfile(path), f"README shows {image}, which is missing (make screenshot)"
        assert os.path.getsize(path) < 500 * 1024, f"{image} is over 500 KiB"


def test_make_screenshot_has_its_pieces():
    assert re.search(r"^screenshot:", text("Makefile"), re.M), "no screenshot target in Makefile"
    for script in ("scripts/screenshot.sh", "scripts/screenshot_wait.py",
                   "scripts/screenshot_image.py"):
        assert os.access(os.path.join(REPO, script), os.X_OK), f"{script} missing or not executable"
    assert "rviz_config" in text("launch/localize.launch")
