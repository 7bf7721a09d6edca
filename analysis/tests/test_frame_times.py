"""frametimes.csv (docs/export.md) into the report's frame-time graph."""
import os
import shutil
import sys

import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))
import analyze  # noqa: E402
from warplab_analysis import inputs  # noqa: E402
from warplab_analysis.inputs import BadInput  # noqa: E402

HEADER = "game,condition,refresh_hz,time_s,frame_time_ms\n"


def test_frame_times_are_read_per_condition_and_drawn(tmp_path):
    rows = [f"shooter,conv15,120,{(k + 1) / 15},66.66666666666667\n" for k in range(149)]
    rows += ["shooter,hitchy,120,0.5,16.666666666666668\n", "shooter,hitchy,120,0.6,100\n"]
    (tmp_path / "frametimes.csv").write_text(HEADER + "".join(rows))
    series = inputs.load_frame_times(str(tmp_path))
    assert list(series) == [("shooter", "conv15", 120.0), ("shooter", "hitchy", 120.0)]
    assert len(series[("shooter", "conv15", 120.0)][1]) == 149
    assert series[("shooter", "hitchy", 120.0)][1] == [16.666666666666668, 100.0]
    from warplab_analysis import figures
    path = tmp_path / "frame_times.png"
    figures.frame_times_figure(str(path), series, ["conv15", "hitchy"])
    assert path.stat().st_size > 10000


def test_every_panel_reaches_the_longest_frame_time(tmp_path):
    # A steady condition drawn first must not cap the axis below a later one's hitch.
    series = {("shooter", "even60", 144.0): ([0.1, 0.2, 0.3], [13.9, 20.8, 13.9]),
              ("shooter", "hitch100", 144.0): ([0.1, 0.2, 0.3], [13.9, 118.1, 20.8])}
    from warplab_analysis import figures
    low, high = figures.frame_times_figure(str(tmp_path / "frame_times.png"), series, ["even60", "hitch100"])
    assert low == 0
    assert 118.1 < high < 130


def test_an_export_without_frame_times_draws_none(tmp_path):
    assert inputs.load_frame_times(str(tmp_path)) == {}


def test_a_frame_time_that_is_not_positive_names_its_line(tmp_path):
    (tmp_path / "frametimes.csv").write_text(HEADER + "shooter,conv15,120,0.1,0\n")
    with pytest.raises(BadInput, match=r"frametimes.csv: line 2, column 'frame_time_ms' is not above 0"):
        inputs.load_frame_times(str(tmp_path))


def test_a_bad_frame_times_csv_ends_the_report_in_one_sentence(tmp_path, capsys):
    data = os.path.join(os.path.dirname(__file__), "data")
    shutil.copy(os.path.join(data, "thesis_table1_hitrates.csv"), tmp_path / "hitrates.csv")
    shutil.copy(os.path.join(data, "modes.csv"), tmp_path / "modes.csv")
    (tmp_path / "frametimes.csv").write_text(HEADER + "shooter,conv15,120,0.1,0\n")
    assert analyze.main([str(tmp_path), "--out", str(tmp_path / "report")]) == 1
    err = capsys.readouterr().err.strip()
    assert err.endswith("column 'frame_time_ms' is not above 0: '0'.") and "\n" not in err
    assert not list((tmp_path / "report").glob("*.png"))
