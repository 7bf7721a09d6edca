"""Sample size by simulation (analysis/r/power.R through warplab_analysis.power), on pilots made
here as the mixed-model script makes them: trial-level data simulated in R, fitted by glmer, saved
with saveRDS as a named list of {model, formula, reference, data}.

Oracles outside the code under test: lme4's own simulate() for the simulated responses, scipy's
Clopper-Pearson interval for the Monte-Carlo intervals, and what a null or a large effect must do
to power. Replicates are few, so each run takes seconds on one core.
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import scipy.stats

ANALYSIS = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ANALYSIS))
import analyze  # noqa: E402
from warplab_analysis import power  # noqa: E402
from warplab_analysis.inputs import BadInput  # noqa: E402

INSTALL = "apt-get install r-base-core r-cran-lme4 r-cran-jsonlite"

# Four participants x three conditions x 12 targets, as the demo's shooter pilot; the kept formula
# in three shapes the mixed-model script may keep, and a pilot of two participants. Then the click
# game's counts and answers.
PILOTS_R = r"""
suppressPackageStartupMessages(library(lme4))
out <- commandArgs(trailingOnly = TRUE)
pilot <- function(people, seed) {
  set.seed(seed)
  conds <- c("conv15", "conv120", "warp15to120")
  d <- expand.grid(trial = 1:12, condition = conds, participant = sprintf("P%d", seq_len(people)),
                   stringsAsFactors = FALSE)
  u <- setNames(rnorm(people, 0, 0.6), sprintf("P%d", seq_len(people)))
  d$hit <- rbinom(nrow(d), 1, plogis(c(conv15 = -0.8, conv120 = 1.0, warp15to120 = 0.6)[d$condition] +
                                     u[d$participant]))
  d$condition <- factor(d$condition, levels = conds)
  d$trial <- NULL
  d$d_conv120 <- as.numeric(d$condition == "conv120")
  d$d_warp15to120 <- as.numeric(d$condition == "warp15to120")
  d
}
entry <- function(formula, d) {
  m <- suppressWarnings(suppressMessages(glmer(as.formula(formula), d, family = binomial)))
  list(model = m, formula = formula, reference = "conv15", data = d)
}
d <- pilot(4, 11)
saveRDS(list(
  shooter_hit = entry("hit ~ condition + (1 | participant)", d),
  shooter_hit_uncorrelated = entry(paste("hit ~ condition + (1 | participant) + (0 + d_conv120 | participant)",
                                         "+ (0 + d_warp15to120 | participant)"), d),
  shooter_hit_correlated = entry("hit ~ condition + (1 + condition | participant)", d)), out[1])
wrong <- entry("hit ~ condition + (1 | participant)", d)
wrong$reference <- "conv120"  # not the factor's first level, which the coefficients are against
saveRDS(list(shooter_hit = entry("hit ~ condition + (1 | participant)", pilot(2, 12)), wrong_reference = wrong),
        out[2])
# The click game's green hits per match (Poisson), and the two fits the simulation does not do: a
# negative binomial GLMM and a cumulative-link model of answers, as the mixed-model script keeps them.
set.seed(13)
conds <- c("bireproj15to60", "conv60", "conv15")
m <- expand.grid(match = 1:2, condition = conds, participant = sprintf("P%d", 1:5), stringsAsFactors = FALSE)
m$green_hits <- rpois(nrow(m), exp(3 + c(bireproj15to60 = 0, conv60 = 0.2, conv15 = -0.3)[m$condition] +
                                  rnorm(5, 0, 0.1)[as.integer(factor(m$participant))]))
m$condition <- factor(m$condition, levels = conds)
m$match <- NULL
counts <- function(formula, fit) list(model = fit, formula = formula, reference = "bireproj15to60", data = m)
f <- "green_hits ~ condition + (1 | participant)"
a <- data.frame(participant = rep(sprintf("P%d", 1:5), each = 3), condition = factor(rep(conds, 5), levels = conds),
                answer = factor(c(5, 6, 2, 4, 6, 3, 5, 7, 2, 6, 6, 1, 4, 5, 3), levels = 1:7, ordered = TRUE))
saveRDS(list("click/green_hits" = counts(f, suppressWarnings(glmer(as.formula(f), m, family = poisson))),
             "click/green_hits_nb" = counts(f, suppressWarnings(suppressMessages(glmer.nb(as.formula(f), m)))),
             "click/likert:q0" = list(model = ordinal::clmm(answer ~ condition + (1 | participant), data = a),
                                      formula = "answer ~ condition + (1 | participant)",
                                      reference = "bireproj15to60", data = a)), out[3])
"""


def rscript():
    path = shutil.which("Rscript")
    if path is None:
        pytest.fail(f"Rscript is not on PATH: {INSTALL}.")
    return path


@pytest.fixture(scope="module")
def pilots(tmp_path_factory):
    folder = tmp_path_factory.mktemp("pilots")
    script = folder / "pilots.R"
    script.write_text(PILOTS_R)
    paths = folder / "mixed_models.rds", folder / "two_participants.rds", folder / "click.rds"
    done = subprocess.run([rscript(), "--vanilla", str(script), *map(str, paths)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return paths


def plan(tmp_path, rds, **options):
    options = {"models": ["shooter_hit"], "cores": 1, **options}  # models None: every one in the file
    return power.plan(str(tmp_path), str(rds), **options)


@pytest.fixture(scope="module")
def large(pilots, tmp_path_factory):
    """A stated odds ratio of 4 between warp15to120 and conv15, from 2 participants up; the
    result, with the folder it wrote to under `folder`."""
    folder = tmp_path_factory.mktemp("large")
    result = plan(folder, pilots[0], effects=["warp15to120:conv15=4"], replicates=40, n_min=2, n_max=16)
    return dict(result, folder=folder)


def only_contrast(result):
    [model] = result["models"]
    [contrast] = model["contrasts"]
    return model, contrast


def test_a_large_stated_effect_needs_few_participants_and_power_rises_with_them(large):
    model, contrast = only_contrast(large)
    assert (contrast["a"], contrast["b"], contrast["source"]) == ("warp15to120", "conv15", "stated")
    assert contrast["ratio"] == pytest.approx(4.0)
    assert contrast["pilot_ratio"] != pytest.approx(4.0)  # the stated effect, not the pilot's, was simulated
    assert model["fixed_effects"]["conditionwarp15to120"] == pytest.approx(math.log(4.0))
    assert 2 < contrast["needed"] <= 8
    curve = contrast["curve"]
    assert [p["n"] for p in curve] == sorted(p["n"] for p in curve)
    assert curve[0]["power"] < large["target"] <= contrast["at_needed"]["power"]
    assert curve[0]["power"] < curve[-1]["power"]
    below = [p for p in curve if p["n"] < contrast["needed"]]
    assert below and all(p["power"] < large["target"] for p in below[-1:])


def test_a_null_effect_never_reaches_the_target_and_says_so(pilots, tmp_path):
    result = plan(tmp_path, pilots[0], effects=["warp15to120:conv15=1"], replicates=40, n_max=8)
    model, contrast = only_contrast(result)
    assert contrast["needed"] is None
    assert [p["n"] for p in contrast["curve"]] == [4, 8]  # doubling from 4 up to --n-max
    assert all(p["high"] < result["target"] for p in contrast["curve"])
    row = [line for line in power.power_markdown(result) if "warp15to120 vs conv15" in line]
    assert row and "not reached by 8" in row[0]


def timeless(pilots, tmp_path, cores, seed):
    """The plan as the report keeps it: without what timing and the core count change, which
    power.json keeps."""
    result = plan(tmp_path, pilots[0], replicates=30, n=[4, 6], cores=cores, seed=seed)
    written = json.loads((tmp_path / power.RESULT).read_text())
    assert written["cores"] == cores and written["seconds"] > 0
    assert "seconds" not in result and "cores" not in result
    assert all("seconds" not in study for model in result["models"] for study in model["studies"])
    return result


def test_the_same_seed_gives_the_same_answer_on_one_core_and_on_two(pilots, tmp_path):
    one = timeless(pilots, tmp_path, 1, 7)
    assert one == timeless(pilots, tmp_path, 2, 7)
    assert one != timeless(pilots, tmp_path, 1, 8)  # the seed, not chance agreement, makes the two equal


def test_the_json_and_the_markdown_carry_the_monte_carlo_interval(large):
    model, contrast = only_contrast(large)
    for point in contrast["curve"] + [dict(contrast["at_needed"], n=contrast["needed"])]:
        studies = next(s for s in model["studies"] if s["n"] == point["n"])["replicates"]
        rejections = round(point["power"] * studies)
        ci = scipy.stats.binomtest(rejections, studies).proportion_ci(0.95, method="exact")
        assert (point["low"], point["high"]) == pytest.approx((ci.low, ci.high), abs=1e-9)
    low, high = contrast["range"]
    assert low <= contrast["needed"] and (high is None or high >= contrast["needed"])
    at = contrast["at_needed"]
    text = "".join(power.power_markdown(large))
    assert f"{at['power']:.2f} ({at['low']:.2f}–{at['high']:.2f})" in text
    assert "Monte-Carlo interval" in text and f"]({power.FIGURE})" in text
    assert os.path.getsize(large["folder"] / large["figure"]) > 0
    assert (large["folder"] / power.RESULT).is_file()


def test_r_missing_gives_one_sentence(pilots, tmp_path):
    for result in (power.plan(str(tmp_path), str(pilots[0]), rscript=str(tmp_path / "no-such-Rscript")),
                   power.plan(str(tmp_path), str(tmp_path / "mixed_models.rds"))):
        lines = power.power_markdown(result)
        assert len(lines) == 1 and lines[0].count(". ") == 0 and lines[0].rstrip().endswith(".")
        assert lines[0].startswith(power.LEFT_OUT)
    stub = tmp_path / "Rscript"  # an R without lme4, as power.R reports it
    stub.write_text("#!/bin/sh\necho 'power.R: R lacks the package lme4 (Debian: apt-get install r-cran-lme4)' >&2\n"
                    "exit 3\n")
    stub.chmod(0o755)
    [line] = power.power_markdown(power.plan(str(tmp_path), str(pilots[0]), rscript=str(stub)))
    assert line == power.LEFT_OUT + "R lacks the package lme4 (Debian: apt-get install r-cran-lme4).\n"


def test_a_pilot_of_two_participants_is_too_little_data(pilots, tmp_path):
    """So is one whose reference is not what its coefficients are against: each skipped with its
    reason, and with none left, the section is one sentence naming both."""
    [line] = power.power_markdown(plan(tmp_path, pilots[1], models=None))
    assert line.startswith(power.LEFT_OUT) and line.count(". ") == 0
    assert "shooter_hit: the pilot has too little data: 2 participants" in line
    assert "wrong_reference: its reference is conv120 but its model's first condition level is conv15" in line


def test_an_effect_naming_no_model_s_conditions_is_refused(pilots, tmp_path):
    """Even beside one that does: a misspelt condition is not silently left out."""
    with pytest.raises(BadInput, match="^power.R: no model has both conditions of conv60:conv15=2$"):
        plan(tmp_path, pilots[0], effects=["warp15to120:conv15=2", "conv60:conv15=2"], replicates=5, n=[4])


def rows_printed(script_text, rds, folder):
    """Runs an R script that sources power.R (its first argument) and reads `rds` (its second);
    the words of each line it prints."""
    script = folder / "check.R"
    script.write_text(script_text)
    done = subprocess.run([rscript(), "--vanilla", str(script), str(power.SCRIPT), str(rds)], capture_output=True,
                          text=True)
    assert done.returncode == 0, done.stderr
    return [line.split() for line in done.stdout.splitlines()]


SIMULATE_R = r"""
args <- commandArgs(trailingOnly = TRUE)
source(args[1])
suppressPackageStartupMessages(library(lme4))
models <- readRDS(args[2])
for (name in names(models)) {
  entry <- models[[name]]
  model <- entry$model
  beta <- fixef(model)
  beta[["conditionwarp15to120"]] <- log(3)  # a stated effect travels through newparams alike
  ctx <- list(design = design_of(c(entry, name = name), NULL), formula = as.formula(entry$formula),
              family = family(model), params = list(beta = beta, theta = getME(model, "theta")))
  structure <- study_structure(ctx, 9L)
  for (seed in 1:3) {
    set.seed(seed)
    ours <- simulate_response(structure, beta, ctx$family)
    set.seed(seed)
    theirs <- simulate(model, nsim = 1, newdata = structure$study, newparams = ctx$params, re.form = NA,
                       allow.new.levels = TRUE)[[1]]
    cat(name, seed, length(ours), sum(ours != theirs), "\n")
  }
}
"""


def test_each_study_is_drawn_as_lme4_s_simulate_draws_it(pilots, tmp_path):
    """For every formula shape, the same stream gives the same responses as simulate(re.form = NA,
    allow.new.levels = TRUE) for nine new participants: fresh random effects, then the trials."""
    rows = rows_printed(SIMULATE_R, pilots[0], tmp_path)
    assert {r[0] for r in rows} == {"shooter_hit", "shooter_hit_uncorrelated", "shooter_hit_correlated"}
    assert all(r[2] == str(9 * 36) and r[3] == "0" for r in rows), rows


REFIT_R = r"""
args <- commandArgs(trailingOnly = TRUE)
source(args[1])
suppressPackageStartupMessages(library(lme4))
models <- readRDS(args[2])
RNGkind("L'Ecuyer-CMRG")
set.seed(5)
streams <- Reduce(function(s, r) parallel::nextRNGStream(s), seq_len(30), .Random.seed, accumulate = TRUE)[-1]
for (name in names(models)) {
  entry <- models[[name]]
  model <- entry$model
  design <- design_of(c(entry, name = name), NULL)
  beta <- fixef(model)
  L <- do.call(rbind, lapply(list(c("conv120", "conv15"), c("warp15to120", "conv15"), c("warp15to120", "conv120")),
                             function(p) contrast_row(p[[1]], p[[2]], "conv15", beta)))
  ctx <- list(design = design, formula = as.formula(entry$formula), family = family(model), streams = streams,
              params = list(beta = beta, theta = getME(model, "theta")), L = L, alpha = 0.05, nagq = 0L,
              control = glmerControl(optimizer = "nloptwrap", calc.derivs = FALSE))
  fresh <- study_structure(ctx, 6L)
  refitted <- with_template(fresh, ctx)
  stopifnot(inherits(refitted$template, "glmerMod"))
  for (r in seq_along(streams)) {
    a <- one_study(r, refitted, ctx)
    b <- one_study(r, fresh, ctx)
    cat(name, r, sum(a$reject), sum(b$reject), sum(a$reject != b$reject), "\n")
  }
}
"""


def test_refitting_the_template_decides_as_fitting_each_study_afresh(pilots, tmp_path):
    """Each study is refitted from one fit per n (lme4's refit with the study's response): for
    every formula shape, 30 studies of 6 participants reject the same contrasts as glmer run
    afresh on each, and some but not all of them reject (the comparison has something to see)."""
    rows = rows_printed(REFIT_R, pilots[0], tmp_path)
    assert len(rows) == 3 * 30
    assert all(r[4] == "0" for r in rows), [r for r in rows if r[4] != "0"]
    rejections = [int(r[2]) for r in rows]
    assert 0 < sum(rejections) < 3 * len(rows)


def test_the_docs_state_power_r_s_defaults():
    """docs/export.md's numbers are power.R's: the default replicates, the n searched, the batch,
    the smallest pilot, alpha."""
    source = power.SCRIPT.read_text()
    defaults = dict(re.findall(r"(\w+) = ([\d.]+)L?", re.search(r"DEFAULTS <- list\((.*?)\)\n", source, re.S)[1]))
    batch = re.search(r"^BATCH <- (\d+)L", source, re.M)[1]
    fewest = re.search(r"^FEWEST_PILOT_PARTICIPANTS <- (\d+)L", source, re.M)[1]
    docs = " ".join((ANALYSIS.parent / "docs" / "export.md").read_text().split())
    for phrase in (f"{defaults['replicates']} studies per n by default", f"n is searched from {defaults['n_min']},",
                   f"doubling up to {defaults['n_max']}", f"batches of {batch}", f"fewer than {fewest} participants",
                   f"at α = {defaults['alpha']}", f"(default {defaults['seed']})"):
        assert phrase in docs, phrase


@pytest.mark.parametrize("text, good", [("warp15to120:conv15=2", True), ("a:b=0.5", True), ("a:b=0", False),
                                        ("a:b=-1", False), ("a:b=inf", False), ("ab=2", False), ("a:b", False),
                                        ("a:b=two", False)])
def test_the_effect_option_wants_two_conditions_and_a_ratio_above_zero(text, good):
    if good:
        assert power.effect_argument(text) == text
    else:
        with pytest.raises(argparse.ArgumentTypeError, match="A:B=RATIO"):
            power.effect_argument(text)


def test_counts_are_planned_by_their_rate_ratio_and_other_fits_are_named_as_not_simulated(pilots, tmp_path):
    """A Poisson GLMM is simulated as one (a stated rate ratio of 1.5 on about 20 green hits a
    match is found with few participants); a negative binomial GLMM and a clmm are named with
    their reasons, beside it."""
    result = plan(tmp_path, pilots[2], models=None, effects=["conv60:bireproj15to60=1.5"], replicates=25,
                  n_min=2, n_max=8)
    models = {m["model"]: m for m in result["models"]}
    counts = models["click/green_hits"]
    assert (counts["family"], counts["ratio_name"]) == ("poisson", "rate ratio")
    assert counts["fixed_effects"]["conditionconv60"] == pytest.approx(math.log(1.5))
    [contrast] = counts["contrasts"]
    assert contrast["needed"] is not None and contrast["needed"] <= 4
    assert counts["trials_per_condition"] == {"bireproj15to60": 2, "conv60": 2, "conv15": 2}
    assert models["click/green_hits_nb"]["skipped"].startswith("its family is Negative Binomial(")
    assert models["click/likert:q0"]["skipped"] == ("it is not a glmer fit (only binomial and Poisson GLMMs are "
                                                   "simulated)")
    text = "".join(power.power_markdown(result))
    assert "click/green\\_hits: a Poisson model, so its ratios are rate ratios." in text  # _ escaped
    assert "click/likert:q0: not simulated, it is not a glmer fit" in text


def test_each_condition_is_planned_against_the_reference_unless_every_pair_is_asked_for(pilots, tmp_path):
    pairs = {}
    for asked in power.PAIRS:
        model, = plan(tmp_path, pilots[0], pairs=asked, replicates=25, n=[4])["models"]
        pairs[asked] = [(c["a"], c["b"]) for c in model["contrasts"]]
    assert pairs["reference"] == [("conv120", "conv15"), ("warp15to120", "conv15")]
    assert pairs["all"] == pairs["reference"][:1] + [("warp15to120", "conv15"), ("warp15to120", "conv120")]


def test_contrast_trials_and_alpha_are_the_plan_s(pilots, tmp_path):
    """--contrast names the contrasts planned (one no model has is skipped with the reason),
    --trials sets each new participant's trials per condition, and --alpha the test's level: the
    same studies (the same seed) reject no more often at 0.01 than at 0.05, and less often here."""
    runs = {}
    for alpha in (0.05, 0.01):
        model, = plan(tmp_path, pilots[0], contrasts=["warp15to120:conv120"], trials=6, alpha=alpha, replicates=25,
                      n=[4, 8])["models"]
        [contrast] = model["contrasts"]
        assert (contrast["a"], contrast["b"]) == ("warp15to120", "conv120")
        assert model["trials_per_condition"] == {"conv15": 6, "conv120": 6, "warp15to120": 6}
        assert all(s["replicates"] == 25 for s in model["studies"])  # one batch: the same studies at each level
        runs[alpha] = [p["rejections"] for p in contrast["curve"]]
    assert all(strict <= loose for strict, loose in zip(runs[0.01], runs[0.05]))
    assert sum(runs[0.01]) < sum(runs[0.05])
    [line] = power.power_markdown(plan(tmp_path, pilots[0], contrasts=["conv60:conv15"], replicates=25, n=[4]))
    assert line == (power.LEFT_OUT + "shooter_hit: none of the contrasts asked for is between two of its "
                    "conditions.\n")


def test_the_python_side_knows_power_r_s_pairs_and_replicates():
    source = power.SCRIPT.read_text()
    assert re.search(r'^PAIRS <- c\("reference", "all"\)$', source, re.M) and power.PAIRS == ("reference", "all")
    assert re.search(rf"DEFAULTS <- list\(replicates = {power.REPLICATES}L,", source)
    assert re.search(r'pairs = "reference"\)', source)


@pytest.mark.parametrize("text", ["0", "-5", "many", "2.5"])
def test_the_replicates_option_wants_a_whole_number_of_at_least_one(text, tmp_path, capsys):
    """Refused by analyze's command line, before any model is fitted (exit 2, as argparse's)."""
    with pytest.raises(SystemExit) as ended:
        analyze.main([str(tmp_path), "--out", str(tmp_path / "out"), "--power-replicates", text])
    assert ended.value.code == 2
    assert f"argument --power-replicates: {text!r} is not a whole number of at least 1" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()
