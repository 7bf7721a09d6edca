"""Sample size by simulation for the report's trial-level mixed models: runs analysis/r/power.R
(simr's method, Green & MacLeod 2016, written with lme4 since Debian does not package simr) on
the fitted models the mixed-model script saved, and turns its JSON into the report's section and
power_curve.png.

What is simulated, refitted and tested, and what is assumed, is in docs/export.md, "Sample size
by simulation"; power.R's own comments say how. The sign-test planning table (planning.py) stays
beside it: it plans the thesis's own analysis, this one the model's.
"""
import argparse
import json
import math
import os
import shutil
import subprocess
from pathlib import Path

from . import markdown
from .inputs import BadInput

SCRIPT = Path(__file__).resolve().parents[1] / "r" / "power.R"
RESULT = "power.json"
FIGURE = "power_curve.png"
MODELS = "mixed_models.rds"
LEFT_OUT = "Sample size by simulation left out: "
DEBIAN = "Debian: apt-get install r-base-core r-cran-lme4 r-cran-jsonlite"
# power.R's exit statuses (its top comment): 1 bad input, 2 bad command line, 3 a package missing.
MISSING_PACKAGE = 3
# power.R's --pairs values, its default first, and its default --replicates (a test holds these to
# power.R's PAIRS and DEFAULTS).
PAIRS = ("reference", "all")
REPLICATES = 100


def effect_argument(text):
    """argparse type of --effect: A:B=RATIO, a ratio above 0 (the conditions are checked by power.R
    against each model's own, since only the models know them)."""
    pair, equals, ratio = text.rpartition("=")
    try:
        value = float(ratio)
    except ValueError:
        value = math.nan
    if not equals or ":" not in pair or not math.isfinite(value) or value <= 0:
        raise argparse.ArgumentTypeError(f"{text!r} is not A:B=RATIO, two conditions and an odds ratio above 0 "
                                         "(warp15to120:conv15=2)")
    return text


def run(rds_path, out_json, effects=(), replicates=None, cores=None, rscript=None, **options):
    """Runs power.R on `rds_path`, writing `out_json`; its parsed JSON with `available` True, or
    {"available": False, "sentence": why} when R, a package or the fitted models are missing.
    options: models, contrasts (lists of names and A:B), pairs, n (list), n_min, n_max, trials, seed,
    alpha, target, optimizer, nagq, as power.R's options. Raises BadInput when power.R refuses its input
    (an effect naming no model's conditions, effects that contradict each other)."""
    if not os.path.isfile(rds_path):
        return unavailable(f"no mixed models were fitted ({rds_path} is missing).")
    rscript = rscript or shutil.which("Rscript")
    if rscript is None or not os.path.isfile(rscript):
        return unavailable(f"Rscript is not on PATH ({DEBIAN}).")
    command = [rscript, "--vanilla", str(SCRIPT), str(rds_path), "--out", str(out_json)]
    command += [a for e in effects or () for a in ("--effect", e)]
    settings = dict(options, replicates=replicates, cores=cores)
    for key in ("models", "contrasts"):
        command += [a for v in settings.pop(key, None) or () for a in (f"--{key[:-1]}", v)]
    if settings.get("n"):
        settings["n"] = ",".join(str(v) for v in settings["n"])
    command += [a for k, v in settings.items() if v is not None for a in (f"--{k.replace('_', '-')}", str(v))]
    try:
        done = subprocess.run(command, capture_output=True, text=True)
    except OSError as e:
        return unavailable(f"{rscript} does not run ({e.strerror or e}; {DEBIAN}).")
    said = [line[len("power.R: "):] for line in done.stderr.splitlines() if line.startswith("power.R: ")]
    why = said[-1] if said else (done.stderr.strip().splitlines() or ["it ended without saying why"])[-1]
    if done.returncode == MISSING_PACKAGE:
        return unavailable(ending(why))
    if done.returncode != 0:
        raise BadInput(f"power.R: {why}")
    with open(out_json, encoding="utf-8") as f:
        result = timeless(json.load(f))
    result["available"] = True
    if not result["models"]:
        return unavailable("no mixed model was fitted to plan from.")
    simulated = [m for m in result["models"] if "skipped" not in m]
    if not simulated:
        return unavailable("; ".join(f"{m['model']}: {m['skipped']}" for m in result["models"]) + ".")
    return result


def timeless(result):
    """power.json less what the machine changes (the seconds taken, the cores used), so that the
    report made from it is the same on any machine: power.json keeps them."""
    result = {k: v for k, v in result.items() if k not in ("seconds", "cores")}
    result["models"] = [dict(m, studies=[{k: v for k, v in s.items() if k != "seconds"} for s in m["studies"]])
                        if "studies" in m else m for m in result["models"]]
    return result


def unavailable(why):
    return {"available": False, "sentence": LEFT_OUT + why}


def left_out(why):
    """The section's one sentence when the analysis was asked to leave the plan out."""
    return {"available": False, "sentence": f"Sample size by simulation left out, {why}"}


def ending(text):
    return text if text.endswith(".") else text + "."


def plan(report_dir, rds_path, effects=None, replicates=None, cores=None, **options):
    """The report's sample size by simulation: power.json and power_curve.png in report_dir, and
    the result (run's), with `figure` naming the PNG when one was drawn."""
    result = run(rds_path, os.path.join(report_dir, RESULT), effects, replicates, cores, **options)
    if result["available"]:
        power_figure(result, os.path.join(report_dir, FIGURE))
        result["figure"] = FIGURE
    return result


def interval(entry):
    return f"{entry['power']:.2f} ({entry['low']:.2f}–{entry['high']:.2f})"


def studies_at(model, n):
    return next(s for s in model["studies"] if s["n"] == n)


def contrast_row(model, contrast, search):
    """One row of the table: contrast, ratio used and its source, N, power at N with its
    Monte-Carlo interval, the N range, the studies simulated at N, the model."""
    ratio = f"{contrast['ratio']:.3g}"
    source = "stated" if contrast["source"] == "stated" else "pilot"
    if contrast["source"] == "stated":
        source += f" (pilot {contrast['pilot_ratio']:.3g})"
    low, high = contrast["range"]
    if contrast["needed"] is None:
        largest = contrast["curve"][-1]
        needed = f"not reached by {largest['n']}"
        at = f"{interval(largest)} at {largest['n']}"
        replicates = studies_at(model, largest["n"])["replicates"]
    else:
        needed = str(contrast["needed"])
        at = interval(contrast["at_needed"])
        replicates = studies_at(model, contrast["needed"])["replicates"]
        if contrast["needed"] == search["smallest"]:
            needed = f"{needed} or fewer (the fewest searched)"
    top = str(high) if high is not None else f"above {search['largest']}"
    span = markdown.NOTHING if low is None else str(low) if low == high else f"{low}–{top}"
    return [markdown.cell(model["model"]), f"{markdown.cell(contrast['a'])} vs {markdown.cell(contrast['b'])}", ratio,
            source, needed, at, span, str(replicates), markdown.cell(model["formula"])]


def power_markdown(result, level=2):
    """The report section's lines: what was simulated, the table, the figure, the notes; one
    sentence when the simulation could not run."""
    if not result.get("available"):
        return [result["sentence"] + "\n"]
    h = "#" * level
    target, alpha = result["target"], result["alpha"]
    search = result["search"]
    given = search["n"] is not None
    smallest = min(search["n"]) if given else search["n_min"]
    largest = max(search["n"]) if given else search["n_max"]
    lines = [f"{h} Sample size by simulation (mixed models): participants for {target * 100:g} % power\n",
             f"The power of each contrast's Wald z test (two-sided, α = {alpha:g}) in the trial-level mixed model, "
             f"by simulation (what R's simr does): up to {result['replicates']} simulated studies at each number of "
             "participants n, each of n new participants whose random effects are drawn afresh from the pilot's "
             "fitted distribution, each playing the pilot's trials per condition, every study refitted with the "
             f"kept formula (glmer, nAGQ = {result['nagq']}). The pilot's fixed effects are the truth, except a "
             "stated odds ratio, which replaces its contrast; with few pilot participants the random effects' "
             "spread is a rough estimate, taken as the truth too. " + planned_contrasts(result)
             + (f"n is each of {', '.join(str(n) for n in search['n'])}. " if given else
                f"n is searched from {smallest} to {largest}, doubling and then bisecting. ")
             + f"N for {target * 100:g} % is the smallest n searched whose simulated power reached {target:g}; "
             "beside it the power there and its 95 % Monte-Carlo interval (Clopper-Pearson), and the range of n, "
             f"among those simulated, from the first whose interval reaches {target:g} to the first whose interval "
             f"lies above it. An n whose interval already lay wholly on one side of {target:g} stopped early "
             "(studies: those simulated at N). For a study's final size, ask for more studies per n "
             "(`--power-replicates`): the interval narrows with their square root.\n"]
    rows, notes = [], []
    for model in result["models"]:
        if "skipped" in model:
            notes.append(f"{markdown.cell(model['model'])}: not simulated, {model['skipped']}.")
            continue
        for contrast in model["contrasts"]:
            rows.append(contrast_row(model, contrast, {"smallest": smallest, "largest": largest}))
        notes += model_notes(model)
    lines.append(markdown.table(["model", "contrast", "odds or rate ratio", "from", f"N for {target * 100:g} %",
                               "power at N (95 % MC interval)", "N range", "studies", "model simulated"], rows))
    if result.get("figure"):
        lines.append(f"![Power against participants, with 95 % Monte-Carlo intervals]({result['figure']})\n")
    lines += [note + "\n" for note in notes]
    return lines


def planned_contrasts(result):
    """Which contrasts the table plans, as power.R chose them."""
    if result["contrasts"]:
        return "The contrasts planned are those named. "
    if result["effects"]:
        return "The contrasts planned are those stated. "
    if result["pairs"] == "all":
        return "Every pair of each model's conditions is planned. "
    return "Each condition is planned against the model's reference (`--power-pairs all`: every pair). "


def model_notes(model):
    """What a reader needs to weigh the numbers: the trials per condition, the pilot's size and
    whether its fit was singular, the refits that failed or were singular."""
    trials = ", ".join(f"{c} {k}" for c, k in model["trials_per_condition"].items())
    pilot, name = model["pilot"], markdown.cell(model["model"])
    notes = [f"{name}: each simulated participant plays {trials} trials; the pilot had "
             f"{pilot['participants']} participants" + (", and its fit was singular (a random-effect variance at "
                                                          "zero, or a correlation at ±1)" if pilot["singular"] else "")
             + "."]
    studies = model["studies"]
    total = sum(s["replicates"] for s in studies)
    failed, singular = sum(s["failed"] for s in studies), sum(s["singular"] for s in studies)
    if failed:
        notes.append(f"{name}: {failed} of {total} refits failed; each counts as not rejecting.")
    if singular:
        notes.append(f"{name}: {singular} of {total} refits were singular; their Wald tests count as "
                     "they came out.")
    if model["ratio_name"] != "odds ratio":
        notes.append(f"{name}: a Poisson model, so its ratios are rate ratios.")
    return notes


def power_figure(result, path):
    """Power against n per contrast, each point with its 95 % Monte-Carlo interval, the target as a
    line and each contrast's N marked; one panel per model simulated."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker
    models = [m for m in result["models"] if "skipped" not in m]
    rows = max(len(m["contrasts"]) for m in models)
    # The legends go below the panels, where they hide no curve; taller for more contrasts.
    fig, axes = plt.subplots(1, len(models), figsize=(6.0 * len(models), 4.0 + 0.25 * rows), dpi=110, squeeze=False)
    for ax, model in zip(axes[0], models):
        for k, contrast in enumerate(model["contrasts"]):
            colour = plt.get_cmap("tab10")(k % 10)
            curve = contrast["curve"]
            n = [p["n"] for p in curve]
            power = [p["power"] for p in curve]
            errors = [[p["power"] - p["low"] for p in curve], [p["high"] - p["power"] for p in curve]]
            ratio = "OR" if model["ratio_name"] == "odds ratio" else "RR"
            label = f"{contrast['a']} vs {contrast['b']} ({ratio} {contrast['ratio']:.3g}, {contrast['source']})"
            ax.errorbar(n, power, yerr=errors, color=colour, marker="o", markersize=4, capsize=3, label=label)
            if contrast["needed"] is not None:
                ax.axvline(contrast["needed"], color=colour, linestyle=":", linewidth=1)
        ax.axhline(result["target"], color="0.3", linestyle="--", linewidth=1)
        ax.set_xscale("log", base=2)
        ax.xaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:g}"))
        ax.set_ylim(0, 1.02)
        ax.set_xlabel("participants (n)")
        ax.set_ylabel(f"power (Wald z, α = {result['alpha']:g})")
        ax.set_title(model["model"])
        ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.16), frameon=False)
    fig.tight_layout()
    fig.savefig(path, bbox_inches="tight")
    plt.close(fig)
