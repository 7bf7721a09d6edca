"""People apart from scripted players, the questions asked after blocks, and the hit-rate figure's
points: on small exports written here, their numbers checked against independent computations
(scipy's sign test, R's quantile type 7 where Rscript is installed)."""
import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import scipy.stats

ANALYSIS = Path(__file__).resolve().parents[1]
DATA = Path(__file__).resolve().parent / "data"
sys.path.insert(0, str(ANALYSIS))

import analyze  # noqa: E402
from warplab_analysis import figures  # noqa: E402

PEOPLE = {"P1": (150, 120), "P2": (140, 130), "P5": (160, 150)}  # conv120 hits, conv15 hits, of 200
BOTS = {"P3": (100, 180), "P4": (90, 170)}  # the other way round: pooled, they would blur the people's
ANSWERS_HEADER = ("participant,session,game,block,scored_phase,block_index,mode,question_index,question_id,kind,"
                  "prompt,value,text,answered_with,scale_min,scale_max,time_s,answer_s,player_kind,"
                  "condition_position")
LIKERT = {"conv120": [6, 7, 5, 2, 2], "conv15": [3, 4, 2, 6, 7]}  # P1, P2, P5, P3, P4


def write_mixed(export, kinds=True):
    order = ["P1", "P2", "P5", "P3", "P4"]
    rows = ["participant,game,mode,shots,hits,timeouts,hit_rate" + (",player_kind" if kinds else "")]
    for p in order:
        kind = "human" if p in PEOPLE else "bot"
        for k, condition in enumerate(("conv120", "conv15")):
            hits = (PEOPLE.get(p) or BOTS[p])[k]
            rows.append(f"{p},shooter,{condition},200,{hits},0,{hits / 200}" + (f",{kind}" if kinds else ""))
    (export / "hitrates.csv").write_text("\n".join(rows) + "\n", encoding="utf-8")
    shutil.copy(DATA / "modes.csv", export / "modes.csv")
    answers = [ANSWERS_HEADER]
    for index, condition in enumerate(("conv120", "conv15")):
        for i, p in enumerate(order):
            kind = "human" if p in PEOPLE else "bot"
            answers.append(f"{p},{p}.s,shooter,test,true,{index},{condition},0,smooth,likert,How smooth?,"
                           f"{LIKERT[condition][i]},,key,1,7,1,1,{kind},{index + 1}")
            answers.append(f'{p},{p}.s,shooter,test,true,{index},{condition},1,what,text,Anything else?,,'
                           f'"said {p}, {condition}",typed,,,1,1,{kind},{index + 1}')
            answers.append(f"{p},{p}.s,shooter,test,true,{index},{condition},2,pick,choice,Which?,"
                           f"{1 + i % 2},{'AB'[i % 2]},key,1,2,1,1,{kind},{index + 1}")
    (export / "answers.csv").write_text("\n".join(answers) + "\n", encoding="utf-8")
    return export


def run(export, out, *extra):
    assert analyze.main([str(export), "--out", str(out), "--no-power", *extra]) == 0
    return json.loads((out / "report.json").read_text()), (out / "report.md").read_text(encoding="utf-8")


def test_a_mixed_export_names_people_and_bots_and_tests_the_people_alone(tmp_path):
    report, md = run(write_mixed(tmp_path), tmp_path / "out")
    sentence = "5 participants: 3 people (P1, P2, P5), 2 bots (P3, P4)."
    assert report["players"]["sentence"] == sentence
    # At the top: before any statistics.
    assert md.index(sentence) < md.index("## ")
    assert "**people only** (P1, P2, P5)" in md
    (test,) = report["sign_tests"]
    assert (test["a"], test["b"], test["positive"], test["negative"]) == ("conv120", "conv15", 3, 0)
    assert test["p_two_sided"] == pytest.approx(scipy.stats.binomtest(3, 3).pvalue)
    assert report["games"]["shooter"]["participants"] == ["P1", "P2", "P5"]
    (bots,) = report["player_groups"]
    assert bots["group"] == "scripted" and bots["participants"] == ["P3", "P4"]
    assert (bots["sign_tests"][0]["positive"], bots["sign_tests"][0]["negative"]) == (0, 2)
    assert "# Scripted players (bots and simulated participants), on their own: P3, P4" in md
    assert (tmp_path / "out" / "scripted_shooter_hit_rates.png").exists()


def test_pooling_says_so_and_counts_everyone(tmp_path):
    report, md = run(write_mixed(tmp_path), tmp_path / "out", "--pool-players")
    (test,) = report["sign_tests"]
    assert (test["positive"], test["negative"]) == (3, 2)
    assert "player_groups" not in report and report["players"]["pooled"] is True
    assert "**pooled** (--pool-players)" in md


def test_an_export_without_player_kind_is_analysed_as_before_and_says_so_once(tmp_path):
    report, md = run(write_mixed(tmp_path, kinds=False), tmp_path / "out")
    (test,) = report["sign_tests"]
    assert (test["positive"], test["negative"]) == (3, 2)
    assert report["players"]["kinds"] is None and "player_groups" not in report
    assert md.count("no player_kind column") == 1


def r_quantiles(values):
    script = f"x <- c({', '.join(map(str, values))}); q <- quantile(x, c(.25, .5, .75), type = 7); cat(q, IQR(x))"
    out = subprocess.run(["Rscript", "-e", script], capture_output=True, text=True, check=True).stdout
    return [float(v) for v in out.split()]


def test_questions_are_summarised_per_condition_for_the_people(tmp_path):
    report, md = run(write_mixed(tmp_path), tmp_path / "out")
    likert, text, choice = report["questions"]
    assert (likert["kind"], text["kind"], choice["kind"]) == ("likert", "text", "choice")
    people = LIKERT["conv15"][:3]  # P1, P2, P5: the bots' answers are in their own section
    e = likert["by_condition"]["conv15"]
    assert e["n"] == 3
    if shutil.which("Rscript"):
        q25, median, q75, iqr = r_quantiles(people)
    else:  # type 7 by hand: h = (n − 1) p, interpolated between the sorted values around it
        s = sorted(people)
        q25, median, q75 = s[0] + 0.5 * (s[1] - s[0]), s[1], s[1] + 0.5 * (s[2] - s[1])
        iqr = q75 - q25
    assert (e["q25"], e["median"], e["q75"], e["iqr"]) == pytest.approx((q25, median, q75, iqr))
    assert [a["participant"] for a in text["by_condition"]["conv120"]["answers"]] == ["P1", "P2", "P5"]
    assert text["by_condition"]["conv120"]["answers"][0]["text"] == "said P1, conv120"
    assert choice["by_condition"]["conv15"]["counts"] == [{"option": 1, "text": "A", "count": 2},
                                                     {"option": 2, "text": "B", "count": 1}]
    assert "### Question 1 (likert): smooth: How smooth?" in md and "said P5, conv15" in md
    bots = report["player_groups"][0]["questions"][0]["by_condition"]["conv120"]
    assert bots["n"] == 2 and bots["median"] == 2


def test_the_hit_rate_figure_draws_points_not_lines_across_participants(tmp_path, monkeypatch):
    drawn = []
    monkeypatch.setattr(figures.plt, "close", lambda fig: drawn.append(fig))
    rates = {p: {m: {"hit_rate": 0.5 + 0.1 * k} for k, m in enumerate(("a", "b"))} for p in ("P1", "P2", "P3")}
    figures.hit_rates_figure(str(tmp_path / "f.png"), "shooter", ["P1", "P2", "P3"], ["a", "b"], rates, "hits",
                             ["a", "b"])
    (fig,) = [f for f in drawn if getattr(f, "axes", None)]  # matplotlib may close other things too
    series = [line for line in fig.axes[0].get_lines() if len(line.get_xdata()) == 3]
    assert len(series) == 2
    assert all(line.get_linestyle() == "None" for line in series)
