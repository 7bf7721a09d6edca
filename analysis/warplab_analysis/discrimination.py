"""The discrimination task's thresholds: every session's trials of each procedure refitted by
maximum likelihood beside the estimate the procedure itself exported, and the thresholds of
procedures that vary one stimulus dimension compared, participant by participant.

Inputs (docs/export.md): discrimination_trials.csv, one row per answered trial, and
thresholds.csv, one row per session x procedure, each with the function the procedure assumed
(shape, scale, guess rate), the percent correct its threshold is defined at and the lapse rate a
refit holds fixed. An export writes both files, header only, when no discrimination session is
included: then there is no section.

The refit is psychometric.fit on the row's trials with the lapse held at fit_lapse: a free lapse
is poorly determined by the few trials of one session, and a lapse of zero biases the threshold
and slope whenever a participant lapses (Wichmann and Hill 2001). Its threshold is the stimulus
at the row's percent correct, with a seeded percentile bootstrap over resampled trials
(psychometric.bootstrap_interval). The export's own estimate stays beside it: QUEST+'s posterior
mean with its credible interval (Watson 2017), a staircase's mean of the last reversals (Levitt
1971), nothing for constant stimuli.

Comparisons: for every two procedures of one dimension, d = threshold(a) - threshold(b), twice.
First on each procedure's own estimate, where both make one: QUEST+'s posterior mean exists for
every session, however its answers fall, but rests on the procedure's prior and grids as well as
on the trials (and a staircase's reversal mean is another estimator again). Then on the MLE
thresholds, one estimator of every procedure from the trials alone -- which has none where the
likelihood keeps rising towards a step between two levels, common when QUEST+ places a short
session's trials close to the threshold. Each over the participants with that threshold in both.
The participant is the unit: a participant with several sessions of a procedure (a row each)
contributes the mean of their thresholds, so that a participant who came twice does not count as
two. The mean of d, its 95 % t interval, a seeded bootstrap interval over participants, and
stats.paired_tests' paired t-test and Wilcoxon signed-rank test (scipy's, with mid-ranks for
tied |d|; the matches section's tests).

Problems of the data -- a row without trials, a fit that fails, every answer right, a comparison
with fewer than two participants -- are sentences in the section's notes; a malformed file is
BadInput, as every other file of the export.
"""
import math
import os

import numpy as np
import scipy.stats

from . import psychometric, stats
from .inputs import BadInput, boolean, number, read_table, text

TRIALS = "discrimination_trials.csv"
THRESHOLDS = "thresholds.csv"
TRIALS_REQUIRED = ["participant", "session", "procedure", "stimulus", "correct"]
THRESHOLDS_REQUIRED = ["participant", "session", "procedure", "method", "dimension", "reference", "units", "trials",
                       "shape", "scale", "guess", "percent_correct", "fit_lapse", "threshold", "threshold_low",
                       "threshold_high"]
# QUEST+'s marginals; empty for the other methods, and optional so that a hand-made file may leave them out.
MARGINALS = ("slope", "slope_low", "slope_high", "lapse", "lapse_low", "lapse_high")
# What the export's `threshold` of each method is.
ESTIMATES = {"quest_plus": "posterior mean", "staircase": "mean of the last reversals", "constant_stimuli": None}
# Resamples of each row's bootstrap. A fit takes about 0.7 ms, so a 20-participant x 2-procedure
# export of 60-80 trials a row (40 rows) is bootstrapped in about 3 s. The price: each 2.5 % tail
# of the percentile interval rests on the 3rd and 4th of 100 values, so the interval describes a
# session's precision roughly; it is no test. The paired comparisons, which are the tests, resample
# participants, not trials.
RESAMPLES = 100
SEED = 1
# Resamples of participants for a comparison's interval: a mean of a few dozen numbers each.
PAIRED_RESAMPLES = 10000
# A row's interval rests on the resamples that could be fitted (a resample of a short session often
# has no maximum: its answers step from chance to all correct between two levels). The table says
# how many; beyond this share a note says the interval understates the uncertainty.
LEFT_OUT_NOTE_SHARE = 0.2


class Export:
    """What the two files hold: `rows`, thresholds.csv's rows, parsed; `trials`, {(participant,
    session, procedure): (stimuli, correct)} or None without discrimination_trials.csv; `inputs`,
    the counts report.json's inputs lists; `notes`, sentences on the files themselves."""

    def __init__(self, rows, trials, inputs, notes):
        self.rows, self.trials, self.inputs, self.notes = rows, trials, inputs, notes

    def participants(self):
        return {row["participant"] for row in self.rows} | {key[0] for key in self.trials or {}}

    def player_kinds(self):
        """{participant: set of kinds} from thresholds.csv's player_kind (as hitrates.csv's)."""
        kinds = {}
        for row in self.rows:
            kinds.setdefault(row["participant"], set()).update(k for k in (row["player_kind"] or "").split(";") if k)
        return kinds

    def references(self):
        return list(dict.fromkeys(row["reference"] for row in self.rows))


def load(export_dir):
    """The Export of the folder, or None when it has no discrimination data: neither file, or
    both with their header only."""
    paths = {name: os.path.join(export_dir, name) for name in (THRESHOLDS, TRIALS)}
    if not any(os.path.exists(p) for p in paths.values()):
        return None
    rows, trials, inputs, notes = [], None, {}, []
    if os.path.exists(paths[THRESHOLDS]):
        rows = read_thresholds(paths[THRESHOLDS])
        inputs[THRESHOLDS] = {"rows": len(rows)}
    if os.path.exists(paths[TRIALS]):
        trials, count = read_trials(paths[TRIALS])
        inputs[TRIALS] = {"rows": count}
    if not rows and not trials:
        return None
    if not os.path.exists(paths[THRESHOLDS]):
        notes.append(f"There is no {THRESHOLDS} beside {TRIALS}: without it no procedure says which psychometric "
                     "function to fit, so no thresholds.")
    elif trials is None:
        notes.append(f"There is no {TRIALS} beside {THRESHOLDS}: no trials to refit, so only the procedures' own "
                     "estimates.")
    return Export(rows, trials, inputs, notes)


def read_trials(path):
    """({(participant, session, procedure): (stimuli, correct)} in file order, rows read)."""
    table = read_table(path, TRIALS_REQUIRED)
    trials = {}
    for record in table.records:
        key = tuple(text(table, record, c) for c in ("participant", "session", "procedure"))
        stimuli, correct = trials.setdefault(key, ([], []))
        stimuli.append(number(table, record, "stimulus"))
        correct.append(1.0 if boolean(table, record, "correct") else 0.0)
    return trials, len(table.records)


def read_thresholds(path):
    """thresholds.csv's rows as dicts, each cell of the right type (None where empty and allowed)."""
    table = read_table(path, THRESHOLDS_REQUIRED)
    rows, first_seen = [], {}
    for record in table.records:
        line = record["_line"]
        where = f"{path}: line {line}, column"
        row = {c: text(table, record, c) for c in ("participant", "session", "procedure", "method", "dimension",
                                                     "reference", "units")}
        for column, allowed in (("shape", psychometric.SHAPES), ("scale", psychometric.SCALES)):
            row[column] = text(table, record, column)
            if row[column] not in allowed:
                raise BadInput(f"{where} '{column}' is not {' or '.join(allowed)}: {row[column]!r}.")
        row["trials"] = number(table, record, "trials", integer=True)
        row["finished"] = boolean(table, record, "finished") if record.get("finished", "") != "" else None
        for column in ("guess", "percent_correct", "fit_lapse"):
            row[column] = number(table, record, column)
        if not 0.0 <= row["guess"] < 1.0:
            raise BadInput(f"{where} 'guess' is not from 0 up to 1: {record['guess']!r}.")
        if not 0.0 <= row["fit_lapse"] < 1.0 - row["guess"]:
            raise BadInput(f"{where} 'fit_lapse' is not from 0 up to 1 - guess: {record['fit_lapse']!r}.")
        if not 100.0 * row["guess"] < row["percent_correct"] < 100.0:
            raise BadInput(f"{where} 'percent_correct' is not between the guess rate and 100: "
                           f"{record['percent_correct']!r}.")
        for column in ("threshold", "threshold_low", "threshold_high") + MARGINALS:
            row[column] = number(table, record, column, optional=True) if column in record else None
        row["player_kind"] = record.get("player_kind")
        key = (row["participant"], row["session"], row["procedure"])
        if key in first_seen:
            raise BadInput(f"{where} 'procedure': {row['procedure']!r} has a second row for participant "
                           f"{row['participant']!r} and session {row['session']!r} (the first is on line "
                           f"{first_seen[key]}).")
        first_seen[key] = line
        rows.append(row)
    return rows


def analyse(export, who=None, game=None, order_key=None):
    """The report's section for the participants `who` (None: everyone): `rows` (one per
    thresholds.csv row, participants in `order_key` order), `procedures`, `comparisons`, `notes`,
    `figures` (filled in as they are drawn)."""
    order_key = order_key or (lambda p: p)
    chosen = [r for r in export.rows if who is None or r["participant"] in who]
    chosen.sort(key=lambda r: order_key(r["participant"]))  # stable: file order within a participant
    section = {"game": game, "resamples": RESAMPLES, "seed": SEED, "paired_resamples": PAIRED_RESAMPLES,
               "rows": [], "procedures": [], "comparisons": [], "notes": list(export.notes), "figures": {}}
    for row in chosen:
        section["rows"].append(refit(row, export.trials, section["notes"]))
    # Without thresholds.csv at all, export.notes has said so once.
    unlisted = [key for key in (export.trials or {}) if export.rows and (who is None or key[0] in who)
                and not any((r["participant"], r["session"], r["procedure"]) == key for r in chosen)]
    for participant, session, procedure in unlisted:
        section["notes"].append(f"{TRIALS} has trials of {participant}'s {procedure} (session {session}) that "
                                f"{THRESHOLDS} has no row for: without the row's function they are not fitted.")
    procedures = {}
    for row in export.rows:  # file order: the order the procedures are listed and compared in
        entry = procedures.setdefault(row["procedure"], {"procedure": row["procedure"], "method": row["method"],
                                                         "dimension": row["dimension"], "units": row["units"],
                                                         "percent_correct": []})
        if row["percent_correct"] not in entry["percent_correct"]:
            entry["percent_correct"].append(row["percent_correct"])
    section["procedures"] = [p for p in procedures.values() if any(r["procedure"] == p["procedure"] for r in chosen)]
    beyond_the_levels(section["rows"], section["procedures"], section["notes"])
    section["comparisons"] = compare(section["rows"], section["procedures"], order_key, section["notes"])
    return section


def name_of(row):
    return f"{row['participant']}'s {row['procedure']} (session {row['session']})"


def refit(row, trials, notes):
    """The row as report.json gives it, with its trials' levels and MLE refit (None where it
    cannot be fitted: a note says why)."""
    stimuli, correct = (trials or {}).get((row["participant"], row["session"], row["procedure"]), ([], []))
    out = {k: row[k] for k in ("participant", "session", "procedure", "method", "dimension", "reference", "units",
                               "shape", "scale", "guess", "percent_correct", "fit_lapse", "finished", "trials")}
    out["trials_found"] = len(stimuli)
    out["levels"] = levels(stimuli, correct)
    estimate = ESTIMATES.get(row["method"], "the procedure's own estimate") if row["threshold"] is not None else None
    out["export"] = dict({"estimate": estimate},
                         **{k: row[k] for k in ("threshold", "threshold_low", "threshold_high") + MARGINALS})
    out["export"]["location"] = own_location(row)
    out["mle"] = None
    if trials is None:
        return out
    name = name_of(row)
    if stimuli and len(stimuli) != row["trials"]:
        notes.append(f"{name}: {THRESHOLDS} counts {row['trials']} trials, {TRIALS} has {len(stimuli)}; the refit "
                     "takes those it has.")
    why = unfittable(stimuli, correct, out["levels"])
    if why:
        notes.append(f"{name}: {why}, so no MLE threshold.")
        return out
    function = {k: row[k] for k in ("guess", "shape", "scale")}
    function["lapse"] = row["fit_lapse"]
    try:
        fitted = psychometric.fit(stimuli, correct, **function)
        threshold = psychometric.stimulus_at(row["percent_correct"], fitted["threshold"], fitted["slope"],
                                             **function)
    except (ValueError, np.linalg.LinAlgError) as e:
        notes.append(f"{name}: no MLE threshold ({str(e).rstrip('.')}).")
        return out
    low, high, kept, left_out = psychometric.bootstrap_interval(stimuli, correct, row["percent_correct"],
                                                                resamples=RESAMPLES, seed=SEED, **function)
    unbounded = at_most_one_level_between(out["levels"], fitted, function)
    if unbounded:
        notes.append(f"{name}: its answers are likeliest under an ever steeper function (at the guess rate below "
                     "one level, at 1 - lapse above it, in between only at that level), so its slope has no estimate "
                     "(the fit stops where the likelihood no longer rises) and its MLE threshold is where that step "
                     "lies.")
    if left_out > LEFT_OUT_NOTE_SHARE * RESAMPLES:
        notes.append(f"{name}: {left_out} of {RESAMPLES} bootstrap resamples could not be fitted (their answers "
                     "are likeliest under a step between two levels, or never reach the percent correct), so its "
                     "interval, from the "
                     "others, understates the uncertainty.")
    out["mle"] = {"threshold": threshold, "bootstrap_low": low, "bootstrap_high": high, "resamples_fitted": kept,
                  "resamples_left_out": left_out, "slope": fitted["slope"], "slope_unbounded": unbounded,
                  "lapse": row["fit_lapse"],
                  "location": fitted["threshold"], "log_likelihood": fitted["log_likelihood"]}
    return out


def own_location(row):
    """The threshold parameter of the function the procedure's own estimate describes (QUEST+'s:
    its posterior mean threshold at percent_correct, slope and lapse), or None where the row has no
    threshold or no slope. A summary, not the posterior's mean function: the marginal means of
    slope and lapse with the threshold at percent_correct; what the figure draws where the trials
    give no fit."""
    if row["threshold"] is None or row["slope"] is None:
        return None
    lapse = row["lapse"] if row["lapse"] is not None else row["fit_lapse"]
    try:
        return psychometric.location_at(row["percent_correct"], row["threshold"], row["slope"], lapse, row["guess"],
                                        row["shape"], row["scale"])
    except (ValueError, ZeroDivisionError):  # a lapse that never lets it reach percent_correct, a slope of 0
        return None


def beyond_the_levels(rows, procedures, notes):
    """A note per procedure and side naming the sessions whose own threshold lies beyond every level
    they presented: QUEST+'s posterior mean can sit there (it integrates over its whole grid), but
    then it rests on the prior and the grid's end more than on the trials."""
    for procedure in procedures:
        theirs = [r for r in rows if r["procedure"] == procedure["procedure"] and r["levels"]
                  and r["export"]["threshold"] is not None]
        sessions = {}
        for row in theirs:
            sessions[row["participant"]] = sessions.get(row["participant"], 0) + 1
        for side, beyond in (("above", lambda t, tried: t > max(tried)), ("below", lambda t, tried: t < min(tried))):
            whose = [r["participant"] if sessions[r["participant"]] == 1 else name_of(r) for r in theirs
                     if beyond(r["export"]["threshold"], [level["stimulus"] for level in r["levels"]])]
            if not whose:
                continue
            listed = ", ".join(whose)
            notes.append(f"{procedure['procedure']}: in {len(whose)} session{'s' if len(whose) > 1 else ''} "
                         f"({listed}) the procedure's own threshold lies {side} every level presented, so it rests "
                         "on its prior and the end of its grid more than on the trials; the comparisons on own "
                         "estimates take it as it is.")


def levels(stimuli, correct):
    """[{stimulus, n, correct}] per distinct stimulus, ascending: what the figure draws."""
    out = {}
    for x, y in zip(stimuli, correct):
        entry = out.setdefault(x, {"stimulus": x, "n": 0, "correct": 0})
        entry["n"] += 1
        entry["correct"] += int(y)
    return [out[x] for x in sorted(out)]


def at_most_one_level_between(by_level, fitted, function):
    """Every level's fitted probability at the guess rate or at 1 - lapse but one's: the likelihood
    then rises without end along a ridge (the location keeping that one level's probability as the
    slope grows), and the fit's slope is only where the rise fell below its tolerance.
    psychometric.fit refuses the ridge's end with no level between, a step."""
    low, high = function["guess"], 1.0 - function["lapse"]
    p = psychometric.probability(np.array([level["stimulus"] for level in by_level]), fitted["threshold"],
                                 fitted["slope"], **function)
    return int(np.sum((p - low > 1e-6) & (high - p > 1e-6))) <= 1


def unfittable(stimuli, correct, by_level):
    """Why the trials cannot give a threshold before any fit is tried, or None."""
    if not stimuli:
        return f"{TRIALS} has none of its trials"
    if len(by_level) < 2:
        return f"all {len(stimuli)} of its trials are at one level ({by_level[0]['stimulus']:g})"
    right = int(sum(correct))
    if right == len(stimuli):
        return (f"every one of its {len(stimuli)} answers is correct, which bounds the threshold from above only "
                "(below the easiest level tried)")
    if right == 0:
        return f"every one of its {len(stimuli)} answers is wrong, below the guess rate at every level"
    return None


# What a comparison takes of each row, in the order the report gives them: the procedure's own
# estimate, which every QUEST+ session has, then the MLE refit, which rests on the trials alone but
# fails where they step between two levels. For each: what a participant has (the notes' words),
# what the comparison is on, and the row's threshold or None.
COMPARED = {
    "procedure": ("the procedure's own estimate", "the procedures' own estimates",
                  lambda row: row["export"]["threshold"]),
    "mle": ("an MLE threshold", "the MLE thresholds",
            lambda row: row["mle"]["threshold"] if row["mle"] is not None else None),
}
# Below this many non-zero differences the exact signed-rank test cannot reach p < 0.05 (its least
# two-sided p is 2 / 2^n, every difference of one sign): a note says so beside a t-test that can.
WILCOXON_LEAST_N = 6


def compare(rows, procedures, order_key, notes):
    """Every two procedures of one dimension, in the procedures' order, once on each procedure's own
    estimate (where both make one) and once on the MLE thresholds, each over the participants with
    that threshold in both (each participant's mean over their sessions). Own-estimate comparisons
    first, then the MLE's; each has `estimate`, the key of COMPARED it takes."""
    sessions = {}  # (procedure, participant) -> their rows
    for row in rows:
        sessions.setdefault((row["procedure"], row["participant"]), []).append(row)
    for (procedure, participant), theirs in sessions.items():
        if len(theirs) > 1:
            notes.append(f"{participant} has {len(theirs)} sessions of {procedure}: the comparisons take the mean of "
                         "their thresholds, each over the sessions that have one.")
    own = {p["procedure"] for p in procedures
           if any(r["export"]["threshold"] is not None for r in rows if r["procedure"] == p["procedure"])}
    comparisons = {estimate: [] for estimate in COMPARED}
    for i, a in enumerate(procedures):
        for b in procedures[i + 1:]:
            if a["dimension"] != b["dimension"]:
                continue
            where = f"{a['procedure']} against {b['procedure']}"
            for estimate, (what, on, value) in COMPARED.items():
                if estimate == "procedure" and not {a["procedure"], b["procedure"]} <= own:
                    continue  # constant stimuli make no estimate of their own
                comparison = paired_by_participant(sessions, a, b, value, order_key)
                comparisons[estimate].append(dict(estimate=estimate, **comparison))
                if comparison["n"] < 2:
                    both = comparison["pairs"]
                    who = "no participant has" if not both else f"only {both[0]['participant']} has"
                    notes.append(f"{where}: {who} {what} in both, and a paired comparison needs two participants or "
                                 "more.")
                    continue
                m = comparison["positive"] + comparison["negative"]
                if comparison["wilcoxon_method"] == "exact" and m < WILCOXON_LEAST_N:
                    notes.append(f"{where}, on {on}: with {m} non-zero differences the exact Wilcoxon test's "
                                 f"two-sided p is at least 2 / 2^{m} = {2.0 / 2 ** m:.3g}, however large they are; "
                                 "the t-test's is not bounded so.")
            kinds = [ESTIMATES.get(p["method"]) for p in (a, b)]
            if {a["procedure"], b["procedure"]} <= own and kinds[0] != kinds[1]:
                notes.append(f"{where}: their own estimates are of different kinds ({kinds[0] or a['method']} and "
                             f"{kinds[1] or b['method']}), so the difference of those mixes the procedures with the "
                             "estimators; the MLE thresholds are one estimator of both.")
            points = a["percent_correct"] + [p for p in b["percent_correct"] if p not in a["percent_correct"]]
            if len(points) > 1:
                notes.append(f"{where}: their thresholds are defined at different points "
                             f"({', '.join(f'{p:g}' for p in points)} % correct), so the difference mixes the two "
                             "procedures with the two definitions.")
    return [c for estimate in COMPARED for c in comparisons[estimate]]


def paired_by_participant(sessions, a, b, value, order_key):
    """The comparison of procedure a with b on `value` of each row: the participants with a value in
    both, each by the mean of their sessions' values."""
    means = {a["procedure"]: {}, b["procedure"]: {}}
    for (procedure, participant), theirs in sessions.items():
        values = [v for v in map(value, theirs) if v is not None]
        if procedure in means and values:
            means[procedure][participant] = sum(values) / len(values)
    got_a, got_b = means[a["procedure"]], means[b["procedure"]]
    both = sorted(set(got_a) & set(got_b), key=order_key)
    mean_a, mean_b = [got_a[p] for p in both], [got_b[p] for p in both]
    comparison = {"dimension": a["dimension"], "units": a["units"], "a": a["procedure"], "b": b["procedure"],
                  "pairs": [{"participant": p, "a": x, "b": y, "difference": x - y}
                            for p, x, y in zip(both, mean_a, mean_b)]}
    comparison.update(paired(mean_a, mean_b))
    return comparison


def paired(a, b):
    """Mean of d = a - b with its 95 % t interval and seeded bootstrap interval (over participants),
    and stats.paired_tests' tests; every statistic None below two pairs."""
    n = len(a)
    keys = ("mean_diff", "sd", "t_low", "t_high", "bootstrap_low", "bootstrap_high", "t", "df", "p_t", "p_wilcoxon",
            "wilcoxon_method", "positive", "negative", "ties", "p_sign")
    out = dict.fromkeys(keys)
    out["n"] = n
    if n < 2:
        return out
    d = np.asarray(a, dtype=float) - np.asarray(b, dtype=float)
    tests = stats.paired_tests(a, b)
    out.update({k: tests[k] for k in ("mean_diff", "t", "df", "p_t", "p_wilcoxon", "wilcoxon_method", "positive",
                                      "negative", "ties", "p_sign")})
    sd = float(np.std(d, ddof=1))
    half = float(scipy.stats.t.ppf(0.975, n - 1)) * sd / math.sqrt(n)
    means = d[np.random.default_rng(SEED).integers(0, n, size=(PAIRED_RESAMPLES, n))].mean(axis=1)
    low, high = np.percentile(means, [2.5, 97.5])
    out.update(sd=sd, t_low=out["mean_diff"] - half, t_high=out["mean_diff"] + half, bootstrap_low=float(low),
               bootstrap_high=float(high))
    return out
