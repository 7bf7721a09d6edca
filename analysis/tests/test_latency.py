"""latency.csv (docs/export.md) into the report's latency histograms: read, checked, binned exactly
and drawn."""
import json
import os
import shutil
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))
import analyze  # noqa: E402
from warplab_analysis import inputs  # noqa: E402
from warplab_analysis.inputs import BadInput  # noqa: E402

DATA = os.path.join(os.path.dirname(__file__), "data")
HEADER = "game,condition,refresh_hz,kind,latency_ms_from,latency_ms_to,weight\n"
# conv15 at 120 Hz holds each render for 66.7 ms: a mouse step waits 0 to 66.7 ms, uniformly.
# warp15to120's scene latency: two spans of unequal weight.
ROWS = ["shooter,conv15,120,view,0,66.66666666666667,1\n",
        "shooter,conv15,120,scene,8.333333333333334,75,1\n",
        "shooter,warp15to120,120,view,0,8.333333333333334,1\n",
        "shooter,warp15to120,120,scene,0,8.333333333333334,0.25\n",
        "shooter,warp15to120,120,scene,50,58.333333333333336,0.75\n"]


def write_latency(folder, rows=ROWS):
    (folder / "latency.csv").write_text(HEADER + "".join(rows))


def test_latency_is_read_per_condition_and_kind(tmp_path):
    write_latency(tmp_path)
    got = inputs.load_latency(str(tmp_path))
    assert list(got) == [("shooter", "conv15", 120.0), ("shooter", "warp15to120", 120.0)]
    assert got[("shooter", "conv15", 120.0)]["view"] == [(0.0, 66.66666666666667, 1.0)]
    assert [w for _, _, w in got[("shooter", "warp15to120", 120.0)]["scene"]] == [0.25, 0.75]


def test_an_export_without_latency_draws_none(tmp_path):
    assert inputs.load_latency(str(tmp_path)) == {}


def test_the_bins_hold_each_spans_weight_by_overlap():
    from warplab_analysis import figures
    edges = np.arange(0.0, 80.0, 10.0)
    shares = figures.latency_shares([(0.0, 20.0, 0.8), (15.0, 25.0, 0.2)], edges)
    # [0, 10): half of the first; [10, 20): the other half of it and half of the second; [20, 30): the rest.
    assert shares == pytest.approx([0.4, 0.4 + 0.1, 0.1, 0, 0, 0, 0])
    assert figures.latency_bin_width(216.7) == 1.0  # 216.7 ms in 250 bins: 0.87 ms, up to 1
    assert figures.latency_bin_width(75.0) == 0.5  # 0.3 ms, up to 0.5
    assert figures.latency_bin_width(500.0) == 2.0  # exactly 2: not up to 5


@pytest.mark.parametrize("row, sentence", [
    ("shooter,conv15,120,mouse,0,66,1\n", r"line 2, column 'kind' is not view or scene: 'mouse'"),
    ("shooter,conv15,120,view,66,66,1\n", r"line 2, column 'latency_ms_to' is not above latency_ms_from: '66'"),
    ("shooter,conv15,120,view,0,66,0\n", r"line 2, column 'weight' is not above 0"),
    ("shooter,conv15,120,view,0,66,0.5\n", r"the weights of conv15's view latency \(shooter, 120 Hz\) add up to 0.5, "
                                           r"not 1"),
])
def test_bad_latency_rows_name_what_is_wrong(tmp_path, row, sentence):
    write_latency(tmp_path, [row])
    with pytest.raises(BadInput, match=r"latency.csv: " + sentence):
        inputs.load_latency(str(tmp_path))


def thesis_export(folder):
    folder.mkdir()
    shutil.copy(os.path.join(DATA, "thesis_table1_hitrates.csv"), folder / "hitrates.csv")
    shutil.copy(os.path.join(DATA, "modes.csv"), folder / "modes.csv")
    return folder


def test_the_report_draws_latency_png_from_latency_csv(tmp_path, monkeypatch):
    export = thesis_export(tmp_path / "export")
    write_latency(export)
    from warplab_analysis import figures
    drawn = []
    draw = figures.latency_figure

    def recording(path, distributions, palette):
        drawn.append(distributions)
        draw(path, distributions, palette)
    monkeypatch.setattr(figures, "latency_figure", recording)
    out = tmp_path / "report"
    assert analyze.main([str(export), "--out", str(out)]) == 0
    assert drawn == [inputs.load_latency(str(export))]
    png = out / "latency.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10000
    assert "latency.png" in json.loads((out / "report.json").read_text())["figures"]


def test_a_bad_latency_csv_ends_the_report_in_one_sentence(tmp_path, capsys):
    export = thesis_export(tmp_path / "export")
    write_latency(export, ["shooter,conv15,120,view,0,66,0.5\n"])
    assert analyze.main([str(export), "--out", str(tmp_path / "report")]) == 1
    err = capsys.readouterr().err.strip()
    assert err.startswith("analyze: ") and err.endswith("add up to 0.5, not 1.") and "\n" not in err
    assert not (tmp_path / "report" / "latency.png").exists()
