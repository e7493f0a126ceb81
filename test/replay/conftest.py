"""Runs each scenario's replay once per session, IS_GRAPHS_REPLAY_JOBS (default 2) at a time.

A scenario's bag is the one the live rostests share (IS_GRAPHS_TEST_TMP_DIR/<scenario>.bag)
when it is there and up to date; otherwise make_bag makes it into a scratch folder and it is
deleted after its replay (the short bags take 13 GB together; make_bag needs 2-20 s each).
The environment (set by CMakeLists.txt): IS_GRAPHS_TEST_TMP_DIR, IS_GRAPHS_MAKE_BAG,
IS_GRAPHS_REPLAY.
"""
import concurrent.futures
import glob
import os
import shutil
import subprocess
import time

import pytest
import yaml

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))


def scenarios():
    """The scenarios with a localize_<scenario>.test whose building is present."""
    names = []
    for test in sorted(glob.glob(os.path.join(REPO, "test", "ros", "localize_*.test"))):
        name = os.path.basename(test)[len("localize_"):-len(".test")]
        with open(os.path.join(REPO, "bags", name + ".yaml")) as f:
            building = yaml.safe_load(f)["building"]
        names.append(pytest.param(name, marks=() if os.path.isfile(os.path.join(REPO, building))
                                  else pytest.mark.skip(reason=f"{building} not found")))
    return names


def _env(name):
    value = os.environ.get(name)
    if not value:
        pytest.fail(f"{name} is not set (CMakeLists.txt sets it for the replay_contracts test)")
    return value


def _up_to_date(bag, yaml_path, make_bag):
    return (os.path.isfile(bag) and os.path.getmtime(bag) > os.path.getmtime(yaml_path)
            and os.path.getmtime(bag) > os.path.getmtime(make_bag))


def replay_one(name, storey, tmp, make_bag, replay):
    """(prefix, seconds, log) of the replay of scenario `name`."""
    yaml_path = os.path.join(REPO, "bags", name + ".yaml")
    with open(yaml_path) as f:
        building = os.path.join(REPO, yaml.safe_load(f)["building"])
    out = os.path.join(tmp, "replay", name)
    os.makedirs(out, exist_ok=True)
    start = time.monotonic()
    shared = os.path.join(tmp, name + ".bag")
    bag = shared if _up_to_date(shared, yaml_path, make_bag) else os.path.join(out, name + ".bag")
    log = []
    try:
        if bag != shared:
            p = subprocess.run([make_bag, yaml_path, "-o", bag, "--quiet"], capture_output=True,
                               text=True)
            log.append(p.stdout + p.stderr)
            if p.returncode != 0:
                raise RuntimeError(f"make_bag {yaml_path} failed ({p.returncode}): {p.stderr}")
        args = [replay, bag, "--building", building, "--out-prefix", os.path.join(out, "run")]
        if storey:
            args += ["--storey", storey]
        p = subprocess.run(args, capture_output=True, text=True)
        log.append(p.stdout + p.stderr)
        with open(os.path.join(out, "replay.log"), "w") as f:
            f.write("\n".join(log))
        if p.returncode != 0:
            raise RuntimeError(f"replay_pipeline failed ({p.returncode}):\n{p.stderr[-2000:]}")
    finally:
        if bag != shared and os.path.exists(bag):
            os.remove(bag)
    return os.path.join(out, "run"), time.monotonic() - start


@pytest.fixture(scope="session")
def replays(request):
    """{scenario: (prefix, seconds) or the exception}, for the scenarios this session runs."""
    from contract import read_contract

    tmp, make_bag, replay = (_env("IS_GRAPHS_TEST_TMP_DIR"), _env("IS_GRAPHS_MAKE_BAG"),
                             _env("IS_GRAPHS_REPLAY"))
    shutil.rmtree(os.path.join(tmp, "replay"), ignore_errors=True)
    names = sorted({item.callspec.params["scenario"] for item in request.session.items
                    if hasattr(item, "callspec") and "scenario" in item.callspec.params
                    and item.get_closest_marker("skip") is None})
    jobs = int(os.environ.get("IS_GRAPHS_REPLAY_JOBS", "2"))
    results = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        futures = {}
        for name in names:
            test = os.path.join(REPO, "test", "ros", f"localize_{name}.test")
            storey = read_contract(test)["storey"]
            futures[pool.submit(replay_one, name, storey, tmp, make_bag, replay)] = name
        for f in concurrent.futures.as_completed(futures):
            try:
                results[futures[f]] = f.result()
            except Exception as e:  # reported by the scenario's own test
                results[futures[f]] = e
    return results
