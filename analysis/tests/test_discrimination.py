"""The discrimination thresholds (warplab_analysis/discrimination.py) on exports written here from
simulated observers: nine participants, each with a known Weibull function of added lag in one
procedure (QUEST+-placed trials, the function on the log scale) and a known logistic one in the
other (constant stimuli, linear scale) whose 75 % point is higher -- the lag a late warp hides.
The refits are checked against psychometric.fit's own answer on the same trials, the paired
comparison against scipy computed here, and the report against the files it is made from."""
import math

import numpy as np
import pytest
import scipy.stats

from exports import run_in_process, write

from warplab_analysis import discrimination, psychometric  # noqa: E402  (exports has put analysis/ on the path)

PARTICIPANTS = [f"P{k}" for k in range(1, 10)]
GUESS, LAPSE, PERCENT = 0.5, 0.02, 75.0
# procedure: (method, reference, shape, scale, slope, mean 75 % point in display frames)
PROCEDURES = {
    "lag": ("quest_plus", "conv120", "weibull", "log", 3.5, 2.0),
    "lag_warped": ("constant_stimuli", "conv120-rotation", "logistic", "linear", 1.6, 3.5),
}
TRIALS_HEADER = ("participant,session,procedure,trial,procedure_trial,method,dimension,reference,level,stimulus,"
                 "test_condition,test_interval,answer,correct,answered_with,answer_s,player_kind,condition_position")
THRESHOLDS_HEADER = ("participant,session,procedure,method,dimension,reference,units,trials,finished,shape,scale,"
                     "guess,percent_correct,fit_lapse,threshold,threshold_low,threshold_high,slope,slope_low,"
                     "slope_high,lapse,lapse_low,lapse_high,player_kind,condition_position")
SESSIONS_HEADER = ("file,participant,game,protocol,seed,started_at,player,completed,flags,status,included,trials,"
                   "matches,note")
CONDITIONS_HEADER = ("condition,render_hz,lag_frames,fill,late_warp,view_latency_min_ms,view_latency_max_ms,"
                     "scene_latency_min_ms,scene_latency_max_ms,fill_hz,refresh_hz,game,description")


def location(shape, scale, slope, point):
    """The function's threshold parameter that puts its PERCENT point at `point`."""
    if scale == "log":
        return point / psychometric.stimulus_at(PERCENT, 1.0, slope, LAPSE, GUESS, shape, scale)
    return point - psychometric.stimulus_at(PERCENT, 0.0, slope, LAPSE, GUESS, shape, scale)


def simulate(seed=20261205, participants=PARTICIPANTS):
    """{(participant, procedure): (levels, correct)} and each one's true 75 % point."""
    rng = np.random.default_rng(seed)
    out, truth = {}, {}
    for participant in participants:
        factor = math.exp(rng.normal(0.0, 0.15))  # participants differ, procedures keep their order
        for procedure, (method, _, shape, scale, slope, point) in PROCEDURES.items():
            point = point * factor
            if method == "quest_plus":  # trials gathered near the threshold, as QUEST+ places them
                levels = np.clip(np.round(point * np.exp(rng.normal(0.0, 0.45, 60))), 1, 10)
            else:
                levels = rng.permutation(np.repeat(np.arange(1.0, 9.0), 8))
            p = psychometric.probability(levels, location(shape, scale, slope, point), slope, LAPSE, GUESS, shape,
                                         scale)
            out[(participant, procedure)] = (levels, (rng.random(len(levels)) < p).astype(int))
            truth[(participant, procedure)] = point
    return out, truth


def session(participant):
    return f"{participant}.warplab-session"


def write_tables(export, simulated, kinds=None):
    """discrimination_trials.csv and thresholds.csv as the spec has export write them; kinds:
    {participant: player_kind}, human by default."""
    kinds = kinds or {}
    trials, thresholds, k = [TRIALS_HEADER], [THRESHOLDS_HEADER], {}
    for (participant, procedure), (levels, correct) in simulated.items():
        method, reference, shape, scale, *_ = PROCEDURES[procedure]
        kind = kinds.get(participant, "human")
        for j, (level, right) in enumerate(zip(levels, correct)):
            trial = k.setdefault(participant, 0)
            k[participant] += 1
            test_interval = 1 + trial % 2
            answer = 3 - test_interval if right else test_interval
            trials.append(f"{participant},{session(participant)},{procedure},{trial},{j},{method},lag_frames,"
                          f"{reference},{level:g},{level:g},{reference}@lag_frames={level:g},{test_interval},{answer},"
                          f"{right},key,0.8,{kind},1")
        if method == "quest_plus":  # what QUEST+ would say: not checked, only carried into the report
            own = "2.1,1.6,2.9,3.4,2.2,5.1,0.02,0,0.05"
        else:
            own = ",,,,,,,,"
        thresholds.append(f"{participant},{session(participant)},{procedure},{method},lag_frames,{reference},"
                          f"display frames,{len(levels)},1,{shape},{scale},{GUESS},{PERCENT:g},{LAPSE},{own},{kind},1")
    write(export / discrimination.TRIALS, trials)
    write(export / discrimination.THRESHOLDS, thresholds)


def write_export(export, simulated, kinds=None):
    """The least a discrimination-only export has: the two tables, sessions.csv, games.csv,
    conditions.csv, and hitrates.csv with its header only (the game has no shots)."""
    kinds = kinds or {}
    export.mkdir(exist_ok=True)
    write_tables(export, simulated, kinds)
    participants = list(dict.fromkeys(p for p, _ in simulated))
    write(export / "sessions.csv", [SESSIONS_HEADER] + [
        f"{session(p)},{p},discrimination,lag-thresholds,7,2026-12-05T00:00:00Z,"
        f"{'sim:7' if kinds.get(p) == 'simulated' else 'human'},true,,ok,true,124,0," for p in participants])
    write(export / "games.csv", ["game,hits_are,shots_are,tables", "shooter,hits,shots,",
                                 "discrimination,correct answers,answers,discrimination_trials.csv;thresholds.csv"])
    write(export / "conditions.csv", [CONDITIONS_HEADER,
                                      "conv120,120,0,hold,none,8.3,16.7,8.3,16.7,,120,discrimination,reference",
                                      "conv120-rotation,120,0,hold,rotation,2,3,8.3,16.7,,120,discrimination,"
                                      "reference with a late warp"])
    write(export / "hitrates.csv", ["participant,game,condition,shots,hits,timeouts,hit_rate,player_kind"])
    return export


@pytest.fixture
def few_resamples(monkeypatch):
    """For the tests of the report's wiring: the bootstrap's own tests use the real count."""
    monkeypatch.setattr(discrimination, "RESAMPLES", 20)


@pytest.fixture(scope="module")
def simulated():
    return simulate()[0]


@pytest.fixture(scope="module")
def section(simulated, tmp_path_factory):
    export = tmp_path_factory.mktemp("tables")
    write_tables(export, simulated)
    return discrimination.analyse(discrimination.load(export))


def test_each_mle_threshold_is_psychometric_fits_own_answer(simulated, section):
    assert len(section["rows"]) == 2 * len(PARTICIPANTS)
    for row in section["rows"]:
        levels, correct = simulated[(row["participant"], row["procedure"])]
        _, _, shape, scale, *_ = PROCEDURES[row["procedure"]]
        f = psychometric.fit(levels, correct, guess=GUESS, lapse=LAPSE, shape=shape, scale=scale)
        expected = psychometric.stimulus_at(PERCENT, f["threshold"], f["slope"], LAPSE, GUESS, shape, scale)
        where = f"{row['participant']} {row['procedure']}"
        assert row["mle"] is not None, where
        assert row["mle"]["threshold"] == pytest.approx(expected, rel=1e-12), where
        assert row["mle"]["slope"] == pytest.approx(f["slope"], rel=1e-12), where
        assert row["trials_found"] == row["trials"] == len(levels)
        assert sum(level["n"] for level in row["levels"]) == len(levels)
        assert row["mle"]["bootstrap_low"] < row["mle"]["threshold"] < row["mle"]["bootstrap_high"], where
        assert row["mle"]["resamples_fitted"] + row["mle"]["resamples_left_out"] == discrimination.RESAMPLES
    # The export's own QUEST+ estimate is carried beside it, as written; constant stimuli have none.
    quest = next(r for r in section["rows"] if r["procedure"] == "lag")
    assert quest["export"] == {"estimate": "posterior mean", "threshold": 2.1, "threshold_low": 1.6,
                               "threshold_high": 2.9, "slope": 3.4, "slope_low": 2.2, "slope_high": 5.1,
                               "lapse": 0.02, "lapse_low": 0.0, "lapse_high": 0.05}
    assert next(r for r in section["rows"] if r["procedure"] == "lag_warped")["export"]["estimate"] is None


def test_the_paired_comparison_is_scipys_and_finds_the_simulated_difference(section):
    (comparison,) = section["comparisons"]
    assert (comparison["a"], comparison["b"], comparison["dimension"]) == ("lag", "lag_warped", "lag_frames")
    mle = {(r["participant"], r["procedure"]): r["mle"]["threshold"] for r in section["rows"]}
    a = np.array([mle[(p, "lag")] for p in PARTICIPANTS])
    b = np.array([mle[(p, "lag_warped")] for p in PARTICIPANTS])
    d = a - b
    assert comparison["n"] == len(PARTICIPANTS)
    assert [pair["participant"] for pair in comparison["pairs"]] == PARTICIPANTS
    assert comparison["mean_diff"] == pytest.approx(d.mean(), rel=1e-12)
    low, high = scipy.stats.ttest_1samp(d, 0.0).confidence_interval(0.95)
    assert (comparison["t_low"], comparison["t_high"]) == pytest.approx((low, high), rel=1e-12)
    assert comparison["p_t"] == pytest.approx(scipy.stats.ttest_rel(a, b).pvalue, rel=1e-12)
    assert comparison["p_wilcoxon"] == pytest.approx(scipy.stats.wilcoxon(a, b).pvalue, rel=1e-12)
    assert comparison["bootstrap_low"] < d.mean() < comparison["bootstrap_high"]
    # The warped procedure's threshold was simulated 1.5 frames higher: a negative difference, sure.
    assert comparison["t_high"] < 0 and comparison["bootstrap_high"] < 0 and comparison["p_t"] < 0.01
    truth = simulate()[1]
    assert comparison["mean_diff"] == pytest.approx(np.mean([truth[(p, "lag")] - truth[(p, "lag_warped")]
                                                             for p in PARTICIPANTS]), abs=0.6)


def test_the_bootstrap_intervals_are_seeded(simulated, tmp_path, monkeypatch):
    write_tables(tmp_path, {key: value for key, value in simulated.items() if key[0] in ("P1", "P2", "P3")})

    def intervals():
        section = discrimination.analyse(discrimination.load(tmp_path))
        return ([(r["mle"]["bootstrap_low"], r["mle"]["bootstrap_high"]) for r in section["rows"]],
                [(c["bootstrap_low"], c["bootstrap_high"]) for c in section["comparisons"]])

    first = intervals()
    assert intervals() == first
    monkeypatch.setattr(discrimination, "SEED", 2)
    # Another seed, other intervals. (Not the comparison's: three participants' means have ten
    # distinct resamples, whose percentiles 10,000 draws of any seed find alike.)
    assert intervals()[0] != first[0]
    # The comparison's, on nine participants' thresholds.
    a, b = np.random.default_rng(3).normal(2.0, 0.5, (2, 9)) + [[0.0], [1.5]]
    again = discrimination.paired(a, b)
    monkeypatch.setattr(discrimination, "SEED", 1)
    assert discrimination.paired(a, b) == discrimination.paired(a, b) != again


def test_data_problems_are_one_sentence_each(simulated, tmp_path):
    data = dict(simulated)
    levels, correct = data[("P2", "lag")]
    data[("P2", "lag")] = (levels, np.ones_like(correct))
    write_tables(tmp_path, data)
    # P3's QUEST+ trials lost: its thresholds.csv row stays.
    lines = (tmp_path / discrimination.TRIALS).read_text().splitlines()
    write(tmp_path / discrimination.TRIALS, [line for line in lines
                                             if not line.startswith("P3,P3.warplab-session,lag,")])
    section = discrimination.analyse(discrimination.load(tmp_path))
    notes = section["notes"]
    assert ("P2's lag (session P2.warplab-session): every one of its 60 answers is correct, which bounds the "
            "threshold from above only (below the easiest level tried), so no MLE threshold.") in notes
    assert ("P3's lag (session P3.warplab-session): discrimination_trials.csv has none of its trials, so no MLE "
            "threshold.") in notes
    assert [r["mle"] for r in section["rows"] if (r["participant"], r["procedure"]) in (("P2", "lag"), ("P3", "lag"))] \
        == [None, None]
    (comparison,) = section["comparisons"]
    assert comparison["n"] == len(PARTICIPANTS) - 2
    assert all(len(note.split(". ")) == 1 for note in notes), notes


def test_a_single_participant_gives_a_sentence_not_a_comparison(simulated, tmp_path):
    write_tables(tmp_path, {key: value for key, value in simulated.items() if key[0] == "P1"})
    section = discrimination.analyse(discrimination.load(tmp_path))
    (comparison,) = section["comparisons"]
    assert comparison["n"] == 1 and comparison["mean_diff"] is None and comparison["p_t"] is None
    assert [note for note in section["notes"] if " against " in note] == [
        "lag against lag_warped: only P1 has an MLE threshold in both, and a paired comparison needs two participants "
        "or more."]


def test_several_sessions_of_a_participant_count_once_by_their_mean(simulated, tmp_path):
    write_tables(tmp_path, simulated)
    export = discrimination.load(tmp_path)
    # P1 comes back for a second session of each procedure, answering as P2 did.
    for row in [r for r in export.rows if r["participant"] == "P1"]:
        export.rows.append(dict(row, session="P1-day2.warplab-session"))
        export.trials[("P1", "P1-day2.warplab-session", row["procedure"])] = export.trials[
            ("P2", session("P2"), row["procedure"])]
    section = discrimination.analyse(export)
    (comparison,) = section["comparisons"]
    assert comparison["n"] == len(PARTICIPANTS)
    p1 = [r for r in section["rows"] if r["participant"] == "P1"]
    assert len(p1) == 4
    means = {procedure: np.mean([r["mle"]["threshold"] for r in p1 if r["procedure"] == procedure])
             for procedure in PROCEDURES}
    (pair,) = [pair for pair in comparison["pairs"] if pair["participant"] == "P1"]
    assert (pair["a"], pair["b"]) == pytest.approx((means["lag"], means["lag_warped"]), rel=1e-12)
    assert "P1 has 2 sessions of lag with an MLE threshold: the comparisons take their mean." in section["notes"]


def test_a_discrimination_export_makes_the_reports_section(simulated, tmp_path, few_resamples):
    export = write_export(tmp_path / "export", simulated)
    code, report = run_in_process(export, tmp_path / "out")
    assert code == 0
    section = report["discrimination"]
    assert section["game"] == "discrimination" and len(section["rows"]) == 2 * len(PARTICIPANTS)
    row = section["rows"][0]
    assert {"export", "mle", "trials", "levels", "fit_lapse", "percent_correct"} <= set(row)
    assert {"threshold", "bootstrap_low", "bootstrap_high", "slope", "lapse"} <= set(row["mle"])
    assert section["comparisons"][0]["n"] == len(PARTICIPANTS)
    assert section["figures"] == {"lag_frames": "discrimination_lag_frames.png"}
    assert (tmp_path / "out" / "discrimination_lag_frames.png").is_file()
    assert report["games"] == {} and report["sign_tests"] == []
    assert report["inputs"]["thresholds.csv"] == {"rows": 18}
    assert report["condition_order"] == ["conv120-rotation", "conv120"]
    assert report["players"]["sentence"].startswith("9 participants: 9 people")
    md = (tmp_path / "out" / "report.md").read_text(encoding="utf-8")
    assert "## Discrimination thresholds\n" in md and "hit rate" not in md.lower()
    assert "### lag: lag\\_frames (display frames), QUEST+, threshold at 75 % correct" in md
    assert "### lag\\_warped: lag\\_frames (display frames), constant stimuli, threshold at 75 % correct" in md
    assert "### Paired comparisons of thresholds" in md
    assert "| lag\\_frames | lag − lag\\_warped | 9 |" in md
    assert "![lag\\_frames: each participant's psychometric curves](discrimination_lag_frames.png)" in md
    assert "| P1 | 60 | 2.1 [1.6, 2.9] |" in md  # the export's QUEST+ estimate beside the refit


def test_people_and_simulated_participants_each_get_their_section(simulated, tmp_path, few_resamples):
    kinds = {p: "simulated" for p in PARTICIPANTS[6:]}
    export = write_export(tmp_path / "export", simulated, kinds)
    code, report = run_in_process(export, tmp_path / "out")
    assert code == 0
    assert {r["participant"] for r in report["discrimination"]["rows"]} == set(PARTICIPANTS[:6])
    (scripted,) = report["player_groups"]
    assert {r["participant"] for r in scripted["discrimination"]["rows"]} == set(PARTICIPANTS[6:])
    assert (tmp_path / "out" / "scripted_discrimination_lag_frames.png").is_file()
    md = (tmp_path / "out" / "report.md").read_text(encoding="utf-8")
    assert md.count("## Discrimination thresholds") == 2


def test_beside_the_shooters_hit_rates_and_without_rows_of_its_own(simulated, tmp_path, few_resamples):
    """An export of both games: the shooter's hit rates as before, the discrimination game with no
    hit-rate rows (or rows without shots, which have no rate) and its own section."""
    export = write_export(tmp_path / "export", simulated)
    rows = [f"{p},shooter,{c},20,{h},0,{h / 20},human" for p, h in (("S1", 12), ("S2", 15))
            for c in ("conv120", "conv120-rotation")]
    rows += [f"{p},discrimination,conv120,0,0,,,human" for p in PARTICIPANTS]
    write(export / "hitrates.csv", ["participant,game,condition,shots,hits,timeouts,hit_rate,player_kind"] + rows)
    code, report = run_in_process(export, tmp_path / "out")
    assert code == 0
    assert list(report["games"]) == ["shooter"] and report["discrimination"]["comparisons"][0]["n"] == 9
    md = (tmp_path / "out" / "report.md").read_text(encoding="utf-8")
    assert md.index("## Shooter: hit rates") < md.index("## Discrimination thresholds")
    assert "Table 1 (discrimination)" not in md


def test_an_export_without_discrimination_sessions_has_no_section(tmp_path):
    """Export writes every game's tables, header only when none of its sessions is included."""
    write(tmp_path / discrimination.TRIALS, [TRIALS_HEADER])
    write(tmp_path / discrimination.THRESHOLDS, [THRESHOLDS_HEADER])
    assert discrimination.load(tmp_path) is None
    write(tmp_path / "hitrates.csv", ["participant,game,condition,shots,hits,timeouts,hit_rate",
                                      "a,shooter,conv15,10,3,0,0.3", "b,shooter,conv15,10,4,0,0.4"])
    code, report = run_in_process(tmp_path, tmp_path / "out")
    assert code == 0 and report["discrimination"] is None
    assert "Discrimination" not in (tmp_path / "out" / "report.md").read_text(encoding="utf-8")


def test_a_malformed_thresholds_file_is_one_sentence(simulated, tmp_path, capsys):
    export = write_export(tmp_path, simulated)
    lines = (export / discrimination.THRESHOLDS).read_text().splitlines()
    lines[2] = lines[2].replace(",weibull,", ",gumbel,").replace(",logistic,", ",gumbel,")
    write(export / discrimination.THRESHOLDS, lines)
    code, _ = run_in_process(export, tmp_path / "out")
    err = capsys.readouterr().err.strip()
    assert code == 1 and len(err.splitlines()) == 1
    assert err.endswith("thresholds.csv: line 3, column 'shape' is not logistic or weibull: 'gumbel'."), err
