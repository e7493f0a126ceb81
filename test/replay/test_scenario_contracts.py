"""Every scenario's contract (test/ros/localize_<scenario>.test) checked on the deterministic
replay of its short bag (replay_pipeline: the core the nodes run, fed synchronously from the
bag). The live rostests check a subset of the same contracts through real nodes and topics
(CMakeLists.txt, IS_GRAPHS_LIVE_SCENARIOS); each check here mirrors one of test_localize.cpp's.
Each test prints what it measured ("[ scenario ] ...").
"""
import math
import os

import pytest

from conftest import REPO, scenarios
from contract import STAMP_SLACK, Replay, in_carry_window, read_contract, storey_at

SCENARIOS = scenarios()


@pytest.fixture
def case(replays, scenario):
    c = read_contract(os.path.join(REPO, "test", "ros", f"localize_{scenario}.test"))
    assert c["scenario"] == scenario, f"the .test names scenario {c['scenario']}"
    result = replays.get(scenario)
    if isinstance(result, Exception) or result is None:
        pytest.fail(f"[{scenario}] no replay: {result}")
    return c, Replay(result[0])


def say(c, text):
    print(f"[ {c['scenario']} ] {text}")


@pytest.mark.parametrize("scenario", SCENARIOS)
def test_no_pose_before_localized(case):
    c, r = case
    assert r.truth, f"[{c['scenario']}] no ground truth: the bag has none"
    say(c, f"bag {r.run['bag_seconds']:.1f} s, {len(r.poses)} pose_bim, {len(r.matches)} matches")
    if r.first_localized is None:
        assert not r.poses, f"[{c['scenario']}] {len(r.poses)} poses but never localized"
        return
    early = [p for p in r.poses if p[0] < r.t0 + r.first_localized - 1e-6]
    assert not early, f"[{c['scenario']}] {len(early)} poses before the first merge"


@pytest.mark.parametrize("scenario", SCENARIOS)
def test_localizes_in_time(case):
    c, r = case
    if r.first_localized is not None:
        say(c, f"localized at {r.first_localized:.1f} s, {r.run['distance_to_localize']:.1f} m "
               f"(bound {c['max_seconds_to_localize']} s)")
    if not c["expect_localized"]:
        pytest.skip("not expected to localize on this bag")
    assert r.first_localized is not None, f"[{c['scenario']}] not localized within the bag"
    assert r.first_localized <= c["max_seconds_to_localize"], (
        f"[{c['scenario']}] localized at {r.first_localized:.2f} s, bound "
        f"{c['max_seconds_to_localize']} s")
    if c["max_metres_to_localize"] > 0:
        assert r.run["distance_to_localize"] <= c["max_metres_to_localize"], (
            f"[{c['scenario']}] localized after {r.run['distance_to_localize']:.2f} m walked, "
            f"bound {c['max_metres_to_localize']} m")
    if c["kidnap_window"] <= 0 or c["max_seconds_to_relocalize"] > 0:
        assert r.run["localized_at_end"], f"[{c['scenario']}] not localized at the end"


@pytest.mark.parametrize("scenario", SCENARIOS)
def test_ape_within_bounds(case):
    c, r = case
    if not c["expect_localized"]:
        pytest.skip("not expected to localize on this bag: no APE bound")
    kept = [p for p in r.paired if not in_carry_window(c, r, p[0])]
    assert len(kept) >= c["min_poses"], f"[{c['scenario']}] {len(kept)} poses paired with truth"
    n = len(kept)
    rmse = math.sqrt(sum(p[1] ** 2 for p in kept) / n)
    max_xy = max(p[1] for p in kept)
    z_rmse = math.sqrt(sum(p[3] ** 2 for p in kept) / n)
    yaw_rmse = math.degrees(math.sqrt(sum(p[2] ** 2 for p in kept) / n))
    yaw_max = math.degrees(max(abs(p[2]) for p in kept))
    say(c, f"APE x,y RMSE {rmse:.4f} m, max {max_xy:.4f} m over {n} poses; z RMSE {z_rmse:.4f} "
           f"m; yaw RMSE {yaw_rmse:.3f} deg, max {yaw_max:.3f} deg")
    where = f"[{c['scenario']}]"
    assert rmse <= c["max_ape_rmse"], f"{where} APE x,y RMSE {rmse:.4f} m"
    assert max_xy <= c["max_ape_max"], f"{where} APE x,y max {max_xy:.4f} m"
    assert z_rmse <= c["max_ape_z_rmse"], f"{where} APE z RMSE {z_rmse:.4f} m"
    assert yaw_rmse <= c["max_yaw_rmse_deg"], f"{where} yaw RMSE {yaw_rmse:.3f} deg"
    assert yaw_max <= c["max_yaw_deg"], f"{where} yaw max {yaw_max:.3f} deg"


@pytest.mark.parametrize("scenario", SCENARIOS)
def test_never_a_wrong_pose(case):
    c, r = case
    assert len(r.paired) >= len(r.poses) * 9 // 10, (
        f"[{c['scenario']}] pose stamps do not meet truth stamps ({len(r.paired)} of "
        f"{len(r.poses)} paired)")
    checked = [p for p in r.paired if not in_carry_window(c, r, p[0])]
    wrong = [p for p in checked if p[1] > c["max_wrong_distance"]
             or math.degrees(abs(p[2])) > c["max_wrong_yaw_deg"] or abs(p[3]) > c["max_wrong_z"]]
    say(c, f"{len(checked)} poses checked for a wrong pose: {len(wrong)} wrong; "
           f"{r.run['wrong_matches']} wrong UNIQUE matches")
    assert not wrong, (f"[{c['scenario']}] {len(wrong)} wrong poses, the first at "
                       f"{wrong[0][0] - r.t0:.1f} s: {wrong[0][1]:.2f} m, "
                       f"{math.degrees(wrong[0][2]):.1f} deg, {wrong[0][3]:.2f} m in z")


@pytest.mark.parametrize("scenario", SCENARIOS)
def test_never_a_wrong_storey(case):
    c, r = case
    if c["true_storey_id"] < 0 and not c["storey_elevations"]:
        pytest.skip("the localizer was given the storey")
    assert r.matches, f"[{c['scenario']}] no match"
    unique = wrong = doubting = elsewhere = 0
    for m in r.matches:
        truth = storey_at(c, r, r.t0 + m["t"])
        if m["status"] == "UNIQUE":
            unique += 1
            wrong += m["storey"] != truth
        if m["status"] == "AMBIGUOUS":
            elsewhere += c["ambiguous_names_storey"] and m["storey"] != truth
            doubting += bool(m["competing_storeys"]) and (
                m["storey"] == truth or truth in m["competing_storeys"])
    say(c, f"{len(r.matches)} matches: {unique} UNIQUE, {wrong} on another storey; {doubting} "
           f"AMBIGUOUS about the storey")
    assert wrong == 0, f"[{c['scenario']}] {wrong} UNIQUE matches on another storey"
    if c["ambiguous_names_storey"]:
        assert elsewhere == 0, f"[{c['scenario']}] {elsewhere} AMBIGUOUS name another storey"
    if c["storey_in_doubt"]:
        assert doubting > 0, f"[{c['scenario']}] no AMBIGUOUS match names the competing storeys"


@pytest.mark.parametrize("scenario", SCENARIOS)
def test_kidnap_is_detected(case):
    c, r = case
    if c["kidnap_window"] <= 0:
        pytest.skip("no kidnap in this scenario")
    where = f"[{c['scenario']}]"
    assert len(r.carries) == 1, f"{where} ground truth jumps {len(r.carries)} times, not once"
    carry = r.carries[0]
    assert r.first_localized is not None and r.t0 + r.first_localized < carry, (
        f"{where} not localized before the carry: the kidnap tests nothing")
    lost = next((l for l in r.lost if l[0] >= carry), None)
    assert lost is not None, f"{where} never LOST after the carry at {carry - r.t0:.1f} s"
    say(c, f"carried at {carry - r.t0:.1f} s; LOST {lost[0] - carry:.1f} s later; localized "
           f"again {lost[1] - carry:.1f} s after the carry")
    assert lost[0] <= carry + c["kidnap_window"], f"{where} LOST {lost[0] - carry:.1f} s late"
    if c["max_seconds_to_relocalize"] > 0:
        assert lost[1] - carry <= c["max_seconds_to_relocalize"], (
            f"{where} localized again {lost[1] - carry:.1f} s after the carry")
    while_lost = [p for p in r.poses for a, b in r.lost
                  if a + STAMP_SLACK < p[0] < b - STAMP_SLACK]
    assert not while_lost, f"{where} {len(while_lost)} poses while LOST"


@pytest.mark.parametrize("scenario", SCENARIOS)
def test_symmetric_stays_ambiguous(case):
    c, r = case
    if c["max_seconds_to_ambiguous"] <= 0:
        pytest.skip("not a symmetric building")
    where = f"[{c['scenario']}]"
    unique = sum(m["status"] == "UNIQUE" for m in r.matches)
    first = next((m for m in r.matches if m["status"] == "AMBIGUOUS" and m["hypotheses"] >= 2),
                 None)
    say(c, f"{len(r.matches)} matches, {unique} UNIQUE; first AMBIGUOUS: "
           + (f"{first['t']:.1f} s, {first['hypotheses']} hypotheses" if first else "never"))
    assert unique == 0, f"{where} {unique} UNIQUE matches in a symmetric building"
    assert first is not None, f"{where} never AMBIGUOUS with 2 or more hypotheses"
    assert first["t"] <= c["max_seconds_to_ambiguous"], f"{where} first AMBIGUOUS {first['t']} s"
    assert r.first_localized is None and not r.poses, f"{where} localized in a symmetric building"
