"""analysis/analyze on the click game's matches (matches.csv, ratings.csv): means and SDs, paired
tests and the repeated-measures ANOVA checked against formulas written out here, the reference
and its fallback, where the matches' sections go, the rating scale and its refusals, and the
matches beside Yang et al.'s people.
"""
import json
import math
import shutil
import statistics
import sys

import pytest
import scipy.stats

from exports import (CLICK, GAMES_HEADER, CLICK_CONDITIONS, STATEMENTS, papers_rows, run_in_process, write,
                     write_click_export)

import analyze  # noqa: E402  (importing exports has put analysis/ on the path)
from warplab_analysis import stats  # noqa: E402


def participant_means(index):
    """{participant: {condition: mean over that participant's scored matches}} of measure `index`."""
    means = {}
    for (p, condition), games in CLICK.items():
        values = [g[index] for g in games if g[index] is not None]
        means.setdefault(p, {})[condition] = sum(values) / len(values)
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
    c = report["matches"]
    assert c["reference_condition"] == "bireproj15to60" and c["conditions"] == CLICK_CONDITIONS
    assert c["scored_matches"] == 28 and c["participants"] == ["P1", "P2", "P3", "P4", "P5"]
    assert list(c["measures"]) == ["green_hits", "red_hits", "misses", "rating_1", "rating_2"]
    assert [m["label"] for m in c["measures"].values()] == ["Green hits", "Red hits", "Misses"] + STATEMENTS
    for index, key in enumerate(c["measures"]):
        means = participant_means(index)
        for condition in CLICK_CONDITIONS:
            values = [row[condition] for row in means.values() if condition in row]
            entry = c["measures"][key]["conditions"][condition]
            assert entry["n"] == len(values)
            assert entry["mean"] == pytest.approx(statistics.mean(values), rel=1e-12)
            assert entry["sd"] == pytest.approx(statistics.stdev(values), rel=1e-12)
    # A hand check on one cell: conv60 green hits per participant 42.5, 37, 46, 38, 41.
    assert c["measures"]["green_hits"]["conditions"]["conv60"]["mean"] == pytest.approx(40.9)
    # P2's missing rating: their bireproj mean of rating_2 is the one answered match (5).
    assert c["measures"]["rating_2"]["participant_means"]["P2"]["bireproj15to60"] == 5.0


def test_click_paired_t_against_hand_formula(click):
    report, _ = click
    c = report["matches"]
    for index, key in enumerate(c["measures"]):
        means = participant_means(index)
        for condition in ("conv60", "conv15"):
            d = [row[condition] - row["bireproj15to60"] for row in means.values() if condition in row]
            n = len(d)
            mean, sd = sum(d) / n, math.sqrt(sum((x - sum(d) / n) ** 2 for x in d) / (n - 1))
            t = mean / (sd / math.sqrt(n))
            p = 2 * scipy.stats.t.sf(abs(t), n - 1)
            v = c["measures"][key]["conditions"][condition]["vs_reference"]
            assert v["n"] == n and v["df"] == n - 1
            assert v["t"] == pytest.approx(t, rel=1e-9) and v["p_t"] == pytest.approx(p, rel=1e-9)
            positive, negative = sum(x > 0 for x in d), sum(x < 0 for x in d)
            assert (v["positive"], v["negative"], v["ties"]) == (positive, negative, n - positive - negative)
            assert 0.0 < v["p_wilcoxon"] <= 1.0 and 0.0 < v["p_sign"] <= 1.0
    assert c["measures"]["green_hits"]["conditions"]["bireproj15to60"]["vs_reference"] is None
    # Green hits, conv60 against bireproj: every participant hit more, so the sign test is 2 / 2^5.
    v = c["measures"]["green_hits"]["conditions"]["conv60"]["vs_reference"]
    assert (v["positive"], v["n"]) == (5, 5) and v["p_sign"] == pytest.approx(2 / 32, rel=1e-12)
    # Wilcoxon, exact: all five signed ranks positive, two-sided p = 2 / 2^5.
    assert v["p_wilcoxon"] == pytest.approx(2 / 32, rel=1e-12)


def test_click_anova_against_hand_formula(click):
    pytest.importorskip("statsmodels")
    report, _ = click
    c = report["matches"]
    for index, key in enumerate(c["measures"]):
        means = participant_means(index)
        complete = [row for row in means.values() if all(m in row for m in CLICK_CONDITIONS)]  # P5 dropped
        n, k = len(complete), len(CLICK_CONDITIONS)
        grand = sum(row[m] for row in complete for m in CLICK_CONDITIONS) / (n * k)
        ss_conditions = n * sum((sum(row[m] for row in complete) / n - grand) ** 2 for m in CLICK_CONDITIONS)
        ss_subjects = k * sum((sum(row[m] for m in CLICK_CONDITIONS) / k - grand) ** 2 for row in complete)
        ss_total = sum((row[m] - grand) ** 2 for row in complete for m in CLICK_CONDITIONS)
        ss_error = ss_total - ss_conditions - ss_subjects
        f = (ss_conditions / (k - 1)) / (ss_error / ((k - 1) * (n - 1)))
        anova = c["measures"][key]["anova"]
        assert anova["F"] == pytest.approx(f, rel=1e-9)
        assert (anova["df_num"], anova["df_den"]) == (k - 1, (k - 1) * (n - 1))
        assert anova["p"] == pytest.approx(scipy.stats.f.sf(f, k - 1, (k - 1) * (n - 1)), rel=1e-9)
        assert (anova["participants"], anova["dropped"]) == (4, 1)


def test_click_report_and_figures(click):
    report, out = click
    md = (out / "report.md").read_text()
    assert "## Click game" in md and "I enjoyed playing this game" in md
    assert "F(1, n − 1) = t²" in md and "](matches.png)" in md
    assert "Sessions (sessions.csv): 5 of 6 included" in md
    assert "Table 1 (click)" in md  # hit rates: green hits / clicks, with their sign tests
    assert "#### Planning (click): participants for 80 % power" in md  # and what a study would need
    assert all(t["planning"]["pilot_participants"] == t["participants"] for t in report["sign_tests"])
    assert (out / "matches.png").stat().st_size > 10_000
    assert "Pulkkinen" not in md  # no shooter data, no shooter section
    assert [t["game"] for t in report["sign_tests"]] == ["click"] * 3
    # games.csv's words for what the click game's hit rate counts.
    assert "rate = green hits out of clicks" in md and "### Hit rates: green hits / clicks" in md
    assert report["matches"]["game"] == "click"
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
    assert report_new["matches"]["conditions"] == CLICK_CONDITIONS


def test_matches_sections_follow_the_data_not_the_game_name(tmp_path):
    # The click game's data under another name: the matches' sections go with the game whose
    # sessions (sessions.csv) played them, and the wording is games.csv's.
    write_click_export(tmp_path, game="spheres")
    code, report = run_in_process(tmp_path, tmp_path / "out")
    assert code == 0
    md = (tmp_path / "out" / "report.md").read_text()
    assert "## Spheres game: the paper's own analysis, replicated (Yang et al. 2011, seed 000 §8)" in md
    assert "Click game" not in md
    assert "F(1, n − 1) = t²" in md and "Pulkkinen" not in md
    assert "rate = green hits out of clicks" in md and "### Hit rates: green hits / clicks" in md
    assert report["matches"]["game"] == "spheres" and report["matches"]["conditions"] == CLICK_CONDITIONS
    # Without sessions.csv nothing says whose matches they are: a section of their own.
    (tmp_path / "sessions.csv").unlink()
    code, report = run_in_process(tmp_path, tmp_path / "out2")
    assert code == 0
    md = (tmp_path / "out2" / "report.md").read_text()
    assert report["matches"]["game"] is None
    assert "## Matches: the paper's own analysis, replicated (Yang et al. 2011, seed 000 §8)" in md
    assert "## Spheres: hit rates" in md
    assert md.index("## Spheres: hit rates") < md.index("## Matches")
    # games.csv's `tables` (exports since games own their tables) says it without sessions.csv.
    # A game without tables of its own has an empty cell there.
    write(tmp_path / "games.csv", [GAMES_HEADER + ",tables", "shooter,hits,shots,",
                                   "spheres,green hits,clicks,matches.csv;ratings.csv"])
    code, report = run_in_process(tmp_path, tmp_path / "out3")
    assert code == 0 and report["matches"]["game"] == "spheres"



def test_click_reference_fallback_and_no_statsmodels(tmp_path, monkeypatch):
    write_click_export(tmp_path)
    monkeypatch.setitem(sys.modules, "statsmodels", None)  # `import statsmodels` now raises ImportError
    monkeypatch.setitem(sys.modules, "statsmodels.stats.anova", None)
    code, report = run_in_process(tmp_path, tmp_path / "out", "--reference-condition", "warp15to120")
    assert code == 0
    c = report["matches"]
    assert c["reference_condition"] == "bireproj15to60" and c["reference_requested"] == "warp15to120"
    assert any("warp15to120 is not in the scored matches" in note for note in c["notes"])
    assert c["anova_available"] is False and all(m["anova"] is None for m in c["measures"].values())
    assert c["measures"]["green_hits"]["conditions"]["conv60"]["vs_reference"]["p_t"] > 0
    md = (tmp_path / "out" / "report.md").read_text()
    assert "statsmodels is not installed" in md and "Reference condition: bireproj15to60." in md


def test_reference_mode_is_the_older_name_of_reference_condition(tmp_path, capsys):
    """--reference-mode, the option's name in older scripts, gives the report --reference-condition
    gives; --help shows only the new name."""
    export = tmp_path / "export"
    export.mkdir()
    write_click_export(export)
    written = {}
    for flag in ("--reference-condition", "--reference-mode"):
        out = tmp_path / flag.lstrip("-")
        assert analyze.main([str(export), "--out", str(out), flag, "conv60", "--no-power"]) == 0
        written[flag] = {name: (out / name).read_bytes() for name in ("report.json", "report.md")}
    assert written["--reference-mode"] == written["--reference-condition"]
    report = json.loads(written["--reference-condition"]["report.json"])
    # Asked for, and not the default: the flag took effect under either name.
    assert report["matches"]["reference_condition"] == "conv60" != analyze.DEFAULT_REFERENCE
    assert report["matches"]["reference_requested"] == "conv60"
    capsys.readouterr()
    with pytest.raises(SystemExit):
        analyze.main(["--help"])
    shown = capsys.readouterr().out
    assert "--reference-condition NAME" in shown and "--reference-mode" not in shown


def test_paired_tests_with_all_differences_zero():
    v = stats.paired_tests([3, 4, 5], [3, 4, 5])
    assert (v["p_t"], v["t"], v["p_wilcoxon"], v["p_sign"], v["ties"]) == (1.0, 0.0, 1.0, 1.0, 3)


def test_all_phases_export_counts_only_scored_rows(click):
    report, _ = click
    # The practice matches have 99 green hits; a mean above 50 would mean one was counted.
    assert all(e["mean"] < 50 for e in report["matches"]["measures"]["green_hits"]["conditions"].values())


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
    means = report["matches"]["measures"]["rating_1"]["participant_means"]
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



def test_anova_without_residual_variation_is_infinite_not_rounding_noise():
    pytest.importorskip("statsmodels")
    # Every participant rates each condition the same amount above their own level: no residual.
    values = {f"p{k}": {"a": 1.0 + k * 0.1, "b": 3.0 + k * 0.1, "c": 2.0 + k * 0.1} for k in range(5)}
    result = stats.rm_anova(values, ["a", "b", "c"])
    assert result["F"] == math.inf and result["p"] == 0.0
    flat = {f"p{k}": {"a": 1.0 + k * 0.1, "b": 1.0 + k * 0.1} for k in range(5)}
    assert stats.rm_anova(flat, ["a", "b"])["F"] is None
    noisy = {f"p{k}": {"a": 1.0 + k * 0.1, "b": 3.0 + (k % 2) * 0.5} for k in range(5)}
    assert math.isfinite(stats.rm_anova(noisy, ["a", "b"])["F"])



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
    ours = report["matches"]["measures"]["green_hits"]["conditions"]
    assert green[2] == f"{ours['conv15']['mean']:.2f}"
    assert green[4] == f"{ours['conv15']['mean'] / ours['conv60']['mean']:.2f}"
    assert green[5:] == ["31.89", "6.82", f"{31.89 / 43.79:.2f}"]
    # A rating statement is matched to Yang's by its words; counts only have a relative column.
    enjoyed = rows[("I enjoyed playing this game", "bireproj15to60")]
    assert enjoyed[5:] == ["4.38", "1.14", "–"] and enjoyed[4] == "–"
