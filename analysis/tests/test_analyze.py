"""analysis/analyze on small exports: the thesis's published numbers (seed 004 Tables 1–3),
ties and empty sign tests, type-7 quartiles, the click game's table and tests checked against
formulas written out here, and one-sentence refusals of bad input.

Most cases call analyze.main() in-process (importing numpy, scipy and matplotlib once keeps the
suite fast); the entry-point tests run `analysis/analyze` as a user would.
"""
import json
import os
import math
import re
import shutil
import statistics
import subprocess
import sys
from pathlib import Path

import pytest
import scipy.stats

ANALYSIS = Path(__file__).resolve().parents[1]
DATA = Path(__file__).resolve().parent / "data"
sys.path.insert(0, str(ANALYSIS))

import analyze  # noqa: E402
from warplab_analysis import papers, players, stats  # noqa: E402

HITRATES_HEADER = "participant,game,mode,shots,hits,timeouts,hit_rate"

# Seed 004 Table 2: per participant, upconverted − 15 Hz and upconverted − 120 Hz, as printed.
THESIS_TABLE2 = {
    "16": (-0.004, -0.133), "20": (0.004, -0.102), "4": (0.044, -0.102), "11": (0.062, -0.178),
    "8": (0.067, -0.107), "13": (0.071, -0.098), "12": (0.084, -0.076), "19": (0.084, -0.129),
    "9": (0.093, -0.067), "10": (0.093, -0.098), "6": (0.093, -0.129), "18": (0.111, -0.089),
    "15": (0.120, -0.044), "1": (0.124, -0.133), "7": (0.124, -0.160), "5": (0.138, -0.098),
    "2": (0.147, -0.093), "3": (0.169, -0.076), "14": (0.182, -0.080), "17": (0.196, -0.084),
}
# Seed 004 Table 3: min, 25 %, median, 75 %, max.
THESIS_TABLE3 = {"conv15": (-0.004, 0.070, 0.093, 0.128, 0.196), "conv120": (-0.178, -0.129, -0.098, -0.083, -0.044)}
SIGN_TEST_KEYS = {"game", "a", "b", "n", "positive", "negative", "ties", "p_greater", "p_less", "p_two_sided",
                  "diff_quartiles", "planning"}


def write(path, lines):
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def with_modes(export, extra=()):
    """modes.csv as warplab exports it (the nine published presets; test_round_trip checks the copy
    against a real export), plus `extra` rows: what the analysis knows of the modes."""
    lines = (DATA / "modes.csv").read_text(encoding="utf-8").splitlines() + list(extra)
    write(export / "modes.csv", lines)
    return export


def hitrate_lines(rows, game="shooter"):
    """rows: (participant, mode, hits, shots)."""
    return [HITRATES_HEADER] + [f"{p},{game},{m},{s},{h},0,{h / s:.6f}" for p, m, h, s in rows]


def run_in_process(export_dir, out_dir, *extra):
    code = analyze.main([str(export_dir), "--out", str(out_dir), *map(str, extra)])
    report = out_dir / "report.json"
    return code, (json.loads(report.read_text()) if code == 0 else None)


def sign_test(report, a, b, game="shooter"):
    (test,) = [t for t in report["sign_tests"] if (t["game"], t["a"], t["b"]) == (game, a, b)]
    return test


@pytest.fixture(scope="module")
def thesis(tmp_path_factory):
    export = tmp_path_factory.mktemp("thesis_export")
    shutil.copy(DATA / "thesis_table1_hitrates.csv", export / "hitrates.csv")
    with_modes(export)
    out = tmp_path_factory.mktemp("thesis_report")
    code, report = run_in_process(export, out)
    assert code == 0
    return report, out


def test_thesis_sign_tests(thesis):
    report, _ = thesis
    vs15 = sign_test(report, "warp15to120", "conv15")
    assert (vs15["n"], vs15["positive"], vs15["negative"], vs15["ties"]) == (20, 19, 1, 0)
    assert vs15["p_greater"] == pytest.approx(2.0027160644531247e-05, rel=1e-12)
    vs120 = sign_test(report, "warp15to120", "conv120")
    assert (vs120["n"], vs120["positive"], vs120["negative"], vs120["ties"]) == (20, 0, 20, 0)
    assert vs120["p_less"] == pytest.approx(9.5367431640624947e-07, rel=1e-12)
    # Two-sided: twice the smaller tail here (n = 20, p = 1/2 is symmetric).
    assert vs15["p_two_sided"] == pytest.approx(2 * 21 / 2 ** 20, rel=1e-12)
    assert vs120["p_greater"] == 1.0 and vs15["p_less"] == pytest.approx(1 - 1 / 2 ** 20, rel=1e-12)
    # Pairs follow the mode order: warp first, then conv120 before conv15; every pair once.
    assert [(t["a"], t["b"]) for t in report["sign_tests"]] == [
        ("warp15to120", "conv120"), ("warp15to120", "conv15"), ("conv120", "conv15")]


def test_thesis_table2_differences(thesis):
    report, _ = thesis
    vs15 = sign_test(report, "warp15to120", "conv15")["differences"]
    vs120 = sign_test(report, "warp15to120", "conv120")["differences"]
    assert set(vs15) == set(THESIS_TABLE2) == set(vs120)
    for participant, (d15, d120) in THESIS_TABLE2.items():
        assert vs15[participant] == pytest.approx(d15, abs=5e-4), participant
        assert vs120[participant] == pytest.approx(d120, abs=5e-4), participant
    # report.json's Table 2: sorted by the difference to conv15 (the lowest-rate conventional mode).
    (table2,) = report["games"]["shooter"]["upconversion_differences"]
    assert table2["mode"] == "warp15to120" and table2["sorted_by"] == "conv15"
    assert table2["against"] == ["conv15", "conv120"]
    column = [row["differences"]["conv15"] for row in table2["rows"]]
    assert column == sorted(column) and table2["rows"][0]["participant"] == "16"
    assert table2["rows"][-1]["participant"] == "17"


def test_thesis_table3_quartiles(thesis):
    report, _ = thesis
    for other, expected in THESIS_TABLE3.items():
        q = sign_test(report, "warp15to120", other)["diff_quartiles"]
        assert [q[k] for k in ("min", "q25", "median", "q75", "max")] == pytest.approx(expected, abs=5e-4)


def test_thesis_report_json_keys_and_files(thesis):
    report, out = thesis
    for test in report["sign_tests"]:
        assert SIGN_TEST_KEYS <= set(test)
        assert set(test["diff_quartiles"]) == {"min", "q25", "median", "q75", "max"}
        assert all(isinstance(test[k], float) for k in ("p_greater", "p_less", "p_two_sided"))
        assert test["participants"] == 20
    assert report["click"] is None and list(report["games"]) == ["shooter"]
    for name in ("report.md", "report.json", "shooter_hit_rates.png", "shooter_differences.png"):
        assert (out / name).is_file(), name
    assert (out / "shooter_hit_rates.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    md = (out / "report.md").read_text()
    assert "](shooter_hit_rates.png)" in md and "](shooter_differences.png)" in md
    assert "2.003e-05" in md and "9.537e-07" in md
    assert "Click game" not in md


def test_ties_are_decided_on_integers_and_dropped(tmp_path):
    rows = [
        ("a", "warp15to120", 10, 20), ("a", "conv15", 5, 10),  # 1/2 = 1/2, unequal shots: tie
        ("b", "warp15to120", 7, 21), ("b", "conv15", 1, 3),  # 1/3 = 1/3: tie
        ("c", "warp15to120", 12, 20), ("c", "conv15", 12, 20),  # equal counts: tie
        ("d", "warp15to120", 15, 20), ("d", "conv15", 10, 20),
        ("e", "warp15to120", 11, 20), ("e", "conv15", 9, 20),
        ("f", "warp15to120", 8, 20), ("f", "conv15", 9, 20),
        # 1/3 against 0.33333333333333333: one double, but a is higher; integers see it.
        ("g", "warp15to120", 1, 3), ("g", "conv15", 33333333333333333, 10 ** 17),
    ]
    write(with_modes(tmp_path) / "hitrates.csv", hitrate_lines(rows))
    code, report = run_in_process(tmp_path, tmp_path / "out")
    assert code == 0
    test = sign_test(report, "warp15to120", "conv15")
    assert (test["n"], test["positive"], test["negative"], test["ties"], test["participants"]) == (4, 3, 1, 3, 7)
    assert test["p_greater"] == pytest.approx(5 / 16, rel=1e-12)  # P(X >= 3), X ~ Bin(4, 1/2)
    assert test["p_less"] == pytest.approx(15 / 16, rel=1e-12)
    assert test["p_two_sided"] == pytest.approx(10 / 16, rel=1e-12)
    assert test["differences"]["a"] == 0.0 and test["differences"]["b"] == 0.0
    # Quartiles over all seven differences, ties (0) included: -0.05, 0, 0, 0, 0, 0.1, 0.25.
    assert test["diff_quartiles"]["median"] == pytest.approx(0.0, abs=1e-12)
    assert test["diff_quartiles"]["q75"] == pytest.approx(0.05, abs=1e-12)
    assert test["diff_quartiles"]["q25"] == pytest.approx(0.0, abs=1e-12)


def test_all_participants_equal_gives_n_zero(tmp_path):
    rows = [(p, m, 9, 20) for p in ("p1", "p2", "p3") for m in ("warp15to120", "conv120")]
    write(with_modes(tmp_path) / "hitrates.csv", hitrate_lines(rows))
    code, report = run_in_process(tmp_path, tmp_path / "out")
    assert code == 0
    test = sign_test(report, "warp15to120", "conv120")
    assert (test["n"], test["positive"], test["negative"], test["ties"]) == (0, 0, 0, 3)
    assert test["p_greater"] == test["p_less"] == test["p_two_sided"] == 1.0
    assert list(test["diff_quartiles"].values()) == [0.0] * 5
    assert "no untied pairs remain" in (tmp_path / "out" / "report.md").read_text()


def test_type7_quartiles_by_hand():
    q = stats.quartiles([4, 1, 3, 2])
    # Type 7: position h = (n − 1)p; [1, 2, 3, 4] at 0.75, 1.5, 2.25 -> 1.75, 2.5, 3.25.
    assert (q["min"], q["q25"], q["median"], q["q75"], q["max"]) == pytest.approx((1, 1.75, 2.5, 3.25, 4))
    q = stats.quartiles([0.0, 10.0, 20.0, 30.0, 100.0])
    assert (q["q25"], q["median"], q["q75"]) == pytest.approx((10.0, 20.0, 30.0))
    assert stats.quartiles([]) is None


def test_one_mode_games_and_missing_modes(tmp_path):
    rows = [("NA", "warp15to120", 5, 10), ("NA", "conv15", 3, 10), ("'=1+1", "warp15to120", 4, 10),
            ("'=1+1", "conv15", 5, 10), ("x", "warp15to120", 6, 10)]  # x lacks conv15: left out of the pair
    lines = hitrate_lines(rows) + hitrate_lines([("p1", "conv60", 1, 5), ("p2", "conv60", 2, 5)], "other")[1:]
    write(with_modes(tmp_path) / "hitrates.csv", lines)
    code, report = run_in_process(tmp_path, tmp_path / "out")
    assert code == 0
    test = sign_test(report, "warp15to120", "conv15")
    assert test["participants"] == 2 and set(test["differences"]) == {"NA", "'=1+1"}
    assert (test["positive"], test["negative"]) == (1, 1)
    assert not [t for t in report["sign_tests"] if t["game"] == "other"]
    assert report["games"]["other"]["modes"] == ["conv60"]
    md = (tmp_path / "out" / "report.md").read_text()
    assert "Only one mode (conv60): no pairs to test." in md



def test_a_mode_played_without_a_shot_has_no_rate_and_enters_no_test(tmp_path):
    # hitrates.csv has a row for every participant x mode run; one without a click (shots 0, an
    # empty hit_rate) is as if the participant lacked the mode: no 0/0, no rate of 0 in a mean.
    rows = [("a", "warp15to120", 5, 10), ("a", "conv15", 3, 10), ("b", "warp15to120", 4, 10),
            ("b", "conv15", 5, 10), ("c", "warp15to120", 6, 10)]
    write(with_modes(tmp_path) / "hitrates.csv", hitrate_lines(rows) + ["c,shooter,conv15,0,0,0,"])
    code, report = run_in_process(tmp_path, tmp_path / "out")
    assert code == 0
    test = sign_test(report, "warp15to120", "conv15")
    assert test["participants"] == 2 and set(test["differences"]) == {"a", "b"}
    assert "conv15" not in report["games"]["shooter"]["hit_rates"]["c"]

# The click game: two scored matches per participant and mode, a practice match that must not
# count, two rating statements; P5 lacks conv15 (paired tests use whom they can, the ANOVA drops P5).
MODES = ["bireproj15to60", "conv60", "conv15"]
STATEMENTS = ["I enjoyed playing this game", "This game was difficult to play"]
# (participant, mode): [(green, red, misses, rating_1, rating_2), ...]; None: the rating is missing.
CLICK = {
    ("P1", "bireproj15to60"): [(30, 3, 20, 5, 4), (32, 2, 22, 6, 4)],
    ("P1", "conv60"): [(41, 1, 15, 6, 3), (44, 2, 14, 7, 2)],
    ("P1", "conv15"): [(29, 4, 26, 3, 5), (31, 3, 24, 2, 5)],
    ("P2", "bireproj15to60"): [(25, 5, 30, 4, 5), (27, 4, 28, 4, None)],
    ("P2", "conv60"): [(38, 2, 18, 6, 3), (36, 3, 17, 5, 3)],
    ("P2", "conv15"): [(26, 4, 31, 2, 6), (24, 5, 33, 3, 6)],
    ("P3", "bireproj15to60"): [(35, 2, 18, 5, 3), (33, 3, 19, 5, 4)],
    ("P3", "conv60"): [(47, 1, 12, 7, 2), (45, 0, 13, 6, 2)],
    ("P3", "conv15"): [(36, 2, 22, 3, 4), (34, 3, 21, 2, 5)],
    ("P4", "bireproj15to60"): [(28, 4, 24, 3, 5), (30, 3, 23, 4, 5)],
    ("P4", "conv60"): [(37, 2, 16, 5, 4), (39, 1, 17, 6, 3)],
    ("P4", "conv15"): [(27, 5, 27, 2, 6), (29, 4, 25, 1, 7)],
    ("P5", "bireproj15to60"): [(31, 3, 21, 5, 4), (29, 2, 20, 4, 4)],
    ("P5", "conv60"): [(40, 2, 16, 6, 3), (42, 1, 15, 6, 2)],
}
MATCH_HEADER = ("participant,session,round,scored_phase,match,mode,stand_in,green_hits,red_hits,misses,clicks,"
                "duration_s,rating_1,rating_2")


def fmt_cell(v):
    return "" if v is None else str(v)


GAMES_HEADER = "game,hits_are,shots_are"


def write_click_export(export, game="click", rename=None, table=None, scale=None):
    """rename: {mode of CLICK: the name the export gives it}; table: writes the condition table
    (default: with_modes); scale: (ratings.min, ratings.max) for ratings.csv's scale_min and
    scale_max, None for an export from before those columns."""
    rename = rename or {}
    (table or with_modes)(export)
    write(export / "games.csv", [GAMES_HEADER, f"{game},green hits,clicks"])
    matches = [MATCH_HEADER]
    ratings = ["participant,session,round,scored_phase,match,mode,statement_index,statement,value,answered_with"
               + (",scale_min,scale_max" if scale else "")]
    scale_cells = f",{scale[0]},{scale[1]}" if scale else ""
    hitrates = {}
    k = 0
    for (p, preset), games in CLICK.items():
        mode = rename.get(preset, preset)
        practice = [(99, 0, 0, 1, 1)]  # wild values: must be ignored
        for scored, (g, r, m, *rs) in [(False, x) for x in practice] + [(True, x) for x in games]:
            phase, flag = ("scored", "true") if scored else ("practice", "false")
            stand_in = "bidirectional reprojection" if mode == "bireproj15to60" else ""
            matches.append(f"{p},{p}_s.db,{phase},{flag},{k},{mode},{stand_in},{g},{r},{m},{g + r + m},45.0,"
                           + ",".join(fmt_cell(v) for v in rs))
            for i, v in enumerate(rs):
                if v is not None:
                    ratings.append(f'{p},{p}_s.db,{phase},{flag},{k},{mode},{i},"{STATEMENTS[i]}",{v},key'
                                   + scale_cells)
            if scored:
                hits, shots = hitrates.get((p, mode), (0, 0))
                hitrates[(p, mode)] = (hits + g, shots + g + r + m)
            k += 1
    write(export / "matches.csv", matches)
    write(export / "ratings.csv", ratings)
    write(export / "hitrates.csv", hitrate_lines([(p, m, h, s) for (p, m), (h, s) in hitrates.items()], game))
    write(export / "sessions.csv", ["file,participant,game,protocol,seed,started_at,player,completed,flags,status,"
                                    "included,trials,matches,note"]
          + [f"{p}_s.db,{p},{game},click-yang,1,2024-01-01T00:00:00Z,human,true,,ok,true,0,21,"
             for p in ("P1", "P2", "P3", "P4", "P5")]
          + [f"P6_s.db,P6,{game},click-yang,1,2024-01-01T00:00:00Z,human,false,,cut,false,0,3,cut short"])


def participant_means(index):
    """{participant: {mode: mean over that participant's scored matches}} of measure `index`."""
    means = {}
    for (p, mode), games in CLICK.items():
        values = [g[index] for g in games if g[index] is not None]
        means.setdefault(p, {})[mode] = sum(values) / len(values)
    return means


@pytest.fixture(scope="module")
def click(tmp_path_factory):
    export = tmp_path_factory.mktemp("click_export")
    write_click_export(export)
    out = tmp_path_factory.mktemp("click_report")
    code, report = run_in_process(export, out)
    assert code == 0
    return report, out


def test_click_means_and_sds(click):
    report, _ = click
    c = report["click"]
    assert c["reference_mode"] == "bireproj15to60" and c["modes"] == MODES
    assert c["scored_matches"] == 28 and c["participants"] == ["P1", "P2", "P3", "P4", "P5"]
    assert list(c["measures"]) == ["green_hits", "red_hits", "misses", "rating_1", "rating_2"]
    assert [m["label"] for m in c["measures"].values()] == ["Green hits", "Red hits", "Misses"] + STATEMENTS
    for index, key in enumerate(c["measures"]):
        means = participant_means(index)
        for mode in MODES:
            values = [row[mode] for row in means.values() if mode in row]
            entry = c["measures"][key]["modes"][mode]
            assert entry["n"] == len(values)
            assert entry["mean"] == pytest.approx(statistics.mean(values), rel=1e-12)
            assert entry["sd"] == pytest.approx(statistics.stdev(values), rel=1e-12)
    # A hand check on one cell: conv60 green hits per participant 42.5, 37, 46, 38, 41.
    assert c["measures"]["green_hits"]["modes"]["conv60"]["mean"] == pytest.approx(40.9)
    # P2's missing rating: their bireproj mean of rating_2 is the one answered match (5).
    assert c["measures"]["rating_2"]["participant_means"]["P2"]["bireproj15to60"] == 5.0


def test_click_paired_t_against_hand_formula(click):
    report, _ = click
    c = report["click"]
    for index, key in enumerate(c["measures"]):
        means = participant_means(index)
        for mode in ("conv60", "conv15"):
            d = [row[mode] - row["bireproj15to60"] for row in means.values() if mode in row]
            n = len(d)
            mean, sd = sum(d) / n, math.sqrt(sum((x - sum(d) / n) ** 2 for x in d) / (n - 1))
            t = mean / (sd / math.sqrt(n))
            p = 2 * scipy.stats.t.sf(abs(t), n - 1)
            v = c["measures"][key]["modes"][mode]["vs_reference"]
            assert v["n"] == n and v["df"] == n - 1
            assert v["t"] == pytest.approx(t, rel=1e-9) and v["p_t"] == pytest.approx(p, rel=1e-9)
            positive, negative = sum(x > 0 for x in d), sum(x < 0 for x in d)
            assert (v["positive"], v["negative"], v["ties"]) == (positive, negative, n - positive - negative)
            assert 0.0 < v["p_wilcoxon"] <= 1.0 and 0.0 < v["p_sign"] <= 1.0
    assert c["measures"]["green_hits"]["modes"]["bireproj15to60"]["vs_reference"] is None
    # Green hits, conv60 against bireproj: every participant hit more, so the sign test is 2 / 2^5.
    v = c["measures"]["green_hits"]["modes"]["conv60"]["vs_reference"]
    assert (v["positive"], v["n"]) == (5, 5) and v["p_sign"] == pytest.approx(2 / 32, rel=1e-12)
    # Wilcoxon, exact: all five signed ranks positive, two-sided p = 2 / 2^5.
    assert v["p_wilcoxon"] == pytest.approx(2 / 32, rel=1e-12)


def test_click_anova_against_hand_formula(click):
    pytest.importorskip("statsmodels")
    report, _ = click
    c = report["click"]
    for index, key in enumerate(c["measures"]):
        means = participant_means(index)
        complete = [row for row in means.values() if all(m in row for m in MODES)]  # P5 dropped
        n, k = len(complete), len(MODES)
        grand = sum(row[m] for row in complete for m in MODES) / (n * k)
        ss_modes = n * sum((sum(row[m] for row in complete) / n - grand) ** 2 for m in MODES)
        ss_subjects = k * sum((sum(row[m] for m in MODES) / k - grand) ** 2 for row in complete)
        ss_total = sum((row[m] - grand) ** 2 for row in complete for m in MODES)
        ss_error = ss_total - ss_modes - ss_subjects
        f = (ss_modes / (k - 1)) / (ss_error / ((k - 1) * (n - 1)))
        anova = c["measures"][key]["anova"]
        assert anova["F"] == pytest.approx(f, rel=1e-9)
        assert (anova["df_num"], anova["df_den"]) == (k - 1, (k - 1) * (n - 1))
        assert anova["p"] == pytest.approx(scipy.stats.f.sf(f, k - 1, (k - 1) * (n - 1)), rel=1e-9)
        assert (anova["participants"], anova["dropped"]) == (4, 1)


def test_click_report_and_figures(click):
    report, out = click
    md = (out / "report.md").read_text()
    assert "## Click game" in md and "I enjoyed playing this game" in md
    assert "F(1, n − 1) = t²" in md and "](click_measures.png)" in md
    assert "Sessions (sessions.csv): 5 of 6 included" in md
    assert "Table 1 (click)" in md  # hit rates: green hits / clicks, with their sign tests
    assert "#### Planning (click): participants for 80 % power" in md  # and what a study would need
    assert all(t["planning"]["pilot_participants"] == t["participants"] for t in report["sign_tests"])
    assert (out / "click_measures.png").stat().st_size > 10_000
    assert "Pulkkinen" not in md  # no shooter data, no shooter section
    assert [t["game"] for t in report["sign_tests"]] == ["click"] * 3
    # games.csv's words for what the click game's hit rate counts.
    assert "rate = green hits out of clicks" in md and "### Hit rates: green hits / clicks" in md
    assert report["click"]["game"] == "click"
    assert report["games"]["click"]["hits_are"] == "green hits"


def test_the_condition_column_reads_under_its_old_name_too(tmp_path):
    # Exports name each row's condition in a column `condition`; older ones called it `mode`.
    # The same data under either header gives the same report.
    old, new = tmp_path / "old", tmp_path / "new"
    old.mkdir()
    write_click_export(old)
    shutil.copytree(old, new)
    renamed = 0
    for name in ("hitrates.csv", "matches.csv", "answers.csv"):
        if not (new / name).exists():
            continue
        lines = (new / name).read_text().split("\n")
        header = lines[0].split(",")
        assert "mode" in header and "condition" not in header, name
        lines[0] = ",".join("condition" if c == "mode" else c for c in header)
        (new / name).write_text("\n".join(lines))
        renamed += 1
    assert renamed >= 2
    code_old, report_old = run_in_process(old, tmp_path / "out-old")
    code_new, report_new = run_in_process(new, tmp_path / "out-new")
    assert code_old == code_new == 0
    for report in (report_old, report_new):
        report.pop("export_dir")
    assert report_new == report_old
    assert report_new["click"]["modes"] == MODES


def test_matches_sections_follow_the_data_not_the_game_name(tmp_path):
    # The click game's data under another name: the matches' sections go with the game whose
    # sessions (sessions.csv) played them, and the wording is games.csv's.
    write_click_export(tmp_path, game="spheres")
    code, report = run_in_process(tmp_path, tmp_path / "out")
    assert code == 0
    md = (tmp_path / "out" / "report.md").read_text()
    assert "## Spheres game (Yang et al. 2011, seed 000 §8)" in md and "Click game" not in md
    assert "F(1, n − 1) = t²" in md and "Pulkkinen" not in md
    assert "rate = green hits out of clicks" in md and "### Hit rates: green hits / clicks" in md
    assert report["click"]["game"] == "spheres" and report["click"]["modes"] == MODES
    # Without sessions.csv nothing says whose matches they are: a section of their own.
    (tmp_path / "sessions.csv").unlink()
    code, report = run_in_process(tmp_path, tmp_path / "out2")
    assert code == 0
    md = (tmp_path / "out2" / "report.md").read_text()
    assert report["click"]["game"] is None
    assert "## Matches (Yang et al. 2011, seed 000 §8)" in md and "## Spheres: hit rates" in md
    assert md.index("## Spheres: hit rates") < md.index("## Matches")
    # games.csv's `tables` (exports since games own their tables) says it without sessions.csv.
    # A game without tables of its own has an empty cell there.
    write(tmp_path / "games.csv", [GAMES_HEADER + ",tables", "shooter,hits,shots,",
                                   "spheres,green hits,clicks,matches.csv;ratings.csv"])
    code, report = run_in_process(tmp_path, tmp_path / "out3")
    assert code == 0 and report["click"]["game"] == "spheres"


def test_modes_follow_modes_csv(tmp_path):
    # A mode the analysis has never heard of, described by modes.csv alone: a 20 Hz conventional
    # mode and a made-up upconversion mode. Order, Table 2 and descriptions all follow the file.
    with_modes(tmp_path, ['conv20,"conventional rendering at 20 Hz, held",20,0,none,,,false',
                          'blend20to60,"blended from 20 Hz, to 60 Hz",20,0,bidirectional,60,blend,true'])
    rows = [(p, m, h, 20) for p, base in (("a", 5), ("b", 7), ("c", 9))
            for m, h in (("conv15", base), ("conv20", base + 1), ("blend20to60", base + 3), ("lag50", base - 2))]
    write(tmp_path / "hitrates.csv", hitrate_lines(rows))
    code, report = run_in_process(tmp_path, tmp_path / "out")
    assert code == 0
    assert report["games"]["shooter"]["modes"] == ["blend20to60", "conv20", "conv15", "lag50"]
    (table2,) = report["games"]["shooter"]["upconversion_differences"]
    assert table2["mode"] == "blend20to60" and table2["sorted_by"] == "conv15"
    assert sign_test(report, "blend20to60", "conv15")["positive"] == 3
    md = (tmp_path / "out" / "report.md").read_text()
    assert "blend20to60 (blended from 20 Hz, to 60 Hz); conv20 (conventional rendering at 20 Hz, held)" in md
    assert (tmp_path / "out" / "shooter_differences.png").is_file()


def test_without_modes_csv_modes_are_in_id_order_with_a_note(tmp_path):
    rows = [(p, m, h, 20) for p, h in (("a", 5), ("b", 7)) for m in ("warp15to120", "conv15")]
    write(tmp_path / "hitrates.csv", hitrate_lines(rows))
    code, report = run_in_process(tmp_path, tmp_path / "out")
    assert code == 0
    assert report["games"]["shooter"]["modes"] == ["conv15", "warp15to120"]
    assert report["games"]["shooter"]["upconversion_differences"] == []
    md = (tmp_path / "out" / "report.md").read_text()
    assert "No modes.csv" in md and "Modes: conv15; warp15to120." in md


# What the analysis reported for exports written before conditions.csv (modes.csv, or neither),
# as analysis/analyze wrote it from these exports before it read conditions.csv. Such an export
# must keep giving the same numbers, orders and notes.
BEFORE = DATA / "modes_csv_reports"
# report.json's keys that the analysis has added since the pinned reports were written: the
# condition table's rows (here modes.csv's, mapped) and which file they come from.
# Added since, each said once: who played (unknown in these exports: a note), the questions.
ADDED_KEYS = {"conditions", "conditions_file", "players", "questions", "group_notes"}


def modes_csv_exports(base):
    """{name: export folder}: "both", the click export with the thesis's shooter rows (modes.csv,
    games.csv, sessions.csv); "bare", hit rates alone (no modes.csv)."""
    both, bare = base / "both", base / "bare"
    both.mkdir()
    bare.mkdir()
    write_click_export(both)
    shooter = (DATA / "thesis_table1_hitrates.csv").read_text().splitlines()[1:]
    with open(both / "hitrates.csv", "a") as f:
        f.write("\n".join(shooter) + "\n")
    write(both / "games.csv", [GAMES_HEADER, "shooter,hits,shots", "click,green hits,clicks"])
    rows = [(p, m, h, 20) for p, h in (("a", 5), ("b", 7), ("c", 9)) for m in ("warp15to120", "conv15", "lag50")]
    write(bare / "hitrates.csv", hitrate_lines(rows))
    return {"both": both, "bare": bare}


def assert_same(got, expected, where):
    """Equal, floats to 12 significant digits (another scipy may differ in the last bits)."""
    if isinstance(expected, dict):
        assert isinstance(got, dict) and list(got) == list(expected), where
        for key in expected:
            assert_same(got[key], expected[key], f"{where}.{key}")
    elif isinstance(expected, list):
        assert isinstance(got, list) and len(got) == len(expected), where
        for k, (g, e) in enumerate(zip(got, expected)):
            assert_same(g, e, f"{where}[{k}]")
    elif isinstance(expected, float):
        assert got == pytest.approx(expected, rel=1e-12, abs=1e-15), where
    else:
        assert got == expected, where


def without_conditions_section(md):
    """report.md less what was added since: the section that describes each condition's parts, and
    the sections setting the papers' people beside the study."""
    md = re.sub(r"### Beside the papers' people.*?(?=\n#{1,3} |\Z)", "", md, flags=re.S)
    return re.sub(r"## Conditions\n.*?(?=\n## )", "", md, flags=re.S).replace("\n\n\n", "\n\n")


@pytest.mark.parametrize("name", ["both", "bare"])
def test_modes_csv_export_reports_as_before(tmp_path, name):
    export = modes_csv_exports(tmp_path)[name]
    code, report = run_in_process(export, tmp_path / "out")
    assert code == 0
    expected = json.loads((BEFORE / f"{name}.json").read_text(encoding="utf-8"))
    assert report.pop("export_dir") == str(export)
    assert set(report) - set(expected) == ADDED_KEYS and set(expected) <= set(report)
    assert report["conditions_file"] == ("modes.csv" if name == "both" else None)
    assert [r["condition"] for r in report["conditions"]] == [m["mode"] for m in expected["modes"]]
    if report["sessions"]:
        assert report["sessions"].pop("players") == {"human": 5}  # added since: who played, by kind
    report["notes"].remove(players.UNKNOWN_NOTE)
    assert report["players"]["kinds"] is None and report["questions"] == [] and report["group_notes"] == []
    assert_same({k: report[k] for k in expected}, expected, "report")
    md = (tmp_path / "out" / "report.md").read_text(encoding="utf-8").replace(str(export), "EXPORT")
    md = md.replace(players.UNKNOWN_NOTE + "\n\n", "")
    assert without_conditions_section(md) == (BEFORE / f"{name}.md").read_text(encoding="utf-8")


def test_click_reference_fallback_and_no_statsmodels(tmp_path, monkeypatch):
    write_click_export(tmp_path)
    monkeypatch.setitem(sys.modules, "statsmodels", None)  # `import statsmodels` now raises ImportError
    monkeypatch.setitem(sys.modules, "statsmodels.stats.anova", None)
    code, report = run_in_process(tmp_path, tmp_path / "out", "--reference-mode", "warp15to120")
    assert code == 0
    c = report["click"]
    assert c["reference_mode"] == "bireproj15to60" and c["reference_requested"] == "warp15to120"
    assert any("warp15to120 is not in the scored matches" in note for note in c["notes"])
    assert c["anova_available"] is False and all(m["anova"] is None for m in c["measures"].values())
    assert c["measures"]["green_hits"]["modes"]["conv60"]["vs_reference"]["p_t"] > 0
    md = (tmp_path / "out" / "report.md").read_text()
    assert "statsmodels is not installed" in md and "Reference mode: bireproj15to60." in md


def test_paired_tests_with_all_differences_zero():
    v = stats.paired_tests([3, 4, 5], [3, 4, 5])
    assert (v["p_t"], v["t"], v["p_wilcoxon"], v["p_sign"], v["ties"]) == (1.0, 0.0, 1.0, 1.0, 3)


def test_all_phases_export_counts_only_scored_rows(click):
    report, _ = click
    # The practice matches have 99 green hits; a mean above 50 would mean one was counted.
    assert all(e["mean"] < 50 for e in report["click"]["measures"]["green_hits"]["modes"].values())


BAD_CASES = {
    "empty file": ("hitrates.csv", [], "hitrates.csv", "empty"),
    "missing column": ("hitrates.csv", ["participant,game,mode,shots", "a,shooter,conv15,10"], "'hits'", "missing"),
    "non-numeric": ("hitrates.csv", hitrate_lines([("a", "conv15", 3, 10), ("b", "conv15", 4, 10)])[:2]
                    + ["b,shooter,conv15,10,four,0,0.4"], "'hits'", "line 3"),
    "negative": ("hitrates.csv", hitrate_lines([("a", "conv15", 3, 10)]) + ["b,shooter,conv15,10,-1,0,0"], "'hits'",
                 "negative"),
    "hits above shots": ("hitrates.csv", hitrate_lines([("a", "conv15", 3, 10), ("b", "conv15", 11, 10)]), "'hits'",
                         "line 3"),
    "hits with zero shots": ("hitrates.csv", hitrate_lines([("a", "conv15", 3, 10)]) + ["b,shooter,conv15,0,1,0,"],
                             "'hits'", "line 3"),
    "one participant": ("hitrates.csv", hitrate_lines([("a", "conv15", 3, 10), ("a", "conv60", 5, 10)]),
                        "'participant'", "at least two participants"),
    "no rows": ("hitrates.csv", [HITRATES_HEADER], "hitrates.csv", "no data rows"),
    "bad match count": ("matches.csv", [MATCH_HEADER, "a,s,scored,true,0,conv15,,many,1,2,3,45,,"], "'green_hits'",
                        "line 2"),
    "bad scored_phase": ("matches.csv", [MATCH_HEADER, "a,s,scored,yes,0,conv15,,1,1,2,4,45,,"], "'scored_phase'",
                         "line 2"),
    "bad rating": ("matches.csv", [MATCH_HEADER, "a,s,scored,true,0,conv15,,1,1,2,4,45,5,good"], "'rating_2'",
                   "line 2"),
    # Yang et al.'s scale, 1 to 7 (the protocol's default): a 9 would move the mode's mean.
    "rating above the scale": ("matches.csv", [MATCH_HEADER, "a,s,scored,true,0,conv15,,1,1,2,4,45,9,3"],
                               "'rating_1'", "line 2, column 'rating_1' is 9, outside the rating scale 1 to 7"),
    "rating below the scale": ("matches.csv", [MATCH_HEADER, "a,s,scored,true,0,conv15,,1,1,2,4,45,4,0"],
                               "'rating_2'", "line 2, column 'rating_2' is 0, outside the rating scale 1 to 7"),
    "rating_2 without rating_1": ("matches.csv", [MATCH_HEADER.replace(",rating_1", ""),
                                                  "a,s,scored,true,0,conv15,,1,1,2,4,45,3"],
                                  "'rating_1'", "line 1, the header, has column 'rating_2' but no column 'rating_1'"),
    # A count no study has: it passed every other check as a whole, finite number.
    "huge count": ("hitrates.csv", hitrate_lines([("a", "conv15", 3, 10)]) + ["b,shooter,conv15,1e308,1,0,0"],
                   "'shots'", "more than any study counts"),
}


def test_a_pipe_named_like_a_csv_is_refused_not_waited_on(tmp_path, capsys):
    os.mkfifo(tmp_path / "hitrates.csv")
    assert analyze.main([str(tmp_path), "--out", str(tmp_path / "out")]) == 1
    err = capsys.readouterr().err
    assert "hitrates.csv" in err and "is not a regular file" in err and len(err.strip().splitlines()) == 1


@pytest.mark.parametrize("case", sorted(BAD_CASES))
def test_bad_input_is_one_sentence_naming_file_and_column(tmp_path, capsys, case):
    name, lines, column, detail = BAD_CASES[case]
    if name != "hitrates.csv":
        write(tmp_path / "hitrates.csv", hitrate_lines([("a", "conv15", 3, 10), ("b", "conv15", 4, 10)]))
    if lines:
        write(tmp_path / name, lines)
    else:
        (tmp_path / name).write_bytes(b"")
    code = analyze.main([str(tmp_path), "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert code == 1
    assert len(err.strip().splitlines()) == 1, err
    assert name in err and column in err and detail in err, err
    assert not (tmp_path / "out" / "report.json").exists()


def drop_column(path, name):
    lines = path.read_text().splitlines()
    k = lines[0].split(",").index(name)
    path.write_text("".join(",".join(c for i, c in enumerate(line.split(",")) if i != k) + "\n" for line in lines))


def test_a_statement_without_its_rating_column_is_refused(tmp_path, capsys):
    """ratings.csv lists statement 0 but matches.csv has no rating_1: the measure would vanish."""
    write_click_export(tmp_path)
    drop_column(tmp_path / "matches.csv", "rating_1")
    drop_column(tmp_path / "matches.csv", "rating_2")
    assert analyze.main([str(tmp_path), "--out", str(tmp_path / "out")]) == 1
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1, err
    assert ("matches.csv: line 1, the header, has no column 'rating_1', but" in err
            and "ratings.csv lists statement 0 (statement_index, line 2)" in err), err
    assert not (tmp_path / "out" / "report.json").exists()


def test_a_rating_outside_the_scale_is_refused_and_another_scale_can_be_given(tmp_path, capsys):
    write_click_export(tmp_path)
    lines = (tmp_path / "matches.csv").read_text().splitlines()
    line = next(k for k, row in enumerate(lines) if row.startswith("P1,") and ",true," in row)
    cells = lines[line].split(",")
    cells[-2] = "9"  # rating_1 of a scored match
    lines[line] = ",".join(cells)
    (tmp_path / "matches.csv").write_text("\n".join(lines) + "\n")
    assert analyze.main([str(tmp_path), "--out", str(tmp_path / "out")]) == 1
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1, err
    assert f"matches.csv: line {line + 1}, column 'rating_1' is 9, outside the rating scale 1 to 7" in err, err
    assert "--rating-scale" in err
    # A protocol with ratings.min 0 and max 10 says so.
    assert analyze.main([str(tmp_path), "--out", str(tmp_path / "out"), "--rating-scale", "0:10"]) == 0
    with pytest.raises(SystemExit):
        analyze.main([str(tmp_path), "--out", str(tmp_path / "out"), "--rating-scale", "7:1"])


def set_scored_rating(export, value, column=1):
    """Sets rating_`column` of P1's first scored match in matches.csv; returns that row's line."""
    lines = (export / "matches.csv").read_text().splitlines()
    line = next(k for k, row in enumerate(lines) if row.startswith("P1,") and ",true," in row)
    cells = lines[line].split(",")
    cells[len(cells) - len(STATEMENTS) + column - 1] = str(value)
    lines[line] = ",".join(cells)
    (export / "matches.csv").write_text("\n".join(lines) + "\n")
    return line + 1


def test_a_study_on_a_0_to_10_scale_needs_no_flag(tmp_path):
    """ratings.csv records the protocol's scale: a 9 on 0 to 10 is an answer, not bad input."""
    write_click_export(tmp_path, scale=(0, 10))
    set_scored_rating(tmp_path, 9)
    code, report = run_in_process(tmp_path, tmp_path / "out")
    assert code == 0
    means = report["click"]["measures"]["rating_1"]["participant_means"]
    assert means["P1"]["bireproj15to60"] == (9 + 6) / 2


def test_a_rating_outside_the_recorded_scale_is_refused(tmp_path, capsys):
    write_click_export(tmp_path, scale=(0, 10))
    line = set_scored_rating(tmp_path, 11, column=2)
    assert analyze.main([str(tmp_path), "--out", str(tmp_path / "out")]) == 1
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1, err
    assert (f"matches.csv: line {line}, column 'rating_2' is 11, outside the rating scale 0 to 10 (statement 1's "
            "scale_min and scale_max in " in err and "ratings.csv, line " in err), err
    assert not (tmp_path / "out" / "report.json").exists()


def test_an_export_without_the_scale_columns_uses_1_to_7_or_the_flag(tmp_path, capsys):
    """Exports from before scale_min and scale_max: the protocol's default scale, or the one given."""
    write_click_export(tmp_path)
    line = set_scored_rating(tmp_path, 9)
    assert analyze.main([str(tmp_path), "--out", str(tmp_path / "out")]) == 1
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1, err
    assert (f"matches.csv: line {line}, column 'rating_1' is 9, outside the rating scale 1 to 7 (the protocol's "
            "default ratings.min and ratings.max: ratings.csv has no scale_min and scale_max" in err
            and "--rating-scale MIN:MAX" in err), err
    assert analyze.main([str(tmp_path), "--out", str(tmp_path / "out"), "--rating-scale", "0:10"]) == 0


def test_the_flag_overrides_the_recorded_scale(tmp_path, capsys):
    write_click_export(tmp_path, scale=(0, 10))
    line = set_scored_rating(tmp_path, 9)
    assert analyze.main([str(tmp_path), "--out", str(tmp_path / "out"), "--rating-scale", "1:7"]) == 1
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1, err
    assert (f"matches.csv: line {line}, column 'rating_1' is 9, outside the rating scale 1 to 7 (as "
            "--rating-scale gives it)." in err), err


def rewrite_ratings_cell(export, row, column, value):
    """Sets `column` of ratings.csv's data row `row` (0-based); returns the row's line."""
    lines = (export / "ratings.csv").read_text().splitlines()
    header = lines[0].split(",")
    cells = lines[row + 1].split(",")
    cells[header.index(column) - len(header)] = value  # from the end: statements hold no commas there
    lines[row + 1] = ",".join(cells)
    (export / "ratings.csv").write_text("\n".join(lines) + "\n")
    return row + 2


# (row, column, value, what the sentence says after "ratings.csv: line N, column 'C' ")
BAD_SCALES = {
    "rows of one statement disagree": (2, "scale_max", "7", "is 7, but statement 0's scale_max is 10 on line 2"),
    "not a whole number": (0, "scale_min", "0.5", "is not a whole number: '0.5'"),
    "empty": (0, "scale_max", "", "is empty"),
    "min not below max": (0, "scale_min", "10", "is 10, not below column 'scale_max' (10)"),
}


@pytest.mark.parametrize("case", sorted(BAD_SCALES))
def test_a_bad_recorded_scale_is_refused(tmp_path, capsys, case):
    row, column, value, detail = BAD_SCALES[case]
    write_click_export(tmp_path, scale=(0, 10))
    line = rewrite_ratings_cell(tmp_path, row, column, value)
    assert analyze.main([str(tmp_path), "--out", str(tmp_path / "out")]) == 1
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1, err
    assert f"ratings.csv: line {line}, column '{column}' {detail}" in err, err
    assert not (tmp_path / "out" / "report.json").exists()


def test_half_a_recorded_scale_is_refused(tmp_path, capsys):
    write_click_export(tmp_path, scale=(0, 10))
    drop_column(tmp_path / "ratings.csv", "scale_max")
    assert analyze.main([str(tmp_path), "--out", str(tmp_path / "out")]) == 1
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1, err
    assert "ratings.csv: line 1, the header, has column 'scale_min' but no column 'scale_max'" in err, err


def test_missing_folder_and_missing_hitrates(tmp_path, capsys):
    assert analyze.main([str(tmp_path / "nowhere"), "--out", str(tmp_path / "out")]) == 1
    err = capsys.readouterr().err
    assert "nowhere" in err and len(err.strip().splitlines()) == 1
    assert analyze.main([str(tmp_path), "--out", str(tmp_path / "out")]) == 1
    err = capsys.readouterr().err
    assert "hitrates.csv" in err and "no such file" in err and len(err.strip().splitlines()) == 1


def run_entry_point(*args):
    return subprocess.run([str(ANALYSIS / "analyze"), *map(str, args)], capture_output=True, text=True, timeout=120)


def test_entry_point_writes_the_report(tmp_path):
    write_click_export(tmp_path)
    # Both games: the thesis's shooter rows appended to the click export's hit rates.
    shooter = (DATA / "thesis_table1_hitrates.csv").read_text().splitlines()[1:]
    with open(tmp_path / "hitrates.csv", "a") as f:
        f.write("\n".join(shooter) + "\n")
    write(tmp_path / "games.csv", [GAMES_HEADER, "shooter,hits,shots", "click,green hits,clicks"])
    out = tmp_path / "report"
    result = run_entry_point(tmp_path, "--out", out)
    assert result.returncode == 0, result.stderr
    printed = result.stdout.split()
    for name in ("report.md", "report.json", "shooter_hit_rates.png", "shooter_differences.png",
                 "click_hit_rates.png", "click_measures.png"):
        assert (out / name).is_file() and str(out / name) in printed, name
    md = (out / "report.md").read_text()
    assert md.index("## Shooter") < md.index("## Click game")
    report = json.loads((out / "report.json").read_text())
    assert set(report["games"]) == {"shooter", "click"} and report["click"]["reference_mode"] == "bireproj15to60"


def test_entry_point_bad_input_has_no_traceback(tmp_path):
    write(tmp_path / "hitrates.csv", hitrate_lines([("a", "conv15", 3, 10), ("b", "conv15", 4, 10)])[:2]
          + ["b,shooter,conv15,ten,4,0,0.4"])
    result = run_entry_point(tmp_path, "--out", tmp_path / "out")
    assert result.returncode == 1
    assert result.stderr.strip().splitlines() == [
        f"analyze: {tmp_path / 'hitrates.csv'}: line 3, column 'shots' is not a number: 'ten'."]
    assert "Traceback" not in result.stderr and result.stdout == ""


def test_anova_without_residual_variation_is_infinite_not_rounding_noise():
    pytest.importorskip("statsmodels")
    # Every participant rates each mode the same amount above their own level: no residual.
    values = {f"p{k}": {"a": 1.0 + k * 0.1, "b": 3.0 + k * 0.1, "c": 2.0 + k * 0.1} for k in range(5)}
    result = stats.rm_anova(values, ["a", "b", "c"])
    assert result["F"] == math.inf and result["p"] == 0.0
    flat = {f"p{k}": {"a": 1.0 + k * 0.1, "b": 1.0 + k * 0.1} for k in range(5)}
    assert stats.rm_anova(flat, ["a", "b"])["F"] is None
    noisy = {f"p{k}": {"a": 1.0 + k * 0.1, "b": 3.0 + (k % 2) * 0.5} for k in range(5)}
    assert math.isfinite(stats.rm_anova(noisy, ["a", "b"])["F"])


def test_a_study_of_1700_participants_gets_readable_figures(tmp_path):
    """One column per participant would make the hit-rate figure tens of thousands of pixels wide
    (matplotlib refuses above 2^16): beyond a screenful of participants it summarises instead."""
    import matplotlib.image

    export = tmp_path / "export"
    export.mkdir()
    with_modes(export)
    rows = [(f"P{k}", mode, 20 + (k * 7 + j * 5) % 40, 80)
            for k in range(1, 1701) for j, mode in enumerate(("warp15to120", "conv15", "conv120"))]
    write(export / "hitrates.csv", hitrate_lines(rows))
    code, report = run_in_process(export, tmp_path / "out")
    assert code == 0
    for name in report["figures"]:
        height, width = matplotlib.image.imread(tmp_path / "out" / name).shape[:2]
        assert width <= 3000 and height <= 3000, (name, width, height)
    assert len(report["games"]["shooter"]["participants"]) == 1700


def papers_rows(md, title):
    """The cells of each row of the table under the report's heading that starts with `title`."""
    section = md.split("### Beside the papers' people: " + title)[1].split("\n#")[0]
    lines = [line for line in section.splitlines() if line.startswith("| ")][1:]  # the header left out
    return [[c.strip() for c in line.strip().strip("|").split("|")] for line in lines]


def test_the_thesis_data_stands_beside_itself(thesis):
    """The thesis's own Table 1, analysed, must equal the figures the report sets beside it."""
    _, out = thesis
    md = (out / "report.md").read_text(encoding="utf-8")
    rows = {cells[0]: cells for cells in papers_rows(md, "the thesis's Table 1")}
    assert "sessions.csv does not say who played" in md
    for mode, (mean, sd) in papers.thesis_hit_rates().items():
        cells = rows[mode]
        assert cells[1] == cells[4] == f"{mean:.3f}"
        assert cells[2] == cells[5] == f"{sd:.3f}"
        assert cells[3] == cells[6]
    thesis_rates = papers.thesis_hit_rates()
    assert rows["conv15"][6] == f"{thesis_rates['conv15'][0] / thesis_rates['conv120'][0]:.2f}" == "0.70"


def test_a_simulated_study_says_so_beside_yangs_people(tmp_path):
    write_click_export(tmp_path)
    sessions = (tmp_path / "sessions.csv").read_text(encoding="utf-8").replace(",human,", ",sim:3,")
    (tmp_path / "sessions.csv").write_text(sessions, encoding="utf-8")
    out = tmp_path / "out"
    code, report = run_in_process(tmp_path, out)
    assert code == 0
    md = (out / "report.md").read_text(encoding="utf-8")
    assert "participants are **simulated**" in md
    rows = {(cells[0], cells[1]): cells for cells in papers_rows(md, "Yang et al.'s Table 2")}
    green = rows[("Green hits", "conv15")]
    ours = report["click"]["measures"]["green_hits"]["modes"]
    assert green[2] == f"{ours['conv15']['mean']:.2f}"
    assert green[4] == f"{ours['conv15']['mean'] / ours['conv60']['mean']:.2f}"
    assert green[5:] == ["31.89", "6.82", f"{31.89 / 43.79:.2f}"]
    # A rating statement is matched to Yang's by its words; counts only have a relative column.
    enjoyed = rows[("I enjoyed playing this game", "bireproj15to60")]
    assert enjoyed[5:] == ["4.38", "1.14", "–"] and enjoyed[4] == "–"
