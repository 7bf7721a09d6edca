"""A real study through the whole pipeline: headless bot sessions of both games (`warplab run`),
`warplab export`, then analysis/analyze. The counts are checked against the session files
themselves, read here with Python's sqlite3 -- a path independent of both warplab's C++ reader
and the export under test.

Needs the warplab binary (warplab_binary.py says where it comes from).
"""
import collections
import csv
import json
import sqlite3
from pathlib import Path

import pytest

from warplab_binary import binary, run

ROOT = Path(__file__).resolve().parents[2]
PARTICIPANTS = ["P1", "P2", "P3"]


def scored_counts_from_sqlite(session):
    """(participant, game, condition) -> [shots, hits] over the scored phase, straight from SQL (the
    session file names a row's condition in its events' `mode` column)."""
    db = sqlite3.connect(f"file:{session}?mode=ro&immutable=1", uri=True)
    meta = dict(db.execute("SELECT key, value FROM meta"))
    protocol = json.loads(meta["protocol_json"])
    game = protocol["game"]
    counts = collections.defaultdict(lambda: [0, 0])
    if game == "shooter":
        scoring = protocol["test"]["scoring"]
        rows = db.execute("SELECT mode, world_outcome, displayed_outcome FROM events "
                          "WHERE type IN ('shot', 'timeout') AND phase = 'test'")
        hit = "hit"
    else:
        scoring = protocol["matches"]["scoring"]
        scored_rounds = [r["name"] for r in protocol["matches"]["rounds"] if r["scored"]]
        rows = db.execute(f"SELECT mode, world_outcome, displayed_outcome FROM events WHERE type = 'click' "
                          f"AND phase IN ({','.join('?' * len(scored_rounds))})", scored_rounds)
        hit = "green"
    for condition, world, displayed in rows:
        c = counts[(meta["participant"], game, condition)]
        c[0] += 1
        c[1] += (world if scoring == "world" else displayed) == hit
    db.close()
    return counts


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    warplab = binary()
    base = tmp_path_factory.mktemp("study")
    results, export, report = base / "results", base / "export", base / "report"
    results.mkdir()
    for seed, participant in enumerate(PARTICIPANTS, start=1):
        # latewarp-kim-quick defines its conditions in the file: names no analysis code has seen.
        for protocol in ("shooter-quick.json", "click-quick.json", "latewarp-kim-quick.json"):
            run(warplab, "run", "--headless", "--protocol", ROOT / "protocol" / protocol, "--participant",
                participant, "--out", results, "--player", f"bot:{seed}", "--seed", seed)
    before = {p: p.read_bytes() for p in results.iterdir()}
    run(warplab, "export", results, "--out", export)
    assert {p: p.read_bytes() for p in results.iterdir()} == before, "export changed the results folder"
    run(ROOT / "analysis" / "analyze", export, "--out", report)
    return results, export, report


def test_hit_rates_are_the_counts_the_session_files_hold(study):
    results, export, _ = study
    expected = collections.defaultdict(lambda: [0, 0])
    for session in results.glob("*.warplab-session"):
        for key, (shots, hits) in scored_counts_from_sqlite(session).items():
            expected[key][0] += shots
            expected[key][1] += hits
    with open(export / "hitrates.csv", newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    got = {(r["participant"], r["game"], r["condition"]): [int(r["shots"]), int(r["hits"])] for r in rows}
    assert got == dict(expected)
    assert {r["game"] for r in rows} == {"shooter", "click"}


def test_report_has_both_games_tables_and_figures(study):
    _, export, report = study
    data = json.loads((report / "report.json").read_text())
    assert set(data["games"]) == {"shooter", "click"}
    pairs = {(t["game"], t["a"], t["b"]) for t in data["sign_tests"]}
    assert ("shooter", "warp15to120", "conv15") in pairs
    assert ("click", "bireproj15to60", "conv15") in pairs
    for t in data["sign_tests"]:
        assert t["n"] + t["ties"] == len(PARTICIPANTS)
        assert t["positive"] + t["negative"] == t["n"]
    with open(export / "matches.csv", newline="", encoding="utf-8") as f:
        scored = [m for m in csv.DictReader(f) if m["scored_phase"] == "true"]
    assert data["matches"]["scored_matches"] == len(scored) > 0
    text = (report / "report.md").read_text()
    assert "Table 1 (shooter)" in text and "Click game" in text
    for figure in data["figures"]:
        assert (report / figure).stat().st_size > 1000
    assert "shooter_hit_rates.png" in data["figures"] and "matches.png" in data["figures"]


def read_csv(path):
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def test_conditions_and_games_come_from_the_export(study):
    _, export, report = study
    data = json.loads((report / "report.json").read_text())
    if (export / "conditions.csv").exists():
        check_conditions_csv(export, report, data)
    else:
        # An export from before conditions.csv. The analysis tests' modes.csv is what export writes
        # for the published presets: its rows are rows of the real file (which may list more).
        exported = (export / "modes.csv").read_text(encoding="utf-8").splitlines()
        fixture = (ROOT / "analysis" / "tests" / "data" / "modes.csv").read_text(encoding="utf-8").splitlines()
        assert exported[:len(fixture)] == fixture
        assert [r["condition"] for r in data["conditions"]] == [line.split(",")[0] for line in exported[1:]]
        assert "warp15to120 (rendered at 15 Hz, the frames between warped" in (report / "report.md").read_text()
    games = {r["game"]: (r["hits_are"], r["shots_are"]) for r in read_csv(export / "games.csv")}
    assert games == {"shooter": ("hits", "shots"), "click": ("green hits", "clicks")}
    assert data["matches"]["game"] == "click"
    text = (report / "report.md").read_text()
    assert "rate = green hits out of clicks" in text and "rate = hits out of shots" in text


def check_conditions_csv(export, report, data):
    """conditions.csv names every condition the sessions used, with the columns docs/export.md
    lists, and gives the presets the parts the analysis tests' copy (data/conditions.csv) gives
    them; its latencies are the export's own, which that copy only imitates."""
    rows = read_csv(export / "conditions.csv")
    with open(export / "conditions.csv", newline="", encoding="utf-8") as f:
        header = next(csv.reader(f))
    assert header == ["condition", "render_hz", "lag_frames", "fill", "late_warp", "view_latency_min_ms",
                      "view_latency_max_ms", "scene_latency_min_ms", "scene_latency_max_ms", "fill_hz", "refresh_hz",
                      "game", "description", "used_in", "mean_fps", "low_1pct_fps", "low_5pct_fps",
                      "frame_time_median_ms", "frame_time_p95_ms", "frame_time_p99_ms", "frame_time_max_ms", "stutters",
                      "view_latency_median_ms", "view_latency_p95_ms", "scene_latency_median_ms",
                      "scene_latency_p95_ms"]
    names = list(dict.fromkeys(r["condition"] for r in rows))
    assert data["conditions_file"] == "conditions.csv"
    assert list(dict.fromkeys(r["condition"] for r in data["conditions"])) == names
    assert {r["condition"] for r in read_csv(export / "hitrates.csv")} <= set(names)
    fixture = {r["condition"]: r for r in read_csv(ROOT / "analysis" / "tests" / "data" / "conditions.csv")}
    for r in rows:
        preset = fixture.get(r["condition"])
        if preset is None:
            continue
        for column in ("render_hz", "fill_hz"):
            assert float(r[column] or 0) == float(preset[column] or 0), (r["condition"], column)
        for column in ("fill", "late_warp"):
            assert r[column] == preset[column], (r["condition"], column)
        # The preset's lag in ms, to the nearest whole display frame at this refresh.
        refresh = float(r["refresh_hz"])
        lag_ms = int(r["lag_frames"]) * 1000 / refresh
        assert abs(lag_ms - int(preset["lag_frames"]) * 1000 / float(preset["refresh_hz"])) <= 500 / refresh + 1e-9, \
            r["condition"]
    text = (report / "report.md").read_text()
    assert "## Conditions" in text and all(f"| {name} |" in text for name in data["condition_order"] if name in names)


def test_a_condition_the_protocol_defines_reaches_every_table(study):
    _, export, report = study
    data = json.loads((report / "report.json").read_text())
    rows = {r["condition"]: r for r in read_csv(export / "conditions.csv")}
    assert rows["lag60x5-rotation"]["late_warp"] == "rotation"
    assert rows["lag60x5-rotation"]["lag_frames"] == "10"
    assert float(rows["lag60x5-rotation"]["view_latency_max_ms"]) == pytest.approx(1000 / 120)
    assert float(rows["lag60x5"]["view_latency_min_ms"]) == pytest.approx(10000 / 120)
    names = {r["condition"] for r in data["conditions"]}
    for name in ("base60", "lag60x5", "lag60x5-rotation", "lag60x5-depth"):
        assert name in names
    # Late warp upconverts: it comes before the plain lagged condition in every sign test.
    pairs = {(t["game"], t["a"], t["b"]) for t in data["sign_tests"]}
    assert ("shooter", "lag60x5-rotation", "lag60x5") in pairs
    assert ("shooter", "lag60x5-depth", "lag60x5") in pairs
    text = (report / "report.md").read_text()
    assert "each frame late-warped by the camera's rotation" in text
    # The mixed model of the shooter's hits has them as levels, and the sample-size plan made by
    # default plans each of them against the reference.
    [shooter] = [m for m in data["mixed_models"]["models"] if m["key"] == "shooter/hit"]
    assert {"base60", "lag60x5", "lag60x5-rotation", "lag60x5-depth"} <= set(shooter["conditions"])
    [planned] = [m for m in data["power"]["models"] if m["model"] == "shooter/hit"]
    assert [(c["a"], c["b"]) for c in planned["contrasts"]] == [(c, shooter["reference"])
                                                              for c in shooter["conditions"][1:]]
