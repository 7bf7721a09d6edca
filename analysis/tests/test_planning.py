"""planning.sample_size: the power of the two-sided exact sign test with ties, checked against
computations written out here (every split of n participants enumerated; a seeded simulation;
closed forms where p+ = 1), a textbook table of critical values, and the report's planning table.

The checks build the two-sided p as R's binom.test defines it (the sum of the outcomes no more
likely than the one seen) from binomial probabilities, not through scipy's binomtest, which the
code under test uses.
"""
import functools
import json
import math
import shutil
import sys
from pathlib import Path

import numpy as np
import pytest
import scipy.stats

ANALYSIS = Path(__file__).resolve().parents[1]
DATA = Path(__file__).resolve().parent / "data"
sys.path.insert(0, str(ANALYSIS))

import analyze  # noqa: E402
from warplab_analysis import planning  # noqa: E402

# Lower critical values of the two-sided sign test at α = 0.05 (reject when the count of the
# rarer sign is ≤ c), as printed in sign-test tables; none below 6 pairs.
TEXTBOOK_CRITICAL = {5: -1, 6: 0, 7: 0, 8: 0, 9: 1, 10: 1, 11: 1, 12: 2, 13: 2, 14: 2, 15: 3, 16: 3, 17: 4, 18: 4,
                     19: 4, 20: 5, 25: 7, 30: 9}


@functools.lru_cache(maxsize=None)
def rejection_set(m, alpha=0.05):
    """R's binom.test, two-sided, p = ½: the counts whose outcomes no likelier than them sum to ≤ alpha."""
    pmf = scipy.stats.binom.pmf(np.arange(m + 1), m, 0.5)
    return frozenset(k for k in range(m + 1) if m > 0 and pmf[pmf <= pmf[k] * (1 + 1e-7)].sum() <= alpha)


def rejects(positive, m):
    return positive in rejection_set(m)


def enumerated_power(n, p_plus, tie):
    """Sum over every (positive, negative, tied) split of n participants of its multinomial probability."""
    total = 0.0
    for positive in range(n + 1):
        for negative in range(n + 1 - positive):
            tied = n - positive - negative
            ways = math.factorial(n) // (math.factorial(positive) * math.factorial(negative) * math.factorial(tied))
            if rejects(positive, positive + negative):
                total += ways * ((1 - tie) * p_plus) ** positive * ((1 - tie) * (1 - p_plus)) ** negative * tie ** tied
    return total


def test_critical_counts_match_the_textbook_table():
    c = planning.critical_counts()
    for m, expected in TEXTBOOK_CRITICAL.items():
        assert c[m] == expected, m
    for m in range(0, 121):  # and R's definition up to 120 pairs
        assert rejection_set(m) == {k for k in range(m + 1) if k <= c[m] or k >= m - c[m]}, m


@pytest.mark.parametrize("p_plus, tie", [(0.8, 0.0), (0.7, 0.2), (0.95, 0.1), (0.25, 0.4)])
def test_power_equals_enumeration(p_plus, tie):
    power = planning.power_curve(p_plus, tie)
    for n in range(0, 31):
        assert power[n] == pytest.approx(enumerated_power(n, p_plus, tie), abs=1e-12), n


def test_power_equals_seeded_simulation():
    rng = np.random.default_rng(14)
    p_plus, tie, runs = 0.7, 0.2, 100_000
    power = planning.power_curve(p_plus, tie)
    for n in (12, 40, 90):
        counts = rng.multinomial(n, [(1 - tie) * p_plus, (1 - tie) * (1 - p_plus), tie], size=runs)
        hits = np.mean([rejects(int(pos), int(pos + neg)) for pos, neg, _ in counts])
        se = math.sqrt(power[n] * (1 - power[n]) / runs)
        assert abs(hits - power[n]) < 4 * se + 1e-9, n


def test_p_plus_0_8_without_ties_needs_23_not_its_first_crossing():
    # The saw-tooth: power first reaches 0.8 at 20 and falls below at 21 and 22.
    result = planning.sample_size(16, 4, 0)
    assert (result["p_plus"], result["tie_share"], result["extreme"]) == (0.8, 0.0, False)
    assert (result["first"], result["needed"]) == (20, 23)
    exact = [enumerated_power(n, 0.8, 0.0) for n in range(19, 41)]
    assert [n for n, p in zip(range(19, 41), exact) if p < 0.8] == [19, 21, 22]
    assert result["power_at_needed"] == pytest.approx(exact[23 - 19], abs=1e-12)


def test_needed_is_the_start_of_the_last_run_at_or_above_target():
    for counts in [(16, 4, 0), (7, 3, 2), (11, 9, 0), (1, 5, 3)]:
        result = planning.sample_size(*counts)
        power = planning.power_curve(result["p_plus"], result["tie_share"])
        needed, first = result["needed"], result["first"]
        assert np.all(power[needed:] >= 0.8) and power[needed - 1] < 0.8, counts
        assert power[first] >= 0.8 and np.all(power[:first] < 0.8), counts
        assert first <= needed


def test_power_grows_toward_one_and_a_mirrored_difference_needs_the_same():
    power = planning.power_curve(0.8, 0.0)
    assert power[1000] == pytest.approx(1.0, abs=1e-12)
    assert np.all(np.diff(power[[10, 25, 50, 100]]) > 0)  # a saw-tooth, but rising
    assert np.allclose(planning.power_curve(0.3, 0.25), planning.power_curve(0.7, 0.25), atol=1e-12)
    assert planning.sample_size(3, 7, 2)["needed"] == planning.sample_size(7, 3, 2)["needed"]


def test_one_sided_pilot_without_ties_needs_six():
    for counts in [(20, 0, 0), (0, 3, 0)]:
        result = planning.sample_size(*counts)
        assert result["extreme"] and (result["needed"], result["first"], result["power_at_needed"]) == (6, 6, 1.0)
    power = planning.power_curve(1.0, 0.0)
    assert power[5] == 0.0 and power[6] == 1.0 and 2 * 0.5 ** 6 < 0.05 < 2 * 0.5 ** 5
    assert planning.fewest_untied() == 6


@pytest.mark.parametrize("tie", [0.1, 0.3, 0.5, 0.9])
def test_ties_with_a_one_sided_pilot_need_six_untied_participants(tie):
    # p+ = 1: the test rejects exactly when at least 6 participants are untied, M ~ Binomial(n, 1 − tie).
    expected = next(n for n in range(6, 1001) if scipy.stats.binom.sf(5, n, 1 - tie) >= 0.8)
    tied = round(tie * 10)
    result = planning.sample_size(10 - tied, 0, tied)
    assert result["tie_share"] == pytest.approx(tie) and result["extreme"]
    assert result["needed"] == expected
    assert result["power_at_needed"] == pytest.approx(scipy.stats.binom.sf(5, expected, 1 - tie), abs=1e-12)
    if tie == 0.5:
        assert expected == 15


def test_no_difference_to_detect():
    for counts in [(5, 5, 3), (0, 0, 4), (6, 6, 0)]:
        result = planning.sample_size(*counts)
        assert result["needed"] is None and result["first"] is None
        assert result["note"] == "no difference to detect", counts
    assert planning.sample_size(0, 0, 4)["p_plus"] is None and planning.sample_size(0, 0, 4)["tie_share"] == 1.0
    assert planning.sample_size(0, 0, 0)["note"] == "no participant has both conditions"
    # At p+ = ½ the power is the test's size, never above α (so no n would reach 0.8).
    assert planning.power_curve(0.5, 0.3).max() <= 0.05


def test_beyond_the_cap():
    result = planning.sample_size(11, 10, 0)  # p+ = 0.524
    assert result["needed"] is None and result["note"] == "more than 1000"
    assert planning.sample_size(16, 4, 0, cap=22)["note"] == "more than 22"  # power(22) < 0.8
    assert planning.sample_size(16, 4, 0, cap=23)["needed"] == 23


def hitrate_csv(rows):
    return "participant,game,mode,shots,hits,timeouts,hit_rate\n" + "".join(
        f"{p},shooter,{m},20,{h},0,{h / 20}\n" for p, m, h in rows)


def test_report_has_the_planning_table(tmp_path):
    # conv60 − conv30: 11 up, 10 down; conv60 − conv15: all tied; conv30 − conv15: 10 up, 11 down.
    rows = []
    for k in range(21):
        rows += [(f"p{k}", "conv60", 10), (f"p{k}", "conv15", 10), (f"p{k}", "conv30", 9 if k < 11 else 11)]
    (tmp_path / "hitrates.csv").write_text(hitrate_csv(rows))
    shutil.copy(DATA / "modes.csv", tmp_path / "modes.csv")  # the condition order: conv60 before conv30
    assert analyze.main([str(tmp_path), "--out", str(tmp_path / "out")]) == 0
    report = json.loads((tmp_path / "out" / "report.json").read_text())
    plans = {(t["a"], t["b"]): t["planning"] for t in report["sign_tests"]}
    assert plans[("conv60", "conv30")]["note"] == "more than 1000"
    assert plans[("conv60", "conv15")]["note"] == "no difference to detect"
    assert plans[("conv30", "conv15")]["p_plus"] == pytest.approx(10 / 21)
    md = (tmp_path / "out" / "report.md").read_text()
    assert "### Planning (shooter): participants for 80 % power" in md
    assert "| conv60 | conv30 | 21 | 0.524 | 0.000 | more than 1000 | – | – |" in md
    assert "| conv60 | conv15 | 21 | – | 1.000 | no difference to detect | – | – |" in md


def test_thesis_report_planning(tmp_path):
    (tmp_path / "hitrates.csv").write_text((DATA / "thesis_table1_hitrates.csv").read_text())
    shutil.copy(DATA / "modes.csv", tmp_path / "modes.csv")
    assert analyze.main([str(tmp_path), "--out", str(tmp_path / "out")]) == 0
    report = json.loads((tmp_path / "out" / "report.json").read_text())
    plans = {(t["a"], t["b"]): t["planning"] for t in report["sign_tests"]}
    # 19 of 20 up: with 8 pairs only 8 of 8 rejects (0.95^8 < 0.8); with 9, 8 or 9 of 9 (c_9 = 1).
    vs15 = plans[("warp15to120", "conv15")]
    assert (vs15["pilot_participants"], vs15["p_plus"], vs15["tie_share"], vs15["needed"]) == (20, 0.95, 0.0, 9)
    assert 0.95 ** 8 < 0.8
    assert vs15["power_at_needed"] == pytest.approx(scipy.stats.binom.sf(7, 9, 0.95) + 0.05 ** 9 + 9 * 0.95 * 0.05 ** 8,
                                                    abs=1e-12)
    assert plans[("warp15to120", "conv120")]["extreme"] and plans[("warp15to120", "conv120")]["needed"] == 6
    md = (tmp_path / "out" / "report.md").read_text()
    section = md[md.index("### Planning (shooter)"):]
    assert "| a | b | pilot n | p+ (a > b) | tie share | needed | power | first ≥ 0.8 |" in section
    assert "| warp15to120 | conv15 | 20 | 0.950 | 0.000 | 9 | 0.929 | 9 |" in section
    assert "| warp15to120 | conv120 | 20 | 0.000 | 0.000 | 6 | 1.000 | 6 |" in section
    for words in ("independent", "α = 0.05", "power 0.8", "two-sided exact sign test", "only estimates",
                  "every larger n up to 1000", "went one way (p+ = 0 or 1) in warp15to120 against conv120; "
                  "conv120 against conv15. Any 6 untied participants then reject"):
        assert words in section, words
