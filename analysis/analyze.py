#!/usr/bin/python3
"""Statistics for a warplab study: from the CSVs `warplab export` writes to report.md, report.json
and PNG figures.

Usage: analysis/analyze EXPORT_DIR --out REPORT_DIR [--reference-condition NAME] [--rating-scale MIN:MAX]
       [--pool-players] [--rscript PATH] [--no-mixed-models] [--no-power] [--effect A:B=OR]...
       [--power-pairs reference|all] [--power-replicates N]

First, the trial-level mixed models reviewers expect (hits by binomial GLMMs, counts by Poisson or
negative binomial GLMMs, Likert answers by cumulative-link mixed models), fitted by R from the
script analysis/r/mixed_models.R, which the report keeps beside itself (mixed_models.py), and the
participants a study needs for each condition's contrast with the reference in those models, by
simulation (power.py, analysis/r/power.R). Then each paper's own analysis, replicated, as below.

A condition (the `condition` column of the other files; `mode` in an older export) is one the
export's condition table describes: conditions.csv, or modes.csv in an export from before it
(conditions.ConditionTable).

Hit rates (hitrates.csv, every game): exact paired sign tests between every two conditions of a game,
as Pulkkinen's thesis tests warp upconversion against 15 and 120 Hz rendering (seed 004 §7,
Tables 1–3, Figures 32–34): per participant the difference of hit rates, ties dropped, binomial
tails, and the type-7 quartiles of the differences. Pairs are oriented by the condition order,
taken from the condition table: conditions that upconvert first, so warp15to120 − conv15 is positive
where warping helps. What a game's hits and shots are (green hits out of clicks) is games.csv's.

Matches (matches.csv, scored matches only; the click game's): per participant and condition the
average over their matches of green hits, red hits, misses and each rating, then per condition
mean and SD across participants, each condition against a reference condition (bireproj15to60 by
default; choose_reference says which when the matches lack it) by paired t-test
(the "simple contrast" F(1, n−1) = t² Yang et al. report, seed 000 §8 Table 2), Wilcoxon
signed-rank and sign test, and a repeated-measures ANOVA per measure (statsmodels' AnovaRM,
left out with a note if statsmodels is missing).

Discrimination thresholds (thresholds.csv and discrimination_trials.csv, the discrimination
game's): every session's trials of each procedure refitted by maximum likelihood beside the
procedure's own estimate, and the thresholds of procedures of one stimulus dimension compared
between them, participant by participant (warplab_analysis/discrimination.py). That game has no
shots: an export of it alone has a hitrates.csv without rows.

Bad input (a missing folder or file, an empty file, a missing column, a cell that is not a
count, hits above shots, a game with one participant, a condition the table gives no valid
parts, a rating outside the scale, a statement without its rating_k column) ends in one sentence on stderr naming the file, column and line, and exit status 1.
"""
import argparse
import importlib
import json
import math
import os
import re
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from warplab_analysis import discrimination, inputs, mixed_models, players, power, questions, report, stats  # noqa: E402
from warplab_analysis.conditions import ConditionTable  # noqa: E402
from warplab_analysis.inputs import BadInput  # noqa: E402

# Yang et al.'s reference (seed 000 §8): bidirectional reprojection, the method their study tests.
# An export without it falls back by choose_reference's rule.
DEFAULT_REFERENCE = "bireproj15to60"
MATCH_COUNTS = [("green_hits", "Green hits"), ("red_hits", "Red hits"), ("misses", "Misses")]


def natural_key(participant):
    """p2 before p10; ties broken by the exact string."""
    parts = tuple((0, int(t), "") if t.isdigit() else (1, 0, t.lower()) for t in re.split(r"(\d+)", participant) if t)
    return parts, participant


def order_games(games, described):
    """games.csv's order (the order warplab knows its games in), then any others by name."""
    return [g for g in described if g in games] + sorted(set(games) - set(described))


def file_stem(name, taken):
    stem = re.sub(r"[^A-Za-z0-9_.-]+", "_", name).strip("._") or "game"
    candidate, k = stem, 2
    while candidate in taken:
        candidate, k = f"{stem}_{k}", k + 1
    taken.add(candidate)
    return candidate


def analyse_game(game, participants, table, wording):
    """One game's hit rates: Table 1 data, every pair's sign test, Table 2 per upconverting condition."""
    order = sorted(participants, key=natural_key)
    participants = {p: participants[p] for p in order}
    conditions = table.order({c for row in participants.values() for c in row})
    hit_rates = {p: {c: {"shots": row[c][1], "hits": row[c][0], "hit_rate": row[c][0] / row[c][1]}
                     for c in conditions if c in row}
                 for p, row in participants.items()}
    tests = [stats.hit_rate_sign_test(game, a, b, participants)
             for i, a in enumerate(conditions) for b in conditions[i + 1:]]
    upconversion = []
    for condition in [c for c in conditions if table.upconverts(c)]:
        others = [c for c in conditions if c != condition]
        if not others:
            continue
        conventional = [c for c in others if table.conventional_rate(c) is not None]
        sort_by = min(conventional, key=table.conventional_rate) if conventional else others[0]
        others = [sort_by] + [c for c in others if c != sort_by]  # the thesis's Table 2 leads with it
        rows = []
        for p, row in participants.items():
            differences = {}
            for other in others:
                if condition in row and other in row:
                    differences[other] = stats.rate_difference(row[condition], row[other])[1]
            if differences:
                rows.append({"participant": p, "differences": differences})
        rows.sort(key=lambda r: (sort_by not in r["differences"], r["differences"].get(sort_by, 0.0)))
        upconversion.append({"condition": condition, "against": others, "sorted_by": sort_by, "rows": rows})
    notes = []
    if len(conditions) == 1:
        notes.append(f"Only one condition ({conditions[0]}): no pairs to test.")
    summary = {"participants": order, "conditions": conditions, "hits_are": wording["hits_are"],
               "shots_are": wording["shots_are"], "hit_rates": hit_rates, "upconversion_differences": upconversion,
               "figures": {}, "notes": notes}
    return summary, tests


def choose_reference(requested, conditions, table):
    """(reference, note or None): `requested` when the scored matches have it; else as if none had
    been asked for: bireproj15to60 when there, else the first condition in the condition order
    that upconverts (the method under test, the part bireproj15to60 plays in Yang et al.'s table),
    else the first in the order. A note says which rule chose it whenever it is not the one asked
    for."""
    if requested in conditions:
        return requested, None
    asked = (f"The default reference condition {requested}" if requested == DEFAULT_REFERENCE
             else f"The reference condition {requested}")
    if DEFAULT_REFERENCE in conditions:
        return DEFAULT_REFERENCE, (f"{asked} is not in the scored matches; {DEFAULT_REFERENCE}, the default, is the "
                                   "reference instead.")
    upconverting = [c for c in conditions if table.upconverts(c)]
    if upconverting:
        return upconverting[0], (f"{asked} is not in the scored matches; {upconverting[0]}, the first condition in "
                                 "the condition order that upconverts, is the reference instead.")
    return conditions[0], (f"{asked} is not in the scored matches and no condition there upconverts; "
                           f"{conditions[0]}, the first in the condition order, is the reference instead.")


def analyse_matches(loaded, statements, requested_reference, table, game):
    """The matches' tables; `game` is the game whose sessions hold them (None when sessions.csv does
    not say, or names several)."""
    matches, rating_columns, rows = loaded[:3]
    labels = statements[0] if statements else {}
    measures = MATCH_COUNTS + [(c, labels.get(int(c.split("_")[1]), c)) for c in rating_columns]
    result = {"game": game, "scored_matches": len(matches), "rows": rows, "participants": [], "conditions": [],
              "reference_condition": None, "reference_requested": requested_reference, "anova_available": None,
              "measures": {}, "notes": list(statements[1]) if statements else [], "figure": None}
    if not matches:
        result["notes"].append("matches.csv has no scored matches: nothing to tabulate.")
        return result
    participants = sorted({m["participant"] for m in matches}, key=natural_key)
    conditions = table.order({m["condition"] for m in matches})
    reference, note = choose_reference(requested_reference, conditions, table)
    if note:
        result["notes"].append(note)
    others = [c for c in conditions if c != reference]
    result.update(participants=participants, conditions=conditions, reference_condition=reference)
    try:
        importlib.import_module("statsmodels.stats.anova")
        result["anova_available"] = True
    except ImportError:
        result["anova_available"] = False
        result["notes"].append("statsmodels is not installed (Debian: python3-statsmodels): no repeated-measures "
                              "ANOVA.")
    for index, (key, label) in enumerate(measures):
        cells = {}  # participant -> condition -> the values of their matches
        for m in matches:
            value = m[key] if index < len(MATCH_COUNTS) else m["ratings"][index - len(MATCH_COUNTS)]
            if value is not None:
                cells.setdefault(m["participant"], {}).setdefault(m["condition"], []).append(float(value))
        values = {p: {c: sum(v) / len(v) for c, v in cells.get(p, {}).items()} for p in participants}
        per_condition = {}
        for condition in conditions:
            entry = stats.describe([row[condition] for row in values.values() if condition in row])
            if condition != reference:
                paired = [p for p in participants if condition in values[p] and reference in values[p]]
                entry["vs_reference"] = stats.paired_tests([values[p][condition] for p in paired],
                                                           [values[p][reference] for p in paired])
            else:
                entry["vs_reference"] = None
            per_condition[condition] = entry
        anova = None
        if result["anova_available"]:
            anova = stats.rm_anova(values, conditions)
            for k in ("df_num", "df_den"):
                if anova[k] is not None and float(anova[k]).is_integer():
                    anova[k] = int(anova[k])
        result["measures"][key] = {"label": label, "conditions": per_condition, "anova": anova,
                                   "participant_means": values}
    if not others:
        result["notes"].append(f"Only one condition ({reference}) in the scored matches: nothing to compare.")
    return result


def analyse_part(export_dir, data, who, reference_condition, table):
    """The statistics of the participants `who` (None: everyone): {games, sign_tests, matches,
    discrimination, answers}. A game that has fewer than two of them has no paired tests: a note
    says so."""
    games, described, matches, statements, answers, thresholds = data
    part = {"games": {}, "sign_tests": [], "matches": None, "discrimination": None, "group_notes": [],
            "answers": [a for a in answers or [] if who is None or a["participant"] in who]}
    for game in order_games(games, described):
        chosen = {p: row for p, row in games[game].items() if who is None or p in who}
        if not chosen:
            continue
        if len(chosen) < 2:
            part["group_notes"].append(f"{title_of(game)}: a single participant ({next(iter(chosen))}) here, so no "
                                       "paired tests.")
            continue
        wording = described.get(game, {"hits_are": "hits", "shots_are": "shots"})
        summary, tests = analyse_game(game, chosen, table, wording)
        part["games"][game] = summary
        part["sign_tests"] += tests
    if matches is not None and matches[2]:  # header-only when no session played matches: no matches section then
        chosen = [m for m in matches[0] if who is None or m["participant"] in who]
        if chosen or who is None:
            game = matches_game(export_dir, described, matches[3])
            part["matches"] = analyse_matches((chosen,) + tuple(matches[1:]), statements, reference_condition, table,
                                            game)
    if thresholds is not None and (who is None or thresholds.participants() & who):
        sessions = {row["session"] for row in thresholds.rows}
        game = owning_game(export_dir, described, discrimination.THRESHOLDS, sessions)
        part["discrimination"] = discrimination.analyse(thresholds, who, game, natural_key)
    return part


def matches_game(export_dir, described, sessions):
    """The game whose matches matches.csv holds (owning_game)."""
    return owning_game(export_dir, described, inputs.MATCHES, sessions)


def owning_game(export_dir, described, table_file, sessions):
    """The game whose rows a game's own table holds: the one games.csv says has the table; in an
    export from before games.csv said so, the one game of the rows' sessions (sessions.csv); None
    when neither tells."""
    owners = [g for g, d in described.items() if table_file in (d.get("tables") or ())]
    if len(owners) == 1:
        return owners[0]
    of_session = inputs.session_games(export_dir)
    games = {of_session[s] for s in sessions if s in of_session}
    return games.pop() if len(games) == 1 else None


def title_of(game):
    return game[:1].upper() + game[1:]


def analyse(export_dir, reference_condition, rating_scale=None, pool_players=False):
    """rating_scale: (low, high) for every statement, overriding the scales ratings.csv records;
    pool_players: analyse people and scripted players together (players.py)."""
    if not os.path.exists(export_dir):
        raise BadInput(f"{export_dir}: no such directory (expected the folder `warplab export` wrote).")
    if not os.path.isdir(export_dir):
        raise BadInput(f"{export_dir}: is not a directory (expected the folder `warplab export` wrote).")
    thresholds = discrimination.load(export_dir)
    # The discrimination game has no shots: an export of it alone has hit rates of no game.
    games, hitrate_rows = inputs.load_hitrates(export_dir, rows_required=thresholds is None)
    statements = inputs.load_statements(export_dir)
    matches = inputs.load_matches(export_dir, inputs.rating_scales(statements, rating_scale))
    inputs.check_rating_columns(matches, statements)
    sessions = inputs.load_sessions(export_dir)
    records, source, table_notes = inputs.load_conditions(export_dir)
    described = inputs.load_games(export_dir)
    table = ConditionTable(records)
    results = {"export_dir": export_dir, "inputs": {inputs.HITRATES: {"rows": hitrate_rows}},
               "sessions": None, "conditions_file": source, "conditions": table.records, "condition_order": [],
               "games": {}, "sign_tests": [], "matches": None, "figures": [], "notes": []}
    if isinstance(sessions, str):
        results["notes"].append(sessions)
    else:
        results["sessions"] = sessions
    if source is None:
        results["notes"].append("No modes.csv (an export from before warplab wrote one): conditions in the order of "
                                "their ids, none known as an upconverting condition, so no Table 2 and no "
                                "histograms.")
    elif source == inputs.MODES:
        results["inputs"][inputs.MODES] = {"conditions": len(records)}
    else:
        results["inputs"][inputs.CONDITIONS] = {"rows": len(records), "conditions": len(table.rows)}
    results["notes"] += table_notes
    if matches is not None:
        results["inputs"][inputs.MATCHES] = {"rows": matches[2], "scored_rows": len(matches[0])}
    answers = inputs.load_answers(export_dir)
    if answers is not None:
        results["inputs"][inputs.ANSWERS] = {"answers": len(answers)}
    kinds = inputs.load_player_kinds(export_dir)
    in_thresholds = set()
    if thresholds is not None:
        results["inputs"].update(thresholds.inputs)
        in_thresholds = thresholds.participants()
        for participant, kinds_of in (thresholds.player_kinds() if kinds is not None else {}).items():
            kinds.setdefault(participant, set()).update(kinds_of)
    everyone = sorted({p for g in games.values() for p in g} | set(kinds or {}) | in_thresholds, key=natural_key)
    split = players.groups(kinds, everyone, natural_key)
    results["players"] = {"sentence": players.sentence(kinds, everyone, natural_key), "pooled": pool_players,
                          "kinds": None if kinds is None else {p: players.kind_of(kinds.get(p, set()))
                                                               for p in everyone},
                          "groups": split, "analysed": None}
    if kinds is None:
        results["notes"].append(players.UNKNOWN_NOTE)
    parts = {"all": None} if kinds is None or pool_players or len(split) <= 1 else split
    data = (games, described, matches, statements, answers, thresholds)
    for k, (group, who) in enumerate(parts.items()):
        part = analyse_part(export_dir, data, None if who is None else set(who), reference_condition, table)
        if k == 0:
            results["players"]["analysed"] = None if who is None else group
            results.update(part)
        else:
            results.setdefault("player_groups", []).append(dict(part, group=group, participants=who))
    if statements is not None:
        results["inputs"][inputs.RATINGS] = {"statements": len(statements[0])}
    seen = set()
    for part in [results] + results.get("player_groups", []):
        seen |= {c for g in part["games"].values() for c in g["conditions"]}
        if part["matches"]:
            seen |= set(part["matches"]["conditions"])
        if part["discrimination"]:  # the references; each level's condition is one of them with one part changed
            seen |= {row["reference"] for row in part["discrimination"]["rows"]}
    results["condition_order"] = table.order(seen)
    for part in [results] + results.get("player_groups", []):
        part["questions"] = questions.summarise(part.pop("answers"), results["condition_order"], natural_key)
    unlisted = [c for c in results["condition_order"] if not table.known(c)]
    if source is not None and unlisted:
        results["notes"].append(f"{source} does not list {', '.join(unlisted)}: they follow the others by name, and "
                                "none counts as an upconverting condition.")
    return results


def draw_figures(results, out_dir):
    """Draws every figure, records its file name in results, and returns the paths written."""
    # Read here, not kept in results: report.json is the statistics, not every frame time. Read
    # before anything is drawn, so that a bad file ends the report before any figure is written.
    frame_times = inputs.load_frame_times(results["export_dir"])
    latency = inputs.load_latency(results["export_dir"])
    from warplab_analysis import figures  # matplotlib only once the input has been accepted
    written, taken = [], set()
    table = ConditionTable(results["conditions"])
    palette = table.all_conditions()
    for part in [results] + results.get("player_groups", []):
        # A second group's figures are named after it: "scripted_shooter_hit_rates.png".
        prefix = f"{part['group']}_" if "group" in part else ""
        written += draw_part(figures, part, out_dir, taken, table, palette, prefix, results["conditions_file"])
    written += draw_model_figures(results.get("mixed_models"), out_dir, taken, palette)
    if frame_times:
        name = file_stem("frame_times", taken) + ".png"
        figures.frame_times_figure(os.path.join(out_dir, name), frame_times, palette)
        written.append(name)
    if latency:
        name = file_stem("latency", taken) + ".png"
        figures.latency_figure(os.path.join(out_dir, name), latency, palette)
        written.append(name)
    results["figures"] = written
    return [os.path.join(out_dir, name) for name in written]


def draw_model_figures(section, out_dir, taken, palette):
    """The mixed models' contrasts and means (model_figures), where R fitted any; the names written."""
    if not section or not any(m.get("fitted") for m in section["models"]):
        return []
    from warplab_analysis import model_figures
    written = []
    drawers = [("means", model_figures.means_figure)]
    if any(m.get("fitted") and m["contrasts"] for m in section["models"]):
        drawers.insert(0, ("contrasts", model_figures.contrasts_figure))
    for kind, draw in drawers:
        name = file_stem(f"mixed_models_{kind}", taken) + ".png"
        draw(os.path.join(out_dir, name), section, palette)
        section["figures"][kind] = name
        written.append(name)
    return written


def draw_part(figures, part, out_dir, taken, table, palette, prefix, conditions_file):
    """The figures of one group's statistics (analyse_part); the file names written."""
    written = []
    tests_by_game = {}
    for test in part["sign_tests"]:
        tests_by_game.setdefault(test["game"], []).append(test)
    for game, summary in part["games"].items():
        stem = file_stem(prefix + game, taken)
        name = f"{stem}_hit_rates.png"
        labels = {c: legend_label(c, table.latency(c, game)) for c in summary["conditions"]}
        figures.hit_rates_figure(os.path.join(out_dir, name), game, summary["participants"], summary["conditions"],
                                 summary["hit_rates"], f"{summary['hits_are']} / {summary['shots_are']}", palette,
                                 labels)
        summary["figures"]["hit_rates"] = name
        written.append(name)
        panels = []
        for test in tests_by_game.get(game, []):
            a, b = test["a"], test["b"]
            if table.upconverts(a) or table.upconverts(b):
                flip = not table.upconverts(a)  # draw upconversion − other
                values = [-d if flip else d for d in test["differences"].values()]
                panels.append(((b, a) if flip else (a, b), values))
        if panels:
            name = f"{stem}_differences.png"
            figures.differences_figure(os.path.join(out_dir, name), game, panels, palette)
            summary["figures"]["differences"] = name
            written.append(name)
        elif len(summary["conditions"]) > 1:
            upconverting = [c for c in palette if table.upconverts(c)]
            lists_none = f"{conditions_file or inputs.MODES} lists none"
            summary["notes"].append(f"No upconverting condition ({', '.join(upconverting) or lists_none}): "
                                    "no histograms of differences.")
    matches = part["matches"]
    if matches and matches["conditions"]:
        name = file_stem(prefix + "matches", taken) + ".png"
        figures.matches_figure(os.path.join(out_dir, name), matches, palette)
        matches["figure"] = name
        written.append(name)
    section = part["discrimination"]
    for dimension in dict.fromkeys(row["dimension"] for row in (section or {}).get("rows", [])):
        rows = [row for row in section["rows"] if row["dimension"] == dimension]
        if not any(row["levels"] for row in rows):
            continue  # no trials to draw
        name = file_stem(f"{prefix}discrimination_{dimension}", taken) + ".png"
        figures.discrimination_figure(os.path.join(out_dir, name), dimension,
                                      list(dict.fromkeys(row["participant"] for row in rows)), rows,
                                      [p["procedure"] for p in section["procedures"] if p["dimension"] == dimension])
        section["figures"][dimension] = name
        written.append(name)
    return written


def legend_label(condition, latency):
    """The condition, and how long a mouse step takes to reach the screen in it where the table says."""
    if latency is None:
        return condition
    return f"{condition} (view {latency[0]:.1f}–{latency[1]:.1f} ms)"


def finite_or_none(value):
    """JSON has no NaN or infinity: such values become null."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {k: finite_or_none(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [finite_or_none(v) for v in value]
    return value


def rating_scale(text):
    """--rating-scale MIN:MAX, two whole numbers, MIN below MAX (as a protocol's ratings.min, ratings.max)."""
    low, _, high = text.partition(":")
    try:
        low, high = int(low), int(high)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not MIN:MAX, two whole numbers such as 1:7")
    if low >= high:
        raise argparse.ArgumentTypeError(f"{text!r}: MIN must be below MAX")
    return low, high


def replicates(text):
    """--power-replicates N, a whole number of at least 1 (power.R's own check, made before any
    model is fitted)."""
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 1:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number of at least 1")
    return value


def main(argv=None):
    parser = argparse.ArgumentParser(prog="analyze", description="Sign tests, the matches' tables and figures from "
                                                                 "the CSVs `warplab export` writes.")
    parser.add_argument("export_dir", metavar="EXPORT_DIR", help="the folder `warplab export` wrote")
    parser.add_argument("--out", required=True, metavar="REPORT_DIR",
                        help="where to write report.md, report.json and the figures (created if missing)")
    parser.add_argument("--reference-condition", default=DEFAULT_REFERENCE, metavar="NAME",
                        help=f"the condition of the matches every other one is compared with (default "
                             f"{DEFAULT_REFERENCE}; when the matches lack it, the first in the condition order that "
                             "upconverts, else the first)")
    # The same option under its name from before the analysis said condition, for the scripts that
    # pass it; left out of --help.
    parser.add_argument("--reference-mode", dest="reference_condition", default=argparse.SUPPRESS,
                        help=argparse.SUPPRESS)
    parser.add_argument("--rating-scale", type=rating_scale, metavar="MIN:MAX",
                        help="the lowest and highest answer of every statement, in place of the protocol's "
                             "ratings.min and ratings.max that ratings.csv records (default: those; for an export "
                             "from before ratings.csv had them, 1:7, the protocol's default); a rating outside the "
                             "scale is refused")
    parser.add_argument("--rscript", default="Rscript", metavar="PATH",
                        help="the Rscript that fits the mixed models (default: Rscript on PATH)")
    parser.add_argument("--no-mixed-models", action="store_true",
                        help="leave out the trial-level mixed models (R), for a quick look at a large study")
    parser.add_argument("--no-power", action="store_true",
                        help="leave out the sample size by simulation of the mixed models (R; docs/export.md, "
                             "\"Sample size by simulation\"), which takes about 35 s for the demo on 2 cores")
    # The plan was once asked for by --power; it is made by default now, and the option is kept
    # for the scripts that pass it; left out of --help.
    parser.add_argument("--power", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--effect", action="append", type=power.effect_argument, metavar="A:B=OR",
                        help="the odds ratio (rate ratio) of condition A against B to plan the sample size for, "
                             "in place of the pilot's estimate; only the stated contrasts are then planned; "
                             "repeatable")
    parser.add_argument("--power-pairs", choices=power.PAIRS, default=power.PAIRS[0],
                        help="the contrasts planned from the pilot's estimates: each condition against the "
                             "model's reference (default), or every pair, which takes longer (half as long again for "
                             "the demo)")
    parser.add_argument("--power-replicates", type=replicates, metavar="N",
                        help=f"simulated studies per number of participants (default {power.REPLICATES})")
    parser.add_argument("--pool-players", action="store_true",
                        help="analyse people and scripted players (bots, simulated participants) together; by "
                             "default each kind is analysed on its own, people first")
    args = parser.parse_args(argv)
    try:
        results = analyse(args.export_dir, args.reference_condition, args.rating_scale, args.pool_players)
    except BadInput as e:
        print(f"analyze: {e}", file=sys.stderr)
        return 1
    target = args.out
    if os.path.exists(args.out) and not os.path.isdir(args.out):
        print(f"analyze: {args.out}: is not a directory (REPORT_DIR, where the report goes).", file=sys.stderr)
        return 1
    try:
        os.makedirs(args.out, exist_ok=True)
        results["mixed_models"] = (mixed_models.left_out("Left out, as --no-mixed-models asked.")
                                   if args.no_mixed_models else mixed_models.fit(results, args.out, args.rscript))
        results["power"] = None
        if args.no_power and not args.no_mixed_models:
            results["power"] = power.left_out("as --no-power asked.")
        elif not args.no_mixed_models:
            results["power"] = power.plan(args.out, os.path.join(args.out, power.MODELS), effects=args.effect,
                                          replicates=args.power_replicates, pairs=args.power_pairs,
                                          rscript=shutil.which(args.rscript) or args.rscript)
        written = draw_figures(results, args.out)
        if results["power"] and results["power"].get("figure"):
            written.append(os.path.join(args.out, results["power"]["figure"]))
        target = os.path.join(args.out, "report.json")
        with open(target, "w", encoding="utf-8") as f:
            json.dump(finite_or_none(results), f, indent=2, allow_nan=False, ensure_ascii=False)
            f.write("\n")
        written.append(target)
        target = os.path.join(args.out, "report.md")
        with open(target, "w", encoding="utf-8") as f:
            f.write(report.render(results))
        written.append(target)
    except OSError as e:
        print(f"analyze: cannot write {e.filename or target}: {e.strerror or e}.", file=sys.stderr)
        return 1
    except BadInput as e:  # frametimes.csv or latency.csv, read as the figures are drawn
        print(f"analyze: {e}", file=sys.stderr)
        return 1
    for path in written:
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
