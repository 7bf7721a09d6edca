"""analysis/analyze on small exports: the thesis's published numbers (seed 004 Tables 1–3),
ties and empty sign tests, type-7 quartiles, exports from before conditions.csv, one-sentence
refusals of bad input, the entry point, and the thesis beside itself. The matches' tables and
tests are test_matches.py's.

Most cases call analyze.main() in-process (importing numpy, scipy and matplotlib once keeps the
suite fast); the entry-point tests run `analysis/analyze` as a user would.
"""
import json
import os
import re
import shutil
import subprocess

import pytest

from exports import (ANALYSIS, DATA, GAMES_HEADER, HITRATES_HEADER, MATCH_HEADER, assert_same, hitrate_lines,
                     modes_csv_exports, papers_rows, run_in_process, sign_test, with_modes, write,
                     write_click_export)

import analyze  # noqa: E402  (importing exports has put analysis/ on the path)
from warplab_analysis import papers, players, stats  # noqa: E402

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
    # Pairs follow the condition order: warp first, then conv120 before conv15; every pair once.
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
    # report.json's Table 2: sorted by the difference to conv15 (the lowest-rate conventional condition).
    (table2,) = report["games"]["shooter"]["upconversion_differences"]
    assert table2["condition"] == "warp15to120" and table2["sorted_by"] == "conv15"
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
    assert report["matches"] is None and list(report["games"]) == ["shooter"]
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


def test_one_condition_games_and_missing_conditions(tmp_path):
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
    assert report["games"]["other"]["conditions"] == ["conv60"]
    md = (tmp_path / "out" / "report.md").read_text()
    assert "Only one condition (conv60): no pairs to test." in md



def test_a_condition_played_without_a_shot_has_no_rate_and_enters_no_test(tmp_path):
    # hitrates.csv has a row for every participant x condition run; one without a click (shots 0,
    # an empty hit_rate) is as if the participant lacked the condition: no 0/0, no rate of 0 in a
    # mean.
    rows = [("a", "warp15to120", 5, 10), ("a", "conv15", 3, 10), ("b", "warp15to120", 4, 10),
            ("b", "conv15", 5, 10), ("c", "warp15to120", 6, 10)]
    write(with_modes(tmp_path) / "hitrates.csv", hitrate_lines(rows) + ["c,shooter,conv15,0,0,0,"])
    code, report = run_in_process(tmp_path, tmp_path / "out")
    assert code == 0
    test = sign_test(report, "warp15to120", "conv15")
    assert test["participants"] == 2 and set(test["differences"]) == {"a", "b"}
    assert "conv15" not in report["games"]["shooter"]["hit_rates"]["c"]


def test_conditions_follow_modes_csv(tmp_path):
    # Conditions the analysis has never heard of, described by modes.csv alone: a 20 Hz conventional
    # one and a made-up upconverting one. Order, Table 2 and descriptions all follow the file.
    with_modes(tmp_path, ['conv20,"conventional rendering at 20 Hz, held",20,0,none,,,false',
                          'blend20to60,"blended from 20 Hz, to 60 Hz",20,0,bidirectional,60,blend,true'])
    rows = [(p, m, h, 20) for p, base in (("a", 5), ("b", 7), ("c", 9))
            for m, h in (("conv15", base), ("conv20", base + 1), ("blend20to60", base + 3), ("lag50", base - 2))]
    write(tmp_path / "hitrates.csv", hitrate_lines(rows))
    code, report = run_in_process(tmp_path, tmp_path / "out")
    assert code == 0
    assert report["games"]["shooter"]["conditions"] == ["blend20to60", "conv20", "conv15", "lag50"]
    (table2,) = report["games"]["shooter"]["upconversion_differences"]
    assert table2["condition"] == "blend20to60" and table2["sorted_by"] == "conv15"
    assert sign_test(report, "blend20to60", "conv15")["positive"] == 3
    md = (tmp_path / "out" / "report.md").read_text()
    assert "blend20to60 (blended from 20 Hz, to 60 Hz); conv20 (conventional rendering at 20 Hz, held)" in md
    assert (tmp_path / "out" / "shooter_differences.png").is_file()


def test_without_a_condition_table_conditions_are_in_id_order_with_a_note(tmp_path):
    rows = [(p, m, h, 20) for p, h in (("a", 5), ("b", 7)) for m in ("warp15to120", "conv15")]
    write(tmp_path / "hitrates.csv", hitrate_lines(rows))
    code, report = run_in_process(tmp_path, tmp_path / "out")
    assert code == 0
    assert report["games"]["shooter"]["conditions"] == ["conv15", "warp15to120"]
    assert report["games"]["shooter"]["upconversion_differences"] == []
    md = (tmp_path / "out" / "report.md").read_text()
    assert "No modes.csv" in md and "Conditions: conv15; warp15to120." in md


# What the analysis reported for exports written before conditions.csv (modes.csv, or neither),
# as analysis/analyze wrote it from these exports before it read conditions.csv, in the report's
# names since (condition where it said mode; `matches` where it said `click`; its one entry per
# condition, then `modes`, as `conditions` with each name's description, render_hz, added_lag_ms
# and upconverts). Such an export must keep giving the same numbers, orders and notes.
BEFORE = DATA / "modes_csv_reports"
# report.json's keys that the analysis has added since the pinned reports were written: which file
# the condition table comes from; who played (unknown in these exports: a note), the questions; the
# discrimination thresholds (null: these exports have none); the mixed models (left out here, as
# run_in_process leaves them out).
ADDED_KEYS = {"conditions_file", "players", "questions", "group_notes", "discrimination", "mixed_models", "power"}


def without_conditions_section(md):
    """report.md less what was added since: the mixed models' section, the section that describes
    each condition's parts, the sections setting the papers' people beside the study, and the
    words labelling the papers' sections as their own analyses."""
    md = re.sub(r"## Mixed models, trial by trial\n.*?(?=\n## )", "", md, flags=re.S)
    md = re.sub(r"[,:] the paper's own analysis, replicated \(", " (", md)
    md = re.sub(r"### Beside the papers' people.*?(?=\n#{1,3} |\Z)", "", md, flags=re.S)
    return re.sub(r"\n{3,}", "\n\n", re.sub(r"## Conditions\n.*?(?=\n## )", "", md, flags=re.S))


@pytest.mark.parametrize("name", ["both", "bare"])
def test_modes_csv_export_reports_as_before(tmp_path, name):
    export = modes_csv_exports(tmp_path)[name]
    code, report = run_in_process(export, tmp_path / "out")
    assert code == 0
    expected = json.loads((BEFORE / f"{name}.json").read_text(encoding="utf-8"))
    assert report.pop("export_dir") == str(export)
    assert set(report) - set(expected) == ADDED_KEYS and set(expected) <= set(report)
    assert report["conditions_file"] == ("modes.csv" if name == "both" else None)
    assert [r["condition"] for r in report["conditions"]] == [c["condition"] for c in expected["conditions"]]
    # Each row has gained the parts a condition table gives since (fill, late warp, refresh, game,
    # latencies): compared, the rows keep what the pinned ones say.
    pinned = list(expected["conditions"][0]) if expected["conditions"] else []
    report["conditions"] = [{k: row[k] for k in pinned} for row in report["conditions"]]
    if report["sessions"]:
        assert report["sessions"].pop("players") == {"human": 5}  # added since: who played, by kind
    report["notes"].remove(players.UNKNOWN_NOTE)
    assert report["players"]["kinds"] is None and report["questions"] == [] and report["group_notes"] == []
    assert report["discrimination"] is None
    assert_same({k: report[k] for k in expected}, expected, "report")
    md = (tmp_path / "out" / "report.md").read_text(encoding="utf-8").replace(str(export), "EXPORT")
    md = md.replace(players.UNKNOWN_NOTE + "\n\n", "")
    assert without_conditions_section(md) == (BEFORE / f"{name}.md").read_text(encoding="utf-8")


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
    # Yang et al.'s scale, 1 to 7 (the protocol's default): a 9 would move the condition's mean.
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
                 "click_hit_rates.png", "matches.png"):
        assert (out / name).is_file() and str(out / name) in printed, name
    md = (out / "report.md").read_text()
    assert md.index("## Mixed models") < md.index("## Shooter") < md.index("## Click game")
    assert (out / "mixed_models.R").is_file() and str(out / "mixed_models_contrasts.png") in printed
    report = json.loads((out / "report.json").read_text())
    assert (set(report["games"]) == {"shooter", "click"}
            and report["matches"]["reference_condition"] == "bireproj15to60")


def test_entry_point_bad_input_has_no_traceback(tmp_path):
    write(tmp_path / "hitrates.csv", hitrate_lines([("a", "conv15", 3, 10), ("b", "conv15", 4, 10)])[:2]
          + ["b,shooter,conv15,ten,4,0,0.4"])
    result = run_entry_point(tmp_path, "--out", tmp_path / "out")
    assert result.returncode == 1
    assert result.stderr.strip().splitlines() == [
        f"analyze: {tmp_path / 'hitrates.csv'}: line 3, column 'shots' is not a number: 'ten'."]
    assert "Traceback" not in result.stderr and result.stdout == ""



def test_a_study_of_1700_participants_gets_readable_figures(tmp_path):
    """One column per participant would make the hit-rate figure tens of thousands of pixels wide
    (matplotlib refuses above 2^16): beyond a screenful of participants it summarises instead."""
    import matplotlib.image

    export = tmp_path / "export"
    export.mkdir()
    with_modes(export)
    rows = [(f"P{k}", condition, 20 + (k * 7 + j * 5) % 40, 80)
            for k in range(1, 1701) for j, condition in enumerate(("warp15to120", "conv15", "conv120"))]
    write(export / "hitrates.csv", hitrate_lines(rows))
    code, report = run_in_process(export, tmp_path / "out")
    assert code == 0
    for name in report["figures"]:
        height, width = matplotlib.image.imread(tmp_path / "out" / name).shape[:2]
        assert width <= 3000 and height <= 3000, (name, width, height)
    assert len(report["games"]["shooter"]["participants"]) == 1700



def test_the_thesis_data_stands_beside_itself(thesis):
    """The thesis's own Table 1, analysed, must equal the figures the report sets beside it."""
    _, out = thesis
    md = (out / "report.md").read_text(encoding="utf-8")
    rows = {cells[0]: cells for cells in papers_rows(md, "the thesis's Table 1")}
    assert "sessions.csv does not say who played" in md
    for condition, (mean, sd) in papers.thesis_hit_rates().items():
        cells = rows[condition]
        assert cells[1] == cells[4] == f"{mean:.3f}"
        assert cells[2] == cells[5] == f"{sd:.3f}"
        assert cells[3] == cells[6]
    thesis_rates = papers.thesis_hit_rates()
    assert rows["conv15"][6] == f"{thesis_rates['conv15'][0] / thesis_rates['conv120'][0]:.2f}" == "0.70"

