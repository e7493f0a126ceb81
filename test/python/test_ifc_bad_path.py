"""A BIM path that is not a readable IFC file is named for what it is, with its path, both with -o
and with --cache-dir (agraph_node's way); output problems keep their own message."""
import os
import shutil
import subprocess
import sys
import tempfile

import pytest

from conftest import CLI, REPO, fails

OFFICE = os.path.join(REPO, "bim", "office.ifc")


def both_modes(run_converter, path, tmp_path, *words):
    for out in (["-o", tmp_path / "h"], ["--cache-dir", tmp_path / "cache"]):
        line = fails(run_converter([path] + out + ["--quiet"]), *words)
        assert "cannot write the output" not in line, line
    assert not (tmp_path / "h.agraph.json").exists()


def test_directory(run_converter, tmp_path):
    (tmp_path / "plans.ifc").mkdir()
    both_modes(run_converter, tmp_path / "plans.ifc", tmp_path,
               f"BIM path is a directory, not an IFC file: {tmp_path / 'plans.ifc'}")


def test_missing_file_and_broken_link(run_converter, tmp_path):
    both_modes(run_converter, tmp_path / "nope.ifc", tmp_path,
               f"no such file: {tmp_path / 'nope.ifc'}")
    (tmp_path / "link.ifc").symlink_to(tmp_path / "gone.ifc")
    both_modes(run_converter, tmp_path / "link.ifc", tmp_path, "no such file: ",
               "link.ifc (a broken symbolic link)")


def test_parent_is_a_file(run_converter, tmp_path):
    shutil.copy(OFFICE, tmp_path / "office.ifc")
    path = tmp_path / "office.ifc" / "x.ifc"
    both_modes(run_converter, path, tmp_path, f"cannot read {path}: Not a directory")


def test_fifo_is_refused_without_blocking(run_converter, tmp_path):
    os.mkfifo(tmp_path / "pipe.ifc")
    env = dict(os.environ, PATH="/usr/bin:" + os.environ.get("PATH", ""))
    for out in (["-o", tmp_path / "h"], ["--cache-dir", tmp_path / "cache"]):
        # Nobody writes the FIFO: a converter that opened it would wait until the timeout.
        proc = subprocess.run([sys.executable, CLI, tmp_path / "pipe.ifc"] + out,
                              capture_output=True, text=True, timeout=120, env=env)
        fails(proc, "BIM path is not a regular file (a FIFO, socket or device), not an IFC "
                    f"file: {tmp_path / 'pipe.ifc'}")


def test_unreadable_file(tmp_path):
    """chmod 000. Root reads it anyway, so as root the converter runs as nobody (setpriv), on a
    file in a directory nobody may enter (tmp_path's parents are private to root)."""
    as_root = os.geteuid() == 0
    if as_root and not shutil.which("setpriv"):
        pytest.skip("running as root and setpriv is absent: cannot make a file unreadable")
    with tempfile.TemporaryDirectory(prefix="is_graphs_unreadable_") as tmp:
        os.chmod(tmp, 0o755)
        path = os.path.join(tmp, "secret.ifc")
        shutil.copy(OFFICE, path)
        os.chmod(path, 0)
        env = dict(os.environ, PATH="/usr/bin:" + os.environ.get("PATH", ""))
        user = ["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"] if as_root else []
        for out in (["-o", os.path.join(tmp, "h")], ["--cache-dir", os.path.join(tmp, "c")]):
            proc = subprocess.run(user + [sys.executable, CLI, path] + out, capture_output=True,
                                  text=True, timeout=300, env=env)
            line = fails(proc, f"cannot read {path}: Permission denied")
            assert "cannot write the output" not in line, line


def test_empty_and_text_files(run_converter, tmp_path):
    (tmp_path / "empty.ifc").write_bytes(b"")
    both_modes(run_converter, tmp_path / "empty.ifc", tmp_path,
               f"empty file (0 bytes), not an IFC file: {tmp_path / 'empty.ifc'}")
    (tmp_path / "notes.ifc").write_text("walls: 4\nrooms: 2\n")
    line = fails(run_converter([tmp_path / "notes.ifc", "-o", tmp_path / "h"]), "notes.ifc: ",
                 "not an IFC file: it does not start with 'ISO-10303-21;'")
    assert line.endswith("it starts with 'walls: 4'"), line
    (tmp_path / "blob.ifc").write_bytes(bytes(range(256)) * 4)
    fails(run_converter([tmp_path / "blob.ifc", "-o", tmp_path / "h"]), "blob.ifc: ",
          "not an IFC file", "it is binary data")


def test_output_problem_keeps_its_message(run_converter, tmp_path):
    (tmp_path / "file").write_text("in the way")
    prefix = tmp_path / "file" / "h"
    fails(run_converter([OFFICE, "-o", prefix, "--quiet"]), "office.ifc: ",
          f"cannot write the output {prefix}: ")
