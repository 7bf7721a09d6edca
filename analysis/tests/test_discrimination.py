"""The discrimination thresholds (warplab_analysis/discrimination.py) on exports written here from
simulated observers: nine participants, each with a known Weibull function of added lag in one
procedure (QUEST+-placed trials, the function on the log scale) and a known logistic one in the
other (constant stimuli, linear scale) whose 75 % point is higher -- the lag a late warp hides.
The refits are checked against psychometric.fit's own answer on the same trials, the paired
comparison against scipy computed here, and the report against the files it is made from."""
import csv
import math

import numpy as np
import pytest
import scipy.stats

from exports import run_in_process, write

from warplab_analysis import discrimination, figures, psychometric  # noqa: E402  (exports has put analysis/ on the path)

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


def write_tables(export, simulated, kinds=None, methods=None, own=None):
    """discrimination_trials.csv and thresholds.csv as the spec has export write them; kinds:
    {participant: player_kind}, human by default; methods: {procedure: method} in place of
    PROCEDURES'; own: {(participant, procedure): the nine cells threshold..lapse_high} in place of
    the fixed QUEST+ estimate below."""
    kinds, methods, own_cells = kinds or {}, methods or {}, own or {}
    trials, thresholds, k = [TRIALS_HEADER], [THRESHOLDS_HEADER], {}
    for (participant, procedure), (levels, correct) in simulated.items():
        method, reference, shape, scale, *_ = PROCEDURES[procedure]
        method = methods.get(procedure, method)
        kind = kinds.get(participant, "human")
        for j, (level, right) in enumerate(zip(levels, correct)):
            trial = k.setdefault(participant, 0)
            k[participant] += 1
            test_interval = 1 + trial % 2
            answer = 3 - test_interval if right else test_interval
            trials.append(f"{participant},{session(participant)},{procedure},{trial},{j},{method},lag_frames,"
                          f"{reference},{level:g},{level:g},{reference}@lag_frames={level:g},{test_interval},{answer},"
                          f"{right},key,0.8,{kind},1")
        if (participant, procedure) in own_cells:
            own = own_cells[(participant, procedure)]
        elif method == "quest_plus":  # what QUEST+ would say: not checked, only carried into the report
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


def compared(section, estimate):
    """The section's comparisons on one estimate: "procedure" (the procedures' own) or "mle"."""
    return [c for c in section["comparisons"] if c["estimate"] == estimate]


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
    location = quest["export"].pop("location")
    assert quest["export"] == {"estimate": "posterior mean", "threshold": 2.1, "threshold_low": 1.6,
                               "threshold_high": 2.9, "slope": 3.4, "slope_low": 2.2, "slope_high": 5.1,
                               "lapse": 0.02, "lapse_low": 0.0, "lapse_high": 0.05}
    # With it, the function QUEST+ concluded: 75 % correct at its threshold.
    assert psychometric.probability(2.1, location, 3.4, 0.02, GUESS, "weibull", "log") == pytest.approx(0.75,
                                                                                                         rel=1e-12)
    warped = next(r for r in section["rows"] if r["procedure"] == "lag_warped")
    assert warped["export"]["estimate"] is None and warped["export"]["location"] is None


def test_the_paired_comparison_is_scipys_and_finds_the_simulated_difference(section):
    # Constant stimuli make no estimate of their own, so the MLE's is the one comparison.
    assert compared(section, "procedure") == []
    (comparison,) = compared(section, "mle")
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
    (comparison,) = compared(section, "mle")
    assert comparison["n"] == len(PARTICIPANTS) - 2
    assert all(len(note.split(". ")) == 1 for note in notes), notes


def test_a_single_participant_gives_a_sentence_not_a_comparison(simulated, tmp_path):
    write_tables(tmp_path, {key: value for key, value in simulated.items() if key[0] == "P1"})
    section = discrimination.analyse(discrimination.load(tmp_path))
    (comparison,) = compared(section, "mle")
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
    (comparison,) = compared(section, "mle")
    assert comparison["n"] == len(PARTICIPANTS)
    p1 = [r for r in section["rows"] if r["participant"] == "P1"]
    assert len(p1) == 4
    means = {procedure: np.mean([r["mle"]["threshold"] for r in p1 if r["procedure"] == procedure])
             for procedure in PROCEDURES}
    (pair,) = [pair for pair in comparison["pairs"] if pair["participant"] == "P1"]
    assert (pair["a"], pair["b"]) == pytest.approx((means["lag"], means["lag_warped"]), rel=1e-12)
    assert ("P1 has 2 sessions of lag: the comparisons take the mean of their thresholds, each over the sessions "
            "that have one.") in section["notes"]


def own_estimates(participants, seed=7):
    """{(participant, procedure): thresholds.csv's nine cells threshold..lapse_high} of two QUEST+
    procedures, each participant's posterior means drawn apart, the second about 1.5 frames higher."""
    rng = np.random.default_rng(seed)
    cells = {}
    for participant in participants:
        for procedure, shift in (("lag", 0.0), ("lag_warped", 1.5)):
            t = 2.0 + shift + rng.normal(0.0, 0.6)
            cells[(participant, procedure)] = f"{t!r},{0.6 * t!r},{1.5 * t!r},3.1,1.5,6,0.02,0,0.05"
    return cells


def separated(participants):
    """Trials QUEST+-like in count, every answer wrong below a level and right from it up: no MLE
    has a maximum."""
    levels = np.repeat(np.arange(1.0, 9.0), 3)
    return {(p, procedure): (levels, (levels >= step).astype(int))
            for p in participants for procedure, step in (("lag", 3.0), ("lag_warped", 5.0))}


def thresholds_column(path):
    """{(participant, procedure): threshold} read here from thresholds.csv, empty cells left out."""
    with open(path, newline="", encoding="utf-8") as f:
        return {(r["participant"], r["procedure"]): float(r["threshold"]) for r in csv.DictReader(f)
                if r["threshold"] != ""}


def test_the_own_estimate_comparison_is_scipys_on_the_thresholds_column(simulated, tmp_path):
    own = own_estimates(PARTICIPANTS)
    own[("P4", "lag_warped")] = ",,,,,,,,"  # P4's second procedure has no estimate: P4 is left out
    own[("P2", "lag_warped")] = "40.0,30.0,50.0,3.1,1.5,6,0.02,0,0.05"  # beyond every level (1 to 8): kept, noted
    write_tables(tmp_path, simulated, methods={"lag_warped": "quest_plus"}, own=own)
    section = discrimination.analyse(discrimination.load(tmp_path))
    (comparison,) = compared(section, "procedure")
    column = thresholds_column(tmp_path / discrimination.THRESHOLDS)
    both = [p for p in PARTICIPANTS if (p, "lag") in column and (p, "lag_warped") in column]
    assert both == [p for p in PARTICIPANTS if p != "P4"]
    a = np.array([column[(p, "lag")] for p in both])
    b = np.array([column[(p, "lag_warped")] for p in both])
    d = a - b
    assert (comparison["a"], comparison["b"], comparison["n"]) == ("lag", "lag_warped", len(both))
    assert [pair["participant"] for pair in comparison["pairs"]] == both
    assert comparison["mean_diff"] == pytest.approx(d.mean(), rel=1e-12)
    low, high = scipy.stats.ttest_1samp(d, 0.0).confidence_interval(0.95)
    assert (comparison["t_low"], comparison["t_high"]) == pytest.approx((low, high), rel=1e-12)
    assert comparison["t"] == pytest.approx(scipy.stats.ttest_rel(a, b).statistic, rel=1e-12)
    assert comparison["p_t"] == pytest.approx(scipy.stats.ttest_rel(a, b).pvalue, rel=1e-12)
    assert comparison["p_wilcoxon"] == pytest.approx(scipy.stats.wilcoxon(a, b).pvalue, rel=1e-12)
    assert comparison["bootstrap_low"] < d.mean() < comparison["bootstrap_high"]
    assert ("lag_warped: in 1 session (P2) the procedure's own threshold lies above every level presented, so it "
            "rests on its prior and the end of its grid more than on the trials; the comparisons on own estimates "
            "take it as it is.") in section["notes"]
    # The same pair on the MLE thresholds follows it, over every participant (each has trials).
    assert [c["estimate"] for c in section["comparisons"]] == ["procedure", "mle"]
    assert compared(section, "mle")[0]["n"] == len(PARTICIPANTS)


def test_the_own_estimates_are_compared_when_every_mle_fails(tmp_path, few_resamples):
    participants = PARTICIPANTS[:4]
    export = tmp_path / "export"
    write_export(export, separated(participants))
    write_tables(export, separated(participants), methods={"lag_warped": "quest_plus"},
                 own=own_estimates(participants))
    section = discrimination.analyse(discrimination.load(export))
    assert all(row["mle"] is None for row in section["rows"])
    (own,) = compared(section, "procedure")
    (mle,) = compared(section, "mle")
    column = thresholds_column(export / discrimination.THRESHOLDS)
    d = [column[(p, "lag")] - column[(p, "lag_warped")] for p in participants]
    assert own["n"] == len(participants) and own["mean_diff"] == pytest.approx(np.mean(d), rel=1e-12)
    assert mle["n"] == 0 and mle["mean_diff"] is None
    notes = section["notes"]
    assert ("lag against lag_warped: no participant has an MLE threshold in both, and a paired comparison needs two "
            "participants or more.") in notes
    assert ("lag against lag_warped, on the procedures' own estimates: with 4 non-zero differences the exact "
            "Wilcoxon test's two-sided p is at least 2 / 2^4 = 0.125, however large they are; the t-test's is not "
            "bounded so.") in notes
    # In the report: the own estimates' table first, then the MLE's.
    code, _ = run_in_process(export, tmp_path / "out")
    assert code == 0
    md = (tmp_path / "out" / "report.md").read_text(encoding="utf-8")
    first, second = md.index("#### On the procedures' own estimates"), md.index("#### On the MLE thresholds")
    assert first < md.index("| lag\\_frames | lag − lag\\_warped | 4 |", first) < second
    assert md.index("| lag\\_frames | lag − lag\\_warped | 0 |", second) > second


def test_a_staircase_against_quest_plus_says_their_own_estimates_differ_in_kind(simulated, tmp_path):
    own = {(p, "lag_warped"): "3.6,,,,,,,," for p in PARTICIPANTS}
    write_tables(tmp_path, simulated, methods={"lag_warped": "staircase"}, own=own)
    section = discrimination.analyse(discrimination.load(tmp_path))
    assert [c["n"] for c in compared(section, "procedure")] == [len(PARTICIPANTS)]
    assert ("lag against lag_warped: their own estimates are of different kinds (posterior mean and mean of the last "
            "reversals), so the difference of those mixes the procedures with the estimators; the MLE thresholds "
            "are one estimator of both.") in section["notes"]


def write_tables_to(folder, data):
    folder.mkdir()
    write_tables(folder, data)
    return folder


@pytest.mark.parametrize("shape", psychometric.SHAPES)
@pytest.mark.parametrize("scale", psychometric.SCALES)
def test_the_location_of_a_threshold_at_a_percent_correct_round_trips(shape, scale):
    """location_at inverts stimulus_at in its threshold: stimulus_at of the location found is the
    stimulus, and the function itself gives the percent correct there."""
    for stimulus in (0.7, 2.1, 28.0):
        for slope in (0.8, 3.4) if scale == "log" else (0.3, 1.6):
            for lapse, guess, percent in ((0.0, 0.5, 75.0), (0.03, 0.5, 70.7), (0.02, 0.25, 62.5)):
                function = dict(lapse=lapse, guess=guess, shape=shape, scale=scale)
                location = psychometric.location_at(percent, stimulus, slope, **function)
                assert psychometric.stimulus_at(percent, location, slope, **function) == pytest.approx(stimulus,
                                                                                                       rel=1e-12)
                assert psychometric.probability(stimulus, location, slope, **function) == pytest.approx(
                    percent / 100.0, rel=1e-12)
                # A shift on the function's scale: a stimulus k times (log) or c more (linear) moves the
                # location alike.
                if scale == "log":
                    moved = psychometric.location_at(percent, 3.0 * stimulus, slope, **function)
                    assert moved == pytest.approx(3.0 * location, rel=1e-12)
                else:
                    moved = psychometric.location_at(percent, stimulus + 5.0, slope, **function)
                    assert moved == pytest.approx(location + 5.0, rel=1e-12)
    with pytest.raises(ValueError, match="never reaches 99"):
        psychometric.location_at(99.0, 2.0, 3.0, lapse=0.05, guess=0.5, shape=shape, scale=scale)


def test_the_figure_draws_the_procedures_function_dashed_where_no_mle(tmp_path, few_resamples):
    """A row without an MLE fit: the function of QUEST+'s estimate, dashed, through its threshold at
    the percent correct; with a fit, the fit, solid."""
    participants = PARTICIPANTS[:1]
    data = separated(participants)
    write_tables(tmp_path, data, methods={"lag_warped": "quest_plus"}, own=own_estimates(participants))
    section = discrimination.analyse(discrimination.load(tmp_path))
    fitted = discrimination.analyse(discrimination.load(write_tables_to(tmp_path / "fitted", simulate()[0])))
    limits = (0.5, 20.0)
    grid = np.geomspace(*limits, 400)
    for row, style in ((section["rows"][0], "--"), (fitted["rows"][0], "-")):
        fig, ax = figures.plt.subplots()
        figures.discrimination_panel(ax, row, "tab:blue", {"mle": 0.0, "export": 0.0}, grid, 10, limits)
        (curve,) = [line for line in ax.lines if len(line.get_xdata()) > 2]
        assert curve.get_linestyle() == style
        at = row["mle"]["threshold"] if row["mle"] else row["export"]["threshold"]
        assert np.interp(np.log(at), np.log(curve.get_xdata()), curve.get_ydata()) == pytest.approx(0.75, abs=2e-3)
        figures.plt.close(fig)


def test_the_stimulus_axis_spans_levels_and_intervals_up_to_a_cut():
    levels = [2.0, 3.0, 24.0]
    # 0.9 and 40 lie within the reach beyond the levels (a factor of 12^0.35 = 2.4); 8.6e4 and 0.08 do not.
    low, high = figures.stimulus_limits(levels, [0.9, 28.0, 40.0, 8.6e4, 0.08, 0.0], log=True)
    reach = 12.0 ** figures.INTERVAL_REACH
    assert low < 0.9 and high > 40.0
    assert low == pytest.approx(2.0 / reach / (24.0 * reach / (2.0 / reach)) ** 0.06, rel=1e-9)
    assert high == pytest.approx(24.0 * reach * (24.0 * reach / (2.0 / reach)) ** 0.06, rel=1e-9)
    # On a linear axis alike: the reach a share of the levels' span, 0.35 x 10 frames.
    low, high = figures.stimulus_limits([5.0, 15.0], [4.0, 16.0, 100.0], log=False)
    assert low == pytest.approx(4.0 - 0.06 * 14.5) and high == pytest.approx(18.5 + 0.06 * 14.5)
    # A single level: the share of its size, 0.35 x 4 frames.
    low, high = figures.stimulus_limits([4.0, 4.0], [-5.0, 4.5], log=False)
    assert low == pytest.approx(2.6 - 0.06 * 1.9) and high == pytest.approx(4.5 + 0.06 * 1.9)


def test_the_proportion_axis_shows_a_level_answered_wrong_every_time():
    row = {"guess": 0.5, "levels": [{"stimulus": 2.0, "n": 4, "correct": 3}, {"stimulus": 6.0, "n": 1, "correct": 1}]}
    assert figures.proportion_floor([row]) == pytest.approx(0.42)
    row["levels"].append({"stimulus": 3.0, "n": 1, "correct": 0})
    assert figures.proportion_floor([row]) == pytest.approx(-0.04)


def test_a_discrimination_export_makes_the_reports_section(simulated, tmp_path, few_resamples):
    export = write_export(tmp_path / "export", simulated)
    code, report = run_in_process(export, tmp_path / "out")
    assert code == 0
    section = report["discrimination"]
    assert section["game"] == "discrimination" and len(section["rows"]) == 2 * len(PARTICIPANTS)
    row = section["rows"][0]
    assert {"export", "mle", "trials", "levels", "fit_lapse", "percent_correct"} <= set(row)
    assert {"threshold", "bootstrap_low", "bootstrap_high", "slope", "lapse"} <= set(row["mle"])
    assert compared(section, "mle")[0]["n"] == len(PARTICIPANTS)
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
    assert list(report["games"]) == ["shooter"] and compared(report["discrimination"], "mle")[0]["n"] == 9
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
