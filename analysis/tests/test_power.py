"""Sample size by simulation (analysis/r/power.R through warplab_analysis.power), on pilots made
here as the mixed-model script makes them: trial-level data simulated in R, fitted by glmer, saved
with saveRDS as a named list of {model, formula, reference, data}.

Oracles outside the code under test: lme4's own simulate() for the simulated responses, scipy's
Clopper-Pearson interval for the Monte-Carlo intervals, and what a null or a large effect must do
to power. Replicates are few, so each run takes seconds on one core.
"""
import argparse
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
from warplab_analysis import power  # noqa: E402
from warplab_analysis.inputs import BadInput  # noqa: E402

INSTALL = "apt-get install r-base-core r-cran-lme4 r-cran-jsonlite"

# Four participants x three conditions x 12 targets, as the demo's shooter pilot; the kept formula
# in three shapes the mixed-model script may keep, and a pilot of two participants.
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
    paths = folder / "mixed_models.rds", folder / "two_participants.rds"
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
    """A run's JSON less what timing and the core count change."""
    result = plan(tmp_path, pilots[0], replicates=30, n=[4, 6], cores=cores, seed=seed)
    for model in result["models"]:
        for study in model["studies"]:
            study.pop("seconds")
    return {k: v for k, v in result.items() if k not in ("seconds", "cores")}


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
    script = tmp_path / "simulate.R"
    script.write_text(SIMULATE_R)
    done = subprocess.run([rscript(), "--vanilla", str(script), str(power.SCRIPT), str(pilots[0])],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    rows = [line.split() for line in done.stdout.splitlines()]
    assert {r[0] for r in rows} == {"shooter_hit", "shooter_hit_uncorrelated", "shooter_hit_correlated"}
    assert all(r[2] == str(9 * 36) and r[3] == "0" for r in rows), rows


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
