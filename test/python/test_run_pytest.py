"""scripts/run_pytest.py, through which CMake runs the pytest suites and the rostests: a suite
runs when its interpreters have their modules, else it is reported skipped naming what is
missing (a workspace without the project's venv), never failed for that."""
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
RUN = os.path.join(REPO, "scripts", "run_pytest.py")
PY = sys.executable


def run(*args):
    return subprocess.run([PY, RUN, *args], capture_output=True, text=True)


def test_command_runs_with_its_exit_code_when_the_modules_are_there(tmp_path):
    xml = tmp_path / "r.xml"
    done = run("--requires", f"{PY}=os,json", "--xml", str(xml), "--command", "--",
               PY, "-c", "import sys; print('ran'); sys.exit(3)")
    assert done.returncode == 3
    assert "ran" in done.stdout
    assert not xml.exists()  # the command writes its own result


def test_command_is_reported_skipped_naming_what_is_missing(tmp_path):
    xml = tmp_path / "rostest-x.xml"
    done = run("--requires", f"{PY}=os,no_such_module_xyz",
               "--requires", "/nonexistent/python3=os", "--xml", str(xml), "--command", "--",
               "false")
    assert done.returncode == 0, done.stdout + done.stderr
    assert "cannot import no_such_module_xyz" in done.stdout
    assert "/nonexistent/python3 (absent) cannot import os" in done.stdout
    case = ET.parse(xml).getroot().find("testcase")
    skipped = case.find("skipped")
    assert skipped is not None and "no_such_module_xyz" in skipped.get("message")


def test_command_without_xml_only_prints_when_skipped():
    done = run("--requires", f"{PY}=no_such_module_xyz", "--command", "--", "false")
    assert done.returncode == 0
    assert "false skipped" in done.stdout


def test_pytest_form_checks_python_and_requires(tmp_path):
    xml = tmp_path / "pytest-s.xml"
    done = run("--python", PY, "--needs", "os", "--requires", f"{PY}=no_such_module_xyz",
               "--xml", str(xml), "--", "-q", "nothing_here.py")
    assert done.returncode == 0
    assert "pytest-s skipped" in done.stdout
    assert ET.parse(xml).getroot().get("skipped") == "1"


def test_usage_errors():
    assert run("--command").returncode == 2  # no --
    assert run("--xml", "x.xml", "--", "-q").returncode == 2  # pytest form without --python
    assert run("--requires", "nomodules", "--command", "--", "true").returncode == 2
