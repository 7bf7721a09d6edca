"""report.md from the results analyze.py also writes to report.json, so the two cannot disagree.

First the trial-level mixed models R fitted (mixed_report.py), then each paper's own analysis,
replicated and labelled so. Shooter (and any other game): the thesis's layout (seed 004 §6–§7):
Table 1 hits and rates per participant, the hit-rate figure, sign tests for every pair of
conditions, Table 2 differences of each upconverting condition, Table 3 quartiles, histograms,
then a planning table (participants a study would need, this data as pilot). A game whose
sessions played matches (matches.csv; the click game): the layout of Yang et al.'s Table 2 (seed
000 §8) first, then the same hit-rate sections on what its hits and shots count (games.csv: green
hits / clicks). Each condition is described as the export's condition table (conditions.csv, or
modes.csv before it) describes it: its words and, in a section of their own, its parts and
latencies. Rates have 3 decimals, means and SDs 2, p values 4 significant digits (report.json has
them all).
"""
import math
import statistics

from . import mixed_report, papers, planning, players, power
from .conditions import ConditionTable
from .markdown import NOTHING, cell, fmt, table


def title(game):
    return game[:1].upper() + game[1:]


def hit_rate_sections(out, game, summary, tests, level):
    """Tables 1–3 (numbered as the thesis's, labelled with the game), sign tests and figures."""
    h = "#" * level
    participants, conditions, rates = summary["participants"], summary["conditions"], summary["hit_rates"]
    out.append(f"{h} Table 1 ({cell(game)}): hits and hit rates per participant\n")
    shots = {rates[p][c]["shots"] for p in participants for c in conditions if c in rates[p]}
    uniform = len(shots) == 1
    header = (["participant"] + [f"{c} hits" for c in conditions]
              + ([] if uniform else [f"{c} shots" for c in conditions]))
    header += [f"{c} rate" for c in conditions]
    rows = []
    for p in participants:
        row = [cell(p)] + [str(rates[p][c]["hits"]) if c in rates[p] else NOTHING for c in conditions]
        if not uniform:
            row += [str(rates[p][c]["shots"]) if c in rates[p] else NOTHING for c in conditions]
        row += [fmt(rates[p][c]["hit_rate"], ".3f") if c in rates[p] else NOTHING for c in conditions]
        rows.append(row)
    what = f"{summary['hits_are']} out of {summary['shots_are']}"
    out.append(f"{len(participants)} participants, {len(conditions)} conditions; rate = {what}"
               + (f", {shots.pop()} per participant and condition" if uniform else "") + "."
               + (" A dash: the participant has no data in that condition." if any(
                   c not in rates[p] for p in participants for c in conditions) else "") + "\n")
    out.append(table(header, rows))
    if "hit_rates" in summary["figures"]:
        out.append(f"![{cell(game)}: hit rate per participant and condition]({summary['figures']['hit_rates']})\n")
    for note in summary["notes"]:
        out.append(f"{note}\n")
    if not tests:
        return
    out.append(f"{h} Sign tests between every two conditions\n")
    out.append("Per participant with both conditions, d = rate(a) − rate(b). A tie (equal rates, decided on the "
               "integer counts) is dropped from n. With X ~ Binomial(n, ½): p(a > b) = P(X ≥ +) tests "
               "whether a beats b, p(a < b) = P(X ≤ +) whether b beats a; two-sided is scipy's binomtest. "
               "Exact, as R's binom.test (seed 004 §7.1).\n")
    rows = [[t["a"], t["b"], str(t["participants"]), str(t["n"]), str(t["positive"]), str(t["negative"]),
             str(t["ties"]), fmt(t["p_greater"], ".4g"), fmt(t["p_less"], ".4g"), fmt(t["p_two_sided"], ".4g")]
            for t in tests]
    out.append(table(["a", "b", "paired", "n", "+", "−", "ties", "p(a > b)", "p(a < b)", "p two-sided"], rows))
    for t in tests:
        if t["n"] == 0:
            why = "no participant has both conditions" if t["participants"] == 0 else "every pair is tied"
            out.append(f"{t['a']} against {t['b']}: no untied pairs remain ({why}), so n = 0 and every p is 1.\n")
    for k, upconversion in enumerate(summary["upconversion_differences"]):
        condition, against, sort_by = upconversion["condition"], upconversion["against"], upconversion["sorted_by"]
        suffix = "abcdefgh"[k % 8] if len(summary["upconversion_differences"]) > 1 else ""
        out.append(f"{h} Table 2{suffix} ({cell(game)}): {condition} hit rate minus each other condition's\n")
        if not upconversion["rows"]:
            out.append(f"No participant has {condition} and another condition.\n")
            continue
        out.append(f"Sorted by the difference to {sort_by}. Positive: {condition} hit more.\n")
        rows = [[cell(r["participant"])] + [fmt(r["differences"].get(o), ".3f") for o in against]
                for r in upconversion["rows"]]
        out.append(table(["participant"] + [f"{condition} − {o}" for o in against], rows))
    out.append(f"{h} Table 3 ({cell(game)}): quartiles of the differences\n")
    out.append("Of every paired participant's d = rate(a) − rate(b), ties included; R's default quantiles "
               "(type 7), as seed 004 Table 3.\n")
    rows = []
    for t in tests:
        q = t["diff_quartiles"] or {}
        rows.append([f"{t['a']} − {t['b']}"] + [fmt(q.get(k), ".3f") for k in ("min", "q25", "median", "q75",
                                                                                   "max")])
    out.append(table(["difference", "min", "25 %", "median", "75 %", "max"], rows))
    if "differences" in summary["figures"]:
        out.append(f"![{cell(game)}: histograms of upconversion hit-rate differences]"
                   f"({summary['figures']['differences']})\n")
    planning_section(out, game, tests, h)


def planning_section(out, game, tests, h):
    """Participants a new study needs per pair, this data as its pilot (planning.sample_size)."""
    first = tests[0]["planning"]
    alpha, target, cap = first["alpha"], first["target_power"], first["cap"]
    fewest = planning.fewest_untied(cap, alpha)
    out.append(f"{h} Planning ({cell(game)}): participants for {target * 100:g} % power\n")
    out.append(
        "How many participants a new study would need for the two-sided exact sign test above "
        f"(α = {alpha:g}, ties dropped) to find each difference with power {target:g}, taking this data as its "
        "pilot. Assumptions: participants are independent; each one's difference is tied with probability t "
        "(the pilot's tie share) and otherwise positive, a > b, with probability p+ (the pilot's share among "
        "untied participants); and those two pilot shares are the true ones. They are only estimates, the "
        "more uncertain the fewer the pilot's participants (19 of 20 also fits a true p+ of 0.8), and a true p+ "
        "nearer ½ needs more participants: each number is what the pilot's shares imply, not a guarantee. "
        "Computed exactly: with M ~ Binomial(n, 1 − t) untied participants and X ~ Binomial(M, p+) of them "
        "positive, power(n) = Σ_m P(M = m) · P(the test rejects at X | M = m), rejecting where the table's "
        f"two-sided p ≤ {alpha:g}. Exact power saw-tooths: one more participant can lower it. Needed is the "
        f"smallest n with power ≥ {target:g} at n and at every larger n up to {cap} (power: at that n); "
        f"first ≥ {target:g} is the smallest n with power ≥ {target:g}, which a larger n can fall below again.\n")
    rows = []
    for t in tests:
        p = t["planning"]
        rows.append([t["a"], t["b"], str(p["pilot_participants"]), fmt(p["p_plus"], ".3f"), fmt(p["tie_share"], ".3f"),
                     str(p["needed"]) if p["needed"] is not None else cell(p["note"]), fmt(p["power_at_needed"], ".3f"),
                     fmt(p["first"], "d")])
    out.append(table(["a", "b", "pilot n", "p+ (a > b)", "tie share", "needed", "power", f"first ≥ {target:g}"],
                     rows))
    extreme = [f"{t['a']} against {t['b']}" for t in tests if t["planning"]["extreme"]]
    if extreme:
        out.append(f"An extreme estimate, used as is: every untied pilot participant went one way (p+ = 0 or 1) in "
                   f"{'; '.join(extreme)}. Any {fewest} untied participants then reject (2 · 0.5^{fewest} = "
                   f"{2 * 0.5 ** fewest:g} < {alpha:g}), so the number needed there is the fewest any difference "
                   "could need at that tie share, and optimistic: a true p+ just short of 0 or 1 needs more.\n")


def matches_sections(out, matches, level):
    """The matches' tables (analyze.analyse_matches), as Yang et al.'s Table 2 lays them out."""
    h = "#" * level
    for note in matches["notes"]:
        out.append(f"{note}\n")
    if not matches["conditions"]:
        return
    ref = matches["reference_condition"]
    others = [c for c in matches["conditions"] if c != ref]
    out.append(f"{matches['scored_matches']} scored matches from {len(matches['participants'])} participants "
               f"(matches.csv, scored_phase = true). Reference condition: {ref}.\n")
    out.append(f"{h} Table: results per condition\n")
    out.append("Each participant's measures are averaged over their matches in a condition; M and SD (n − 1) are "
               f"across participants. p: paired t-test of the condition against {ref} over the participants with "
               "both. That is the simple contrast Yang et al. report: F(1, n − 1) = t², same p.\n")
    header = ["Measure", f"{ref} M", f"{ref} SD"]
    for c in others:
        header += [f"{c} M", f"{c} SD", f"{c} p"]
    rows = []
    for measure in matches["measures"].values():
        entry = measure["conditions"][ref]
        row = [cell(measure["label"]), fmt(entry["mean"], ".2f"), fmt(entry["sd"], ".2f")]
        for c in others:
            e = measure["conditions"][c]
            row += [fmt(e["mean"], ".2f"), fmt(e["sd"], ".2f"), fmt(e["vs_reference"]["p_t"], ".4g")]
        rows.append(row)
    out.append(table(header, rows))
    if matches["figure"]:
        whose = f"{matches['game']} game" if matches["game"] else "matches"
        out.append(f"![{cell(whose)}: mean ± SD per condition]({matches['figure']})\n")
    if others:
        out.append(f"{h} Paired tests against {ref}\n")
        out.append(f"Difference = condition − {ref} per participant. t: paired t-test (df = n − 1; "
                   "F(1, n − 1) = t²). "
                   "Wilcoxon: signed-rank, two-sided, zero differences dropped (p = 1 when all are zero), tied "
                   "|differences| given their mid-rank; p exact (the conditional distribution of the statistic given "
                   "those ranks) for up to 200 non-zero differences, else the normal approximation with tie-corrected "
                   "variance and continuity correction; the cell says which. Sign test: exact, two-sided, ties "
                   "dropped.\n")
        rows = []
        for measure in matches["measures"].values():
            for c in others:
                v = measure["conditions"][c]["vs_reference"]
                t = v["t"]
                f_value = t * t if t is not None and math.isfinite(t) else None
                rows.append([cell(measure["label"]), c, str(v["n"]), fmt(v["mean_diff"], ".3f"), fmt(t, ".3f"),
                             fmt(f_value, ".3f"), fmt(v["p_t"], ".4g"),
                             f"{fmt(v['p_wilcoxon'], '.4g')} ({v.get('wilcoxon_method', 'exact')})",
                             f"{v['positive']}/{v['negative']}/{v['ties']}", fmt(v["p_sign"], ".4g")])
        out.append(table(["Measure", "condition", "n", "mean diff", "t", "F(1, n − 1)", "p (t)", "p (Wilcoxon)",
                          "+/−/ties", "p (sign)"], rows))
    out.append(f"{h} Repeated-measures ANOVA over conditions\n")
    if not matches["anova_available"]:
        out.append("Left out: statsmodels is not installed (Debian: python3-statsmodels).\n")
        return
    out.append("statsmodels' AnovaRM, one within factor (condition), on the per-participant averages. A "
               "participant lacking a condition (or every rating of a statement in a condition) is dropped from that "
               "measure's ANOVA.\n")
    rows = []
    for measure in matches["measures"].values():
        a = measure["anova"]
        df = NOTHING if a["df_num"] is None else f"{a['df_num']:g}, {a['df_den']:g}"
        rows.append([cell(measure["label"]), fmt(a["F"], ".3f"), df, fmt(a["p"], ".4g"), str(a["participants"]),
                     str(a["dropped"])])
    out.append(table(["Measure", "F", "df", "p", "participants", "dropped"], rows))


def ms(value):
    return fmt(value, ".2f")


def hz(value):
    return fmt(value, "g")


def conditions_section(out, results):
    """One row per condition, display refresh and game the data has: what the condition's name
    stands for, so a reader sees the latencies the conditions compare without the protocol file.
    Columns the table has nothing for (modes.csv has no refresh, game or latencies) are left out."""
    rows_of = {}
    for record in results["conditions"]:
        rows_of.setdefault(record["condition"], []).append(record)
    listed = [c for c in results["condition_order"] if c in rows_of]
    if not listed:
        return
    source = results["conditions_file"]
    out.append("## Conditions\n")
    if source == "modes.csv":
        words = ("What each condition is, as modes.csv gives it (an export from before conditions.csv, which says no "
                 "display refresh, game or latencies).")
    else:
        words = (f"What each condition is, as {source} gives it: one row per display refresh and game it ran at. Added "
                 "lag = lag frames × 1000 / refresh. Latency, min–max over where in the render cycle a step falls: "
                 "view, a mouse step to the screen; scene, a change of the world's motion to the screen.")
    out.append(words + " A condition upconverts when its fill is not hold or it late-warps.\n")
    columns = [("condition", lambda r: cell(r["condition"])),
               ("refresh (Hz)", lambda r: None if r["refresh_hz"] is None else hz(r["refresh_hz"])),
               ("game", lambda r: None if r["game"] is None else cell(r["game"])),
               ("render (Hz)", lambda r: hz(r["render_hz"])),
               ("added lag (ms)", lambda r: ms(r["added_lag_ms"])),
               ("lag frames", lambda r: None if r["lag_frames"] is None else str(r["lag_frames"])),
               ("fill", fill_cell),
               ("late warp", lambda r: cell(r["late_warp"])),
               ("upconverts", lambda r: "yes" if r["upconverts"] else "no")]
    for kind in ("view", "scene"):
        columns.append((f"{kind} latency (ms)", lambda r, kind=kind: None if r[f"{kind}_latency_min_ms"] is None else
                        f"{ms(r[f'{kind}_latency_min_ms'])}–{ms(r[f'{kind}_latency_max_ms'])}"))
    cells = [[get(r) for _, get in columns] for name in listed for r in rows_of[name]]
    keep = [k for k in range(len(columns)) if any(row[k] is not None for row in cells)]
    out.append(table([columns[k][0] for k in keep],
                     [[NOTHING if row[k] is None else row[k] for k in keep] for row in cells]))


def fill_cell(record):
    """What fills the frames between renders, at how many frames a second where it makes any."""
    if record["fill"] is None:
        return NOTHING
    if record["fill_hz"] is None or record["fill"] == "hold":
        return cell(record["fill"])
    return f"{cell(record['fill'])}, {hz(record['fill_hz'])} Hz"


def render(results):
    out = ["# warplab study report\n"]
    files = ", ".join(name + " (" + ", ".join(f"{v} {k.replace('_', ' ')}" for k, v in info.items()) + ")"
                      for name, info in results["inputs"].items())
    out.append(f"From `{results['export_dir']}`: {files}.\n")
    players_lines(out, results)
    sessions = results["sessions"]
    if sessions:
        by_game = sessions.get("by_game", {})
        detail = "; ".join(f"{g or '(no game)'}: {c['included']} of {c['listed']}" for g, c in by_game.items())
        out.append(f"Sessions (sessions.csv): {sessions['included']} of {sessions['listed']} included"
                   + (f" ({detail})" if detail else "") + ".\n")
    described = ConditionTable(results["conditions"])
    out.append("Conditions: " + "; ".join(f"{c} ({cell(described.description(c))})" if described.description(c) else c
                                          for c in results["condition_order"]) + ".\n")
    for note in results["notes"]:
        out.append(f"{note}\n")
    mixed_report.section(out, results)
    if results.get("power") is not None:
        out.extend(power.power_markdown(results["power"]))
    conditions_section(out, results)
    game_sections(out, results, results)
    questions_section(out, results["questions"])
    for part in results.get("player_groups", []):
        label = players.GROUP_LABELS[part["group"]]
        out.append(f"# {cell(label[:1].upper() + label[1:])}, on their own: {cell(', '.join(part['participants']))}\n")
        out.append("The same analysis of these participants alone: none of them is in the statistics above, nor any "
                   "of those above in these.\n")
        game_sections(out, results, part)
        questions_section(out, part["questions"])
    return "\n".join(out)


def players_lines(out, results):
    """Who played, and whose statistics follow: the report's first words after its sources."""
    who = results["players"]
    if who["sentence"]:
        out.append(f"**{cell(who['sentence'])}**\n")
    groups = who["groups"]
    if who["kinds"] is None or len(groups) <= 1:
        return
    if who["pooled"]:
        out.append("People and scripted players are **pooled** (--pool-players): every statistic below counts them "
                   "together.\n")
        return
    analysed = who["analysed"]
    others = [players.GROUP_LABELS[g] for g in groups if g != analysed]
    out.append(f"The statistics below are of the **{cell(players.GROUP_LABELS[analysed])} only** "
               f"({cell(', '.join(groups[analysed]))}); the {cell(' and the '.join(others))} follow, each on their "
               "own, at the end (--pool-players analyses everyone together).\n")


def game_sections(out, results, part):
    """One group's hit-rate and match sections (analyze.analyse_part)."""
    for note in part.get("group_notes", []):
        out.append(f"{note}\n")
    tests_by_game = {}
    for test in part["sign_tests"]:
        tests_by_game.setdefault(test["game"], []).append(test)
    # The matches' sections go with the game whose sessions played them; when sessions.csv does not
    # say which game that is, they stand on their own after the games.
    matches = part["matches"]
    match_game = matches["game"] if matches is not None else None
    games = list(part["games"])
    if matches is not None and match_game not in games:
        games.append(match_game)
    # The discrimination thresholds go with their game too; that game has no shots, so it is one
    # of the games with hit rates only in an export that gives it some.
    section = part.get("discrimination")
    for game in games:
        summary = part["games"].get(game)
        if section is not None and game == section["game"]:
            discrimination_section(out, section, 2)
            section = None
        if matches is not None and game == match_game:
            heading = f"{title(game)} game" if game else "Matches"
            out.append(f"## {cell(heading)}: the paper's own analysis, replicated (Yang et al. 2011, seed 000 §8)\n")
            matches_sections(out, matches, 3)
            if shares(matches["conditions"], papers.YANG_CONDITIONS, papers.YANG_BEST):
                yang_section(out, results, matches, 3)
            if summary:
                out.append(f"### Hit rates: {cell(summary['hits_are'])} / {cell(summary['shots_are'])}\n")
                hit_rate_sections(out, game, summary, tests_by_game.get(game, []), 4)
        else:
            out.append(f"## {cell(title(game))}: hit rates, the paper's own analysis, replicated (Pulkkinen 2014, "
                       "seed 004 §6–§7)\n")
            hit_rate_sections(out, game, summary, tests_by_game.get(game, []), 3)
            if shares(summary["conditions"], papers.THESIS_CONDITIONS, papers.THESIS_BEST):
                thesis_section(out, results, game, summary, 3)
    if section is not None:
        discrimination_section(out, section, 2)


METHODS = {"quest_plus": "QUEST+", "staircase": "staircase", "constant_stimuli": "constant stimuli"}
# The column of a procedure's own estimate, by method; constant stimuli have none.
ESTIMATE_HEADERS = {"quest_plus": "QUEST+ posterior mean [95 % credible]",
                    "staircase": "staircase: mean of the last reversals"}


def number(value):
    return fmt(value, ".3g")


def interval(value, low, high):
    """"3.1 [2.5, 3.8]", the value alone without its interval, a dash without the value."""
    if value is None:
        return NOTHING
    if low is None or high is None or not (math.isfinite(low) and math.isfinite(high)):
        return number(value)
    return f"{number(value)} [{number(low)}, {number(high)}]"


def discrimination_section(out, section, level):
    """The discrimination thresholds (discrimination.analyse): a table per procedure, the paired
    comparisons, the figures and the notes."""
    h = "#" * level
    game = section["game"]
    out.append(f"{h} Discrimination thresholds" + (f" ({cell(game)} game)" if game and game != "discrimination"
                                                    else "") + "\n")
    out.append("Each session's trials of a procedure (discrimination_trials.csv) refitted by maximum likelihood with "
               "the function thresholds.csv gives the procedure (shape, scale, guess rate) and its lapse rate held at "
               "the row's fit\\_lapse (Wichmann and Hill 2001). The MLE threshold is the stimulus at the procedure's "
               "percent correct, with the 95 % percentile interval of "
               f"{section['resamples']} bootstrap resamples of the trials (seed {section['seed']}; a resample that "
               "cannot be fitted is left out). Beside it, the procedure's own estimate: QUEST+'s posterior mean with "
               "its 95 % credible interval (Watson 2017), a staircase's mean of its last reversals (Levitt 1971). "
               "Thresholds are differences from the reference, in the dimension's units. Slopes are per unit of "
               "the function's scale (the log of the stimulus on the log scale).\n")
    for procedure in section["procedures"]:
        procedure_table(out, procedure, [r for r in section["rows"] if r["procedure"] == procedure["procedure"]],
                        level + 1)
    comparisons_table(out, section, level + 1)
    for dimension, name in section["figures"].items():
        out.append(f"![{cell(dimension)}: each participant's psychometric curves]({name})\n")
    if section["notes"]:
        out.append("Notes:\n\n" + "\n".join(f"- {cell(note)}" for note in section["notes"]) + "\n")


def procedure_table(out, procedure, rows, level):
    """One procedure's rows: the export's estimate (where its method makes one) beside the refit."""
    method = procedure["method"]
    points = " and ".join(f"{p:g}" for p in procedure["percent_correct"])
    out.append(f"{'#' * level} {cell(procedure['procedure'])}: {cell(procedure['dimension'])} "
               f"({cell(procedure['units'])}), {cell(METHODS.get(method, method))}, threshold at {points} % correct\n")
    out.append(f"Reference: {', '.join(dict.fromkeys(cell(r['reference']) for r in rows))}.\n")
    columns = [("participant", lambda r: cell(r["participant"]))]
    if len({r["participant"] for r in rows}) < len(rows):  # a participant with several sessions
        columns.append(("session", lambda r: cell(r["session"])))
    columns.append(("trials", lambda r: str(r["trials_found"])))
    if any(r["export"]["threshold"] is not None for r in rows):
        columns.append((ESTIMATE_HEADERS.get(method, "the procedure's estimate"),
                        lambda r: interval(r["export"]["threshold"], r["export"]["threshold_low"],
                                           r["export"]["threshold_high"])))
    columns.append(("MLE threshold [95 % bootstrap]",
                    lambda r: interval(r["mle"]["threshold"], r["mle"]["bootstrap_low"], r["mle"]["bootstrap_high"])))
    if any(r["mle"] and r["mle"]["resamples_left_out"] for r in rows):
        columns.append(("resamples fitted", lambda r: f"{r['mle']['resamples_fitted']} of "
                        f"{r['mle']['resamples_fitted'] + r['mle']['resamples_left_out']}"))
    columns.append(("MLE slope", lambda r: "unbounded" if r["mle"]["slope_unbounded"] else number(r["mle"]["slope"])))
    columns.append(("lapse held", lambda r: number(r["fit_lapse"])))
    if method == "quest_plus":
        for part in ("slope", "lapse"):
            columns.append((f"QUEST+ {part} [95 %]", lambda r, part=part: interval(
                r["export"][part], r["export"][f"{part}_low"], r["export"][f"{part}_high"])))
    needs_fit = {"MLE threshold [95 % bootstrap]", "resamples fitted", "MLE slope"}
    cells = [[NOTHING if name in needs_fit and r["mle"] is None else get(r) for name, get in columns] for r in rows]
    out.append(table([name for name, _ in columns], cells))


# The comparisons' tables, in report.json's order (discrimination.COMPARED): heading, and the
# sentence where a dimension's procedures give nothing to compare on it.
COMPARISON_TABLES = {
    "procedure": ("On the procedures' own estimates", "No two procedures of one dimension both make an estimate of "
                  "their own (constant stimuli make none): nothing to compare on them."),
    "mle": ("On the MLE thresholds", None),
}


def comparisons_table(out, section, level):
    if not section["procedures"]:
        return  # nothing was fitted: the notes say why
    out.append(f"{'#' * level} Paired comparisons of thresholds\n")
    comparisons = section["comparisons"]
    if not comparisons:
        out.append("No two procedures vary the same dimension: nothing to compare.\n")
        return
    out.append("Every two procedures of one dimension, compared twice. First on each procedure's own estimate "
               "(thresholds.csv's threshold: QUEST+'s posterior mean, a staircase's mean of its last reversals; "
               "constant stimuli make none): QUEST+'s exists for every session, however its answers fall, but rests "
               "on the procedure's prior and grids as well as on the trials. Then on the MLE thresholds: one "
               "estimator for every procedure, from the trials alone, but none where the likelihood keeps rising "
               "towards a step between two levels, as it often does when QUEST+ places a short session's trials "
               "close to the threshold. Each over the participants with that threshold in both: d = threshold(a) "
               "− threshold(b), a participant with several sessions of a procedure counted once, by the mean of "
               "their thresholds. The mean of d with its 95 % t interval and the 95 % percentile interval of "
               f"{section['paired_resamples']} bootstrap resamples of the participants (seed {section['seed']}); the "
               "paired t-test and the Wilcoxon signed-rank test (exact, mid-ranks for tied |d|), two-sided.\n")
    for estimate, (heading, none) in COMPARISON_TABLES.items():
        chosen = [c for c in comparisons if c["estimate"] == estimate]
        out.append(f"{'#' * (level + 1)} {heading}\n")
        if not chosen:
            out.append(f"{none}\n")
            continue
        rows = []
        for c in chosen:
            rows.append([cell(c["dimension"]), f"{cell(c['a'])} − {cell(c['b'])}", str(c["n"]),
                         f"{number(c['mean_diff'])} {cell(c['units'])}" if c["mean_diff"] is not None else NOTHING,
                         interval(c["mean_diff"], c["t_low"], c["t_high"]).partition(" ")[2] or NOTHING,
                         interval(c["mean_diff"], c["bootstrap_low"], c["bootstrap_high"]).partition(" ")[2]
                         or NOTHING,
                         fmt(c["t"], ".3f") + (f" ({c['df']})" if c["df"] is not None else ""),
                         fmt(c["p_t"], ".4g"), fmt(c["p_wilcoxon"], ".4g")])
        out.append(table(["dimension", "a − b", "n", "mean d", "95 % t interval", "95 % bootstrap", "t (df)", "p (t)",
                          "p (Wilcoxon)"], rows))


def condition_name(condition):
    return "(the whole test: its conditions interleaved)" if condition == "" else cell(condition)


def questions_section(out, summaries):
    """Every question asked after blocks (answers.csv), per condition (questions.summarise)."""
    if not summaries:
        return
    out.append("## Questions after blocks (answers.csv)\n")
    out.append("Per question and condition, over every answer given in the scored blocks (a participant who "
               "answered twice in a condition counts twice). Likert: n, median, the 25 % and 75 % quantiles and their "
               "difference, the IQR, by R's default quantiles (type 7); choice: how many chose each option; text: "
               "every answer, by participant and block (block_index, 0-based).\n")
    for q in summaries:
        name = f"{q['question_id']}: " if q["question_id"] else ""
        out.append(f"### Question {q['question'] + 1} ({q['kind']}): {cell(name + q['prompt'])}\n")
        if q["kind"] == "likert":
            rows = [[condition_name(c), str(e["n"]), fmt(e["median"], "g"), fmt(e["q25"], "g"), fmt(e["q75"], "g"),
                     fmt(e["iqr"], "g")] for c, e in q["by_condition"].items()]
            out.append(table(["condition", "n", "median", "25 %", "75 %", "IQR"], rows))
        elif q["kind"] == "choice":
            rows = [[condition_name(c), str(e["n"]), "; ".join(f"{c['option']}. {cell(c['text'])}: {c['count']}"
                                                           for c in e["counts"])]
                    for c, e in q["by_condition"].items()]
            out.append(table(["condition", "n", "chosen (option: times)"], rows))
        else:
            rows = [[condition_name(c), cell(a["participant"]), NOTHING if a["block"] is None else str(a["block"]),
                     cell(a["text"]) if a["text"] else NOTHING]
                    for c, e in q["by_condition"].items() for a in e["answers"]]
            out.append(table(["condition", "participant", "block", "answer"], rows))


def mean_sd(values):
    values = [v for v in values if v is not None and math.isfinite(v)]
    if not values:
        return None, None
    return statistics.mean(values), statistics.stdev(values) if len(values) > 1 else None


def shares(conditions, paper_conditions, best):
    """The study played the paper's best condition and another of the paper's: there is something to
    compare."""
    return best in conditions and len(set(conditions) & set(paper_conditions)) > 1


def who_played(results):
    """What a comparison with the papers says of this study's participants (sessions.csv's player)."""
    players = results["sessions"].get("players", {}) if isinstance(results["sessions"], dict) else {}
    if players and set(players) == {"sim"}:
        who = ("This study's participants are **simulated** (warplab's perceptual model, "
               "docs/simulated-participant.md), not people: their figures show what the model does, the paper's "
               "what people did.")
    elif players:
        who = "This study's sessions (" + ", ".join(f"{k}: {n}" for k, n in sorted(players.items())) + ")."
    else:
        who = "sessions.csv does not say who played."
    return who + (" Relative: the condition's mean over the best condition's, the measure the studies' own "
                  "comparisons rest on, since difficulty and skill set the absolute level.\n")


def thesis_section(out, results, game, summary, level):
    """The shooter beside the thesis's people (Table 1), for the conditions both have."""
    rates = summary["hit_rates"]
    thesis = papers.thesis_hit_rates()
    conditions = [c for c in papers.THESIS_CONDITIONS if c in summary["conditions"]]
    ours = {c: mean_sd([rates[p][c]["hit_rate"] for p in summary["participants"] if c in rates[p]])
            for c in conditions}
    best, best_paper = ours[papers.THESIS_BEST][0], thesis[papers.THESIS_BEST][0]
    out.append(f"{'#' * level} Beside the papers' people: the thesis's Table 1 (seed 004, 20 people, "
               f"{papers.THESIS_TARGETS} targets per condition)\n")
    out.append(who_played(results))
    rows = []
    for c in conditions:
        mean, sd = ours[c]
        relative = mean / best if mean is not None and best else None
        rows.append([c, fmt(mean, ".3f"), fmt(sd, ".3f"), fmt(relative, ".2f"), fmt(thesis[c][0], ".3f"),
                     fmt(thesis[c][1], ".3f"), fmt(thesis[c][0] / best_paper, ".2f")])
    out.append(table(["condition", "hit rate M", "SD", "relative", "thesis M", "thesis SD", "thesis relative"], rows))


def yang_section(out, results, matches, level):
    """The matches beside Yang et al.'s people (Table 2), for the conditions and measures both have."""
    ref = papers.YANG_BEST
    out.append(f"{'#' * level} Beside the papers' people: Yang et al.'s Table 2 (seed 000 §8, 33 people, two 45 s "
               "matches per condition)\n")
    out.append(who_played(results))
    out.append("Counts are per match, so their absolute size follows the match length: compare the relative "
               "columns. Ratings on 1..7 compare as they are.\n")
    rows = []
    for key, measure in matches["measures"].items():
        paper_key = key if key in papers.YANG_TABLE2 else papers.yang_rating_key(measure["label"])
        if paper_key is None:
            continue
        paper = papers.YANG_TABLE2[paper_key]
        counts = paper_key in ("green_hits", "red_hits", "misses")
        ref_mean = measure["conditions"][ref]["mean"]
        for c in [c for c in papers.YANG_CONDITIONS if c in matches["conditions"]]:
            e = measure["conditions"][c]
            relative = e["mean"] / ref_mean if counts and e["mean"] is not None and ref_mean else None
            rows.append([cell(measure["label"]), c, fmt(e["mean"], ".2f"), fmt(e["sd"], ".2f"),
                         fmt(relative, ".2f") if counts else NOTHING, fmt(paper[c][0], ".2f"),
                         fmt(paper[c][1], ".2f"), fmt(paper[c][0] / paper[ref][0], ".2f") if counts else NOTHING])
    out.append(table(["measure", "condition", "M", "SD", "relative", "Yang M", "Yang SD", "Yang relative"], rows))
