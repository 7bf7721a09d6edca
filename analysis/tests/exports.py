"""The small exports the analysis tests write, in an older export's layout (hitrates.csv,
matches.csv and ratings.csv naming each row's condition in a `mode` column; modes.csv as the
condition table), analyze.main() run in-process on them, and the readers of report.json and
report.md the tests share.
"""
import json
import sys
from pathlib import Path

import pytest

ANALYSIS = Path(__file__).resolve().parents[1]
DATA = Path(__file__).resolve().parent / "data"
sys.path.insert(0, str(ANALYSIS))

import analyze  # noqa: E402

HITRATES_HEADER = "participant,game,mode,shots,hits,timeouts,hit_rate"


def write(path, lines):
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def with_modes(export, extra=()):
    """modes.csv as warplab exports it (the nine published presets; test_round_trip checks the copy
    against a real export), plus `extra` rows: what the analysis knows of the conditions."""
    lines = (DATA / "modes.csv").read_text(encoding="utf-8").splitlines() + list(extra)
    write(export / "modes.csv", lines)
    return export


def hitrate_lines(rows, game="shooter"):
    """rows: (participant, condition, hits, shots)."""
    return [HITRATES_HEADER] + [f"{p},{game},{m},{s},{h},0,{h / s:.6f}" for p, m, h, s in rows]


def run_in_process(export_dir, out_dir, *extra, mixed_models=False, power=False):
    """mixed_models: fit them (R, a few seconds a report); power: plan the sample size from them
    by simulation (R, up to a minute). The tests of other sections leave both out;
    test_mixed_models.py and test_power.py test them."""
    flags = ([] if power else ["--no-power"]) if mixed_models else ["--no-mixed-models"]
    code = analyze.main([str(export_dir), "--out", str(out_dir), *map(str, extra), *flags])
    report = out_dir / "report.json"
    return code, (json.loads(report.read_text()) if code == 0 else None)


def sign_test(report, a, b, game="shooter"):
    (test,) = [t for t in report["sign_tests"] if (t["game"], t["a"], t["b"]) == (game, a, b)]
    return test


# The click game: two scored matches per participant and condition, a practice match that must not
# count, two rating statements; P5 lacks conv15 (paired tests use whom they can, the ANOVA drops P5).
CLICK_CONDITIONS = ["bireproj15to60", "conv60", "conv15"]
STATEMENTS = ["I enjoyed playing this game", "This game was difficult to play"]
# (participant, condition): [(green, red, misses, rating_1, rating_2), ...]; None: the rating is missing.
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
    """rename: {condition of CLICK: the name the export gives it}; table: writes the condition table
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
        condition = rename.get(preset, preset)
        practice = [(99, 0, 0, 1, 1)]  # wild values: must be ignored
        for scored, (g, r, m, *rs) in [(False, x) for x in practice] + [(True, x) for x in games]:
            phase, flag = ("scored", "true") if scored else ("practice", "false")
            stand_in = "bidirectional reprojection" if condition == "bireproj15to60" else ""
            matches.append(f"{p},{p}_s.db,{phase},{flag},{k},{condition},{stand_in},{g},{r},{m},{g + r + m},45.0,"
                           + ",".join(fmt_cell(v) for v in rs))
            for i, v in enumerate(rs):
                if v is not None:
                    ratings.append(f'{p},{p}_s.db,{phase},{flag},{k},{condition},{i},"{STATEMENTS[i]}",{v},key'
                                   + scale_cells)
            if scored:
                hits, shots = hitrates.get((p, condition), (0, 0))
                hitrates[(p, condition)] = (hits + g, shots + g + r + m)
            k += 1
    write(export / "matches.csv", matches)
    write(export / "ratings.csv", ratings)
    write(export / "hitrates.csv", hitrate_lines([(p, m, h, s) for (p, m), (h, s) in hitrates.items()], game))
    write(export / "sessions.csv", ["file,participant,game,protocol,seed,started_at,player,completed,flags,status,"
                                    "included,trials,matches,note"]
          + [f"{p}_s.db,{p},{game},click-yang,1,2024-01-01T00:00:00Z,human,true,,ok,true,0,21,"
             for p in ("P1", "P2", "P3", "P4", "P5")]
          + [f"P6_s.db,P6,{game},click-yang,1,2024-01-01T00:00:00Z,human,false,,cut,false,0,3,cut short"])



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



def papers_rows(md, title):
    """The cells of each row of the table under the report's heading that starts with `title`."""
    section = md.split("### Beside the papers' people: " + title)[1].split("\n#")[0]
    lines = [line for line in section.splitlines() if line.startswith("| ")][1:]  # the header left out
    return [[c.strip() for c in line.strip().strip("|").split("|")] for line in lines]

