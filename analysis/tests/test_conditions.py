"""analysis/analyze on exports whose conditions come from conditions.csv: the nine presets in the
documented order and with modes.csv's results, conditions a lab composed that the analysis has
never seen, conditions.csv over a modes.csv beside it, the reference rule without the presets,
and one-sentence refusals of a malformed conditions.csv.
"""
import csv
import io
import json
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

from exports import (DATA, GAMES_HEADER, assert_same, hitrate_lines, modes_csv_exports,  # noqa: E402
                          run_in_process, sign_test, with_modes, write, write_click_export)

import analyze  # noqa: E402  (importing exports has put analysis/ on the path)

CONDITIONS_HEADER = ("condition,render_hz,lag_frames,fill,late_warp,view_latency_min_ms,view_latency_max_ms,"
                     "scene_latency_min_ms,scene_latency_max_ms,fill_hz,refresh_hz,game,description")
PRESET_ORDER = ["warp15to120", "bireproj15to60", "conv120", "conv60", "conv30", "conv15", "lag50", "lag100", "lag200"]


def condition(name, render=60, lag=0, fill="hold", late="none", view=(8, 16), scene=(8, 16), fill_hz="",
              refresh=60, game="shooter", description="d"):
    out = io.StringIO()
    csv.writer(out, lineterminator="").writerow([name, render, lag, fill, late, *view, *scene, fill_hz, refresh, game,
                                                 description])
    return out.getvalue()


def per_name(report):
    """What report.json's `conditions` says of each name, in the table's order: its first row, with
    the least added lag over its rows (what the condition order uses)."""
    names = {}
    for row in report["conditions"]:
        first = names.setdefault(row["condition"], dict(row))
        first["added_lag_ms"] = min(first["added_lag_ms"], row["added_lag_ms"])
    return list(names.values())


def with_conditions(export, lines=None):
    """conditions.csv: `lines` under the header, or the presets (data/conditions.csv: the shooter's
    at 120 Hz, the click game's at 60 Hz, latencies worked out by hand from each condition's
    parts and refresh, to have numbers of the right size, not a model of the renderer's)."""
    if lines is None:
        write(export / "conditions.csv", (DATA / "conditions.csv").read_text(encoding="utf-8").splitlines())
    else:
        write(export / "conditions.csv", [CONDITIONS_HEADER] + list(lines))
    return export


# --- the presets --------------------------------------------------------------------------------

@pytest.mark.parametrize("table", ["modes.csv", "conditions.csv"])
def test_presets_keep_the_documented_order(tmp_path, table):
    (with_modes if table == "modes.csv" else with_conditions)(tmp_path)
    rows = [(p, m, h + k, 20) for p, h in (("a", 3), ("b", 6)) for k, m in enumerate(sorted(PRESET_ORDER))]
    write(tmp_path / "hitrates.csv", hitrate_lines(rows))
    code, report = run_in_process(tmp_path, tmp_path / "out")
    assert code == 0
    assert report["games"]["shooter"]["conditions"] == report["condition_order"] == PRESET_ORDER
    assert [t["condition"] for t in report["games"]["shooter"]["upconversion_differences"]] == PRESET_ORDER[:2]


def test_presets_in_conditions_csv_give_modes_csv_results(tmp_path):
    """The same data with the presets' conditions.csv instead of modes.csv: the same tests,
    tables, order and reference; only what the table says of each condition differs."""
    exports = {}
    for table in ("modes", "conditions"):
        (tmp_path / table).mkdir()
        exports[table] = modes_csv_exports(tmp_path / table)["both"]
    (exports["conditions"] / "modes.csv").unlink()
    with_conditions(exports["conditions"])
    reports = {}
    for table, export in exports.items():
        code, reports[table] = run_in_process(export, tmp_path / f"out_{table}")
        assert code == 0
    old, new = reports["modes"], reports["conditions"]
    assert new["conditions_file"] == "conditions.csv" and old["conditions_file"] == "modes.csv"
    for key in ("condition_order", "games", "sign_tests", "matches", "figures"):
        assert_same(new[key], old[key], key)
    new_names, old_names = per_name(new), per_name(old)
    assert [c["condition"] for c in new_names] == ["conv15", "conv30", "conv60", "conv120", "lag50", "lag100",
                                                   "lag200", "warp15to120", "bireproj15to60"]
    assert_same([(c["condition"], c["description"], c["upconverts"], c["render_hz"]) for c in new_names],
                [(c["condition"], c["description"], c["upconverts"], c["render_hz"]) for c in old_names],
                "conditions")
    assert [c["added_lag_ms"] for c in new_names] == pytest.approx([c["added_lag_ms"] for c in old_names])
    # conv60 ran in both games, at two refreshes: two rows, the lag in frames per refresh.
    lag50 = [(r["game"], r["refresh_hz"], r["lag_frames"]) for r in new["conditions"] if r["condition"] == "lag50"]
    assert lag50 == [("shooter", 120, 6), ("click", 60, 3)]
    md = (tmp_path / "out_conditions" / "report.md").read_text()
    assert "| conv60 | 120 | shooter | 60 | 0.00 | 0 | hold | none | no | 8.33–25.00 | 8.33–25.00 |" in md
    assert "| conv60 | 60 | click | 60 | 0.00 | 0 | hold | none | no | 16.67–33.33 | 16.67–33.33 |" in md


# --- a lab's own conditions ----------------------------------------------------------------------

# In a scrambled file order; two have a row per display refresh and game.
LAB = [
    condition("plain60-lag2", lag=2, view=(50, 66.6667), scene=(50, 66.6667), description="60 Hz, 2 frames late"),
    condition("plain60-lag2", lag=4, view=(41.6667, 58.3333), scene=(41.6667, 58.3333), refresh=120, game="click",
              description="60 Hz, 4 frames late at 120 Hz"),
    condition("base30", render=30, view=(16.6667, 50), scene=(16.6667, 50), description="30 Hz, held"),
    condition("lag60x5-rotation", lag=5, late="rotation", view=(16.6667, 33.3333), scene=(100, 116.667),
              description="60 Hz, 5 frames late, each re-projected by rotation to the display instant's camera"),
    condition("plain60", view=(16.6667, 33.3333), scene=(16.6667, 33.3333), description="60 Hz, held"),
    condition("plain60", view=(8.33333, 25), scene=(8.33333, 25), refresh=120, game="click", description="60 Hz, held"),
    condition("my-144hz-warp", render=36, fill="warp-full", fill_hz=144, view=(6.94444, 13.8889),
              scene=(6.94444, 34.7222), refresh=144, description="36 Hz renders, warped (full) to 144 Hz, \"fast\""),
    condition("blend-30to120", render=30, fill="blend", fill_hz=120, view=(8.33333, 41.6667), scene=(8.33333, 41.6667),
              refresh=120, game="click", description="30 Hz, blended to 120 Hz"),
]
LAB_SHOOTER_ORDER = ["lag60x5-rotation", "my-144hz-warp", "plain60", "base30", "plain60-lag2", "a-unlisted",
                     "b-unlisted"]
LAB_CLICK = {"bireproj15to60": "blend-30to120", "conv60": "plain60", "conv15": "plain60-lag2"}


def lab_export(export, rename=LAB_CLICK):
    """Both games, every condition a lab's (two the table does not list), no preset anywhere."""
    write_click_export(export, rename=rename, table=lambda e: with_conditions(e, LAB))
    rows = [(p, m, h + k, 20) for p, h in (("s1", 2), ("s2", 5), ("s3", 4), ("s4", 6))
            for k, m in enumerate(["b-unlisted", "plain60-lag2", "base30", "a-unlisted", "plain60", "my-144hz-warp",
                                   "lag60x5-rotation"])]
    with open(export / "hitrates.csv", "a") as f:
        f.write("\n".join(hitrate_lines(rows)[1:]) + "\n")
    write(export / "games.csv", [GAMES_HEADER, "shooter,hits,shots", "click,green hits,clicks"])
    return export


def test_a_labs_conditions(tmp_path, monkeypatch):
    from warplab_analysis import figures
    legends = {}
    drawn = figures.hit_rates_figure

    def recording(path, game, *args):
        legends[game] = args[-1]
        return drawn(path, game, *args)

    monkeypatch.setattr(figures, "hit_rates_figure", recording)
    lab_export(tmp_path)
    code, report = run_in_process(tmp_path, tmp_path / "out")
    assert code == 0
    shooter = report["games"]["shooter"]
    # Upconverting first, in file order (late warp alone makes lag60x5-rotation one); then the least
    # added lag, at equal lag the highest render rate; unlisted ones by name.
    assert shooter["conditions"] == LAB_SHOOTER_ORDER
    assert report["condition_order"] == ["lag60x5-rotation", "my-144hz-warp", "blend-30to120", "plain60", "base30",
                                    "plain60-lag2", "a-unlisted", "b-unlisted"]
    table2 = shooter["upconversion_differences"]
    assert [t["condition"] for t in table2] == ["lag60x5-rotation", "my-144hz-warp"]
    assert all(t["sorted_by"] == "base30" for t in table2)  # the lowest-rate condition without lag or upconversion
    assert sign_test(report, "lag60x5-rotation", "plain60")["positive"] == 4
    assert sign_test(report, "lag60x5-rotation", "my-144hz-warp")["positive"] == 4
    names = {c["condition"]: c for c in per_name(report)}
    assert names["plain60-lag2"]["added_lag_ms"] == pytest.approx(100 / 3)
    assert names["lag60x5-rotation"]["upconverts"] and not names["plain60-lag2"]["upconverts"]
    # The click game: no bireproj15to60, so the first upconverting condition is the reference.
    matches = report["matches"]
    assert matches["conditions"] == ["blend-30to120", "plain60", "plain60-lag2"]
    assert matches["reference_condition"] == "blend-30to120" and matches["reference_requested"] == "bireproj15to60"
    assert ("The default reference condition bireproj15to60 is not in the scored matches; blend-30to120, the first "
            "condition in the condition order that upconverts, is the reference instead.") in matches["notes"]
    out = tmp_path / "out"
    for name in ("shooter_hit_rates.png", "shooter_differences.png", "click_hit_rates.png", "click_differences.png",
                 "matches.png"):
        assert (out / name).stat().st_size > 10_000, name
    md = (out / "report.md").read_text()
    assert "conditions.csv (8 rows, 6 conditions)" in md
    assert ("Conditions: lag60x5-rotation (60 Hz, 5 frames late, each re-projected by rotation to the display instant's "
            "camera); my-144hz-warp (36 Hz renders, warped (full) to 144 Hz, \"fast\"); blend-30to120") in md
    assert "a-unlisted; b-unlisted." in md
    assert ("conditions.csv does not list a-unlisted, b-unlisted: they follow the others by name, and none counts as "
            "an upconverting condition.") in report["notes"]
    assert ("| lag60x5-rotation | 60 | shooter | 60 | 83.33 | 5 | hold | rotation | yes | 16.67–33.33 "
            "| 100.00–116.67 |") in md
    assert "| my-144hz-warp | 144 | shooter | 36 | 0.00 | 0 | warp-full, 144 Hz | none | yes | 6.94–13.89 |" in md
    assert "| plain60-lag2 | 120 | click | 60 | 33.33 | 4 | hold |" in md
    assert "Reference condition: blend-30to120." in md and "Table 2a (shooter): lag60x5-rotation hit rate minus" in md
    assert not any(p in md for p in PRESET_ORDER if p != "bireproj15to60")
    # The legend says how long a mouse step takes to reach the screen, for the game's own rows.
    assert legends["shooter"]["lag60x5-rotation"] == "lag60x5-rotation (view 16.7–33.3 ms)"
    assert legends["click"]["plain60"] == "plain60 (view 8.3–25.0 ms)"
    assert legends["shooter"]["a-unlisted"] == "a-unlisted"


def test_reference_without_any_upconverting_condition(tmp_path):
    lab_export(tmp_path, rename={"bireproj15to60": "base30", "conv60": "plain60", "conv15": "plain60-lag2"})
    code, report = run_in_process(tmp_path, tmp_path / "out")
    assert code == 0
    matches = report["matches"]
    assert matches["conditions"] == ["plain60", "base30", "plain60-lag2"]
    assert matches["reference_condition"] == "plain60"
    assert ("The default reference condition bireproj15to60 is not in the scored matches and no condition there "
            "upconverts; plain60, the first in the condition order, is the reference instead.") in matches["notes"]
    # Asked for one it lacks: the same rule.
    code, report = run_in_process(tmp_path, tmp_path / "out2", "--reference-condition", "conv60")
    assert code == 0 and report["matches"]["reference_condition"] == "plain60"
    assert report["matches"]["notes"][-1].startswith(
        "The reference condition conv60 is not in the scored matches and")
    # Asked for one it has.
    code, report = run_in_process(tmp_path, tmp_path / "out3", "--reference-condition", "plain60-lag2")
    assert code == 0 and report["matches"]["reference_condition"] == "plain60-lag2"
    assert not any("reference" in n for n in report["matches"]["notes"])


def test_reference_defaults_to_bireproj_even_when_not_first(tmp_path):
    # warp15to120 comes first in the order, yet an absent request falls back to bireproj15to60.
    write_click_export(tmp_path, rename={"conv15": "warp15to120"})
    code, report = run_in_process(tmp_path, tmp_path / "out", "--reference-condition", "conv120")
    assert code == 0
    assert report["matches"]["conditions"][:2] == ["warp15to120", "bireproj15to60"]
    assert report["matches"]["reference_condition"] == "bireproj15to60"
    assert ("The reference condition conv120 is not in the scored matches; bireproj15to60, the default, is the "
            "reference instead.") in report["matches"]["notes"]


# --- conditions.csv over modes.csv -----------------------------------------------------------------

def test_conditions_csv_wins_over_modes_csv(tmp_path):
    # modes.csv as an earlier export left it, with a row the analysis would refuse: it is not read.
    with_modes(tmp_path, ["conv999,broken,999,0,none,,,perhaps"])
    with_conditions(tmp_path, [
        condition("conv15", render=15, late="rotation", description="15 Hz, late-warped by rotation here"),
        condition("warp15to120", render=15, fill="warp-sparse8", fill_hz=120, refresh=120, description="warp"),
        condition("conv120", render=120, refresh=120, description="120 Hz"),
    ])
    (tmp_path / "hitrates.csv").write_text((DATA / "thesis_table1_hitrates.csv").read_text())
    code, report = run_in_process(tmp_path, tmp_path / "out")
    assert code == 0
    assert report["conditions_file"] == "conditions.csv"
    assert report["games"]["shooter"]["conditions"] == ["conv15", "warp15to120", "conv120"]
    assert [(t["a"], t["b"]) for t in report["sign_tests"]] == [
        ("conv15", "warp15to120"), ("conv15", "conv120"), ("warp15to120", "conv120")]
    assert sign_test(report, "conv15", "warp15to120")["negative"] == 19
    assert "modes.csv" not in report["inputs"] and report["inputs"]["conditions.csv"] == {"rows": 3, "conditions": 3}
    md = (tmp_path / "out" / "report.md").read_text()
    assert "Conditions: conv15 (15 Hz, late-warped by rotation here); warp15to120 (warp); conv120 (120 Hz)." in md
    assert "conditions.csv is read and modes.csv beside it is not" in md


# --- a malformed conditions.csv ------------------------------------------------------------------

GOOD = condition("plain60")
BAD_CONDITIONS = {
    "missing column": ([CONDITIONS_HEADER.replace(",late_warp", ""), "plain60,60,0,hold,8,16,8,16,,60,shooter,d"],
                       "'late_warp'", "line 1, the header, is missing"),
    "lag_frames not a whole number": ([CONDITIONS_HEADER, GOOD, condition("lag", lag=2.5)], "'lag_frames'",
                                      "line 3, column 'lag_frames' is not a whole number: '2.5'"),
    "lag_frames not a number": ([CONDITIONS_HEADER, condition("lag", lag="two")], "'lag_frames'", "line 2"),
    "lag_frames negative": ([CONDITIONS_HEADER, condition("lag", lag=-1)], "'lag_frames'", "negative"),
    "unknown late_warp": ([CONDITIONS_HEADER, GOOD, condition("x", late="sideways")], "'late_warp'",
                          "line 3, column 'late_warp' is not none, rotation or depth: 'sideways'"),
    "empty fill": ([CONDITIONS_HEADER, condition("x", fill="")], "'fill'", "line 2"),
    "fill without its rate": ([CONDITIONS_HEADER, condition("x", fill="warp-full")], "'fill_hz'", "line 2"),
    "zero refresh": ([CONDITIONS_HEADER, condition("x", refresh=0)], "'refresh_hz'", "not above 0"),
    "latency not a number": ([CONDITIONS_HEADER, condition("x", scene=(8, "soon"))], "'scene_latency_max_ms'",
                             "line 2"),
    "latency range reversed": ([CONDITIONS_HEADER, condition("x", view=(16, 8))], "'view_latency_max_ms'", "below"),
    "a second row for one refresh": ([CONDITIONS_HEADER, GOOD, GOOD], "'condition'", "line 3"),
    "parts differ between refreshes": ([CONDITIONS_HEADER, GOOD, condition("plain60", render=30, refresh=120)],
                                       "'render_hz'", "line 3"),
    "late warp differs between games": ([CONDITIONS_HEADER, GOOD, condition("plain60", late="depth", game="click")],
                                        "'late_warp'", "on line 2"),
}


@pytest.mark.parametrize("case", sorted(BAD_CONDITIONS))
def test_bad_conditions_csv_is_one_sentence(tmp_path, capsys, case):
    lines, column, detail = BAD_CONDITIONS[case]
    write(tmp_path / "hitrates.csv", hitrate_lines([("a", "plain60", 3, 10), ("b", "plain60", 4, 10)]))
    with_modes(tmp_path)  # a good modes.csv beside it does not stand in for a bad conditions.csv
    write(tmp_path / "conditions.csv", lines)
    code = analyze.main([str(tmp_path), "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert code == 1
    assert len(err.strip().splitlines()) == 1 and err.rstrip().endswith("."), err
    assert str(tmp_path / "conditions.csv") in err and column in err and detail in err, err
    assert not (tmp_path / "out" / "report.json").exists()


def test_report_json_has_the_conditions_rows(tmp_path):
    with_conditions(tmp_path, LAB)
    write(tmp_path / "hitrates.csv", hitrate_lines([(p, m, 5 + k, 20) for p in ("a", "b")
                                                    for k, m in enumerate(("plain60", "base30"))]))
    assert analyze.main([str(tmp_path), "--out", str(tmp_path / "out")]) == 0
    report = json.loads((tmp_path / "out" / "report.json").read_text())
    (row,) = [r for r in report["conditions"] if r["condition"] == "my-144hz-warp"]
    assert row == {"condition": "my-144hz-warp", "description": "36 Hz renders, warped (full) to 144 Hz, \"fast\"",
                   "render_hz": 36.0, "lag_frames": 0, "added_lag_ms": 0.0, "fill": "warp-full", "fill_hz": 144.0,
                   "late_warp": "none", "view_latency_min_ms": 6.94444, "view_latency_max_ms": 13.8889,
                   "scene_latency_min_ms": 6.94444, "scene_latency_max_ms": 34.7222, "refresh_hz": 144.0,
                   "game": "shooter", "upconverts": True}
    assert len(report["conditions"]) == len(LAB)
