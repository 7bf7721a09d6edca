"""The report's trial-level mixed models (analysis/r/mixed_models.R, run by analyze): against data
simulated here from stated GLMMs, against an independent fit with glmmTMB, on data that cannot
support a model, re-run from the script the report keeps, and without R.

The exports are simulated in this file, each with a fixed seed:
- `simulated`: the shooter's hit per target from a binomial GLMM, logit P(hit) = β[condition] +
  u[participant] + v[participant, condition], with u ~ N(0, INTERCEPT_SD²) and v ~ N(0, SLOPE_SD²)
  (a participant's own effect of each condition), for 20 participants, 3 conditions and 40
  targets each; and one Likert question after each block, from a cumulative logit model.
- `singular`: the same with no participant-by-condition variation (SLOPE_SD 0), which the maximal
  model cannot estimate, and the click game's green hits per match from a negative binomial.
- `awkward`: a condition conditions.csv lists that nobody played, a participant who hit every
  target of a condition, a participant without one condition, and a game whose every click hit.
R and its packages are needed (scripts/install-deps.sh installs them); a test fails saying so
when they are missing, except the one that shows what the report says without R.
"""
import json
import re
import shutil
import subprocess

import numpy as np
import pytest

from exports import DATA, run_in_process, write
from warplab_analysis import mixed_models
from r_support import installed_by_deps, run_r

INSTALL = ("run scripts/install-deps.sh (it installs r-base-core, r-cran-lme4, r-cran-emmeans, r-cran-ordinal, "
           "r-cran-glmmtmb and r-cran-jsonlite)")
SHOTS_HEADER = "participant,session,game,phase,scored_phase,trial,condition,outcome,hit,player_kind"
ANSWERS_HEADER = ("participant,session,game,block,scored_phase,block_index,condition,question_index,question_id,kind,"
                  "prompt,value,text,answered_with,scale_min,scale_max,player_kind")
MATCH_HEADER = "participant,session,round,scored_phase,match,condition,green_hits,red_hits,misses,player_kind"

# The simulated study: its true log-odds per condition and random-effect SDs (logit scale).
LOG_ODDS = {"warp15to120": 1.0, "conv120": 1.5, "conv15": 0.3}
INTERCEPT_SD, SLOPE_SD = 0.6, 0.4
PARTICIPANTS, TARGETS = 20, 40
# The Likert question's latent effects and thresholds (cumulative logit, answers 1 to 7).
LIKERT_EFFECTS = {"warp15to120": 0.5, "conv120": 1.0, "conv15": -0.8}
LIKERT_CUTS = [-3.0, -1.8, -0.7, 0.4, 1.5, 2.7]
# The click game's green hits per match: log mean per condition, and a negative binomial's size.
GREEN_LOG_MEANS = {"conv60": 3.4, "conv15": 3.0, "bireproj15to60": 3.2}
GREEN_SIZE = 3.0


def rscript():
    program = shutil.which("Rscript")
    if program is None:
        pytest.fail(f"Rscript is not on PATH: {INSTALL}.")
    return program


def simulate_hits(rng, log_odds, intercept_sd, slope_sd, participants, targets, game="shooter"):
    """[(participant, game, condition, hit)] from the binomial GLMM the module docstring states."""
    trials = []
    for p in range(1, participants + 1):
        u = rng.normal(0.0, intercept_sd)
        for condition, beta in log_odds.items():
            v = rng.normal(0.0, slope_sd) if slope_sd else 0.0
            hits = rng.random(targets) < 1 / (1 + np.exp(-(beta + u + v)))
            trials += [(f"P{p}", game, condition, bool(h)) for h in hits]
    return trials


def write_export(export, trials, listed=None, kinds=None):
    """shots.csv and the hitrates.csv it implies, games.csv, and conditions.csv with the rows of
    data/conditions.csv for `listed` (default: the conditions played), used in the test."""
    export.mkdir(exist_ok=True)
    kinds = kinds or {}
    shots, counts = [SHOTS_HEADER], {}
    for k, (p, game, condition, hit) in enumerate(trials):
        shots.append(f"{p},{p}.s,{game},test,true,{k},{condition},{'hit' if hit else 'miss'},{str(hit).lower()},"
                     f"{kinds.get(p, 'human')}")
        hits, n = counts.get((p, game, condition), (0, 0))
        counts[(p, game, condition)] = (hits + hit, n + 1)
    write(export / "shots.csv", shots)
    write(export / "hitrates.csv", ["participant,game,condition,shots,hits,timeouts,hit_rate,player_kind"]
          + [f"{p},{g},{c},{n},{h},0,{h / n},{kinds.get(p, 'human')}" for (p, g, c), (h, n) in counts.items()])
    games = dict.fromkeys(g for _, g, _, _ in trials)
    write(export / "games.csv", ["game,hits_are,shots_are"]
          + [f"{g},{'green hits' if g == 'click' else 'hits'},{'clicks' if g == 'click' else 'shots'}" for g in games])
    table = (DATA / "conditions.csv").read_text(encoding="utf-8").splitlines()
    wanted = {(g, c) for _, g, c, _ in trials} if listed is None else set(listed)
    write(export / "conditions.csv", [table[0] + ",used_in"]
          + [line + ",test" for line in table[1:] if (line.split(",")[11], line.split(",")[0]) in wanted])


def likert_answers(rng, participants):
    rows = [ANSWERS_HEADER]
    for p in range(1, participants + 1):
        u = rng.normal(0.0, 0.8)
        for block, (condition, effect) in enumerate(LIKERT_EFFECTS.items()):
            latent = effect + u + rng.logistic()
            value = 1 + sum(latent > cut for cut in LIKERT_CUTS)
            rows.append(f"P{p},P{p}.s,shooter,test,true,{block},{condition},0,smooth,likert,The motion looked smooth,"
                        f"{value},,key,1,7,human")
    return rows


def analyse(export, out, *extra, power=False):
    code, report = run_in_process(export, out, *extra, mixed_models=True, power=power)
    assert code == 0
    return report, (out / "report.md").read_text(encoding="utf-8")


def model(report, key):
    (found,) = [m for m in report["mixed_models"]["models"] if m["key"] == key]
    return found


@pytest.fixture(scope="module")
def simulated(tmp_path_factory):
    rscript()
    base = tmp_path_factory.mktemp("simulated")
    rng = np.random.default_rng(20240611)
    write_export(base / "export", simulate_hits(rng, LOG_ODDS, INTERCEPT_SD, SLOPE_SD, PARTICIPANTS, TARGETS))
    write(base / "export" / "answers.csv", likert_answers(rng, PARTICIPANTS))
    # The report as analyze makes it by default, but for fewer simulated studies (one batch).
    report, md = analyse(base / "export", base / "report", "--power-replicates", 25, power=True)
    return base, report, md


@pytest.fixture(scope="module")
def singular(tmp_path_factory):
    rscript()
    base = tmp_path_factory.mktemp("singular")
    rng = np.random.default_rng(7)
    export = base / "export"
    write_export(export, simulate_hits(rng, LOG_ODDS, 0.8, 0.0, PARTICIPANTS, 30))
    rows = [MATCH_HEADER]
    for p in range(1, PARTICIPANTS + 1):
        u = rng.normal(0.0, 0.3)
        for k, (condition, log_mean) in enumerate(GREEN_LOG_MEANS.items()):
            for match in range(2):
                green = rng.negative_binomial(GREEN_SIZE, GREEN_SIZE / (GREEN_SIZE + np.exp(log_mean + u)))
                rows.append(f"P{p},P{p}.c,scored,true,{2 * k + match},{condition},{green},3,10,human")
    write(export / "matches.csv", rows)
    report, md = analyse(export, base / "report")
    return base, report, md


def test_estimates_cover_the_true_odds_ratios(simulated):
    _, report, md = simulated
    shooter = model(report, "shooter/hit")
    assert shooter["fitted"] and shooter["n_participants"] == PARTICIPANTS
    assert shooter["n_observations"] == PARTICIPANTS * TARGETS * len(LOG_ODDS)
    # The reference is the first in the condition order: the upconverting condition.
    assert shooter["reference"] == "warp15to120" and shooter["conditions"] == ["warp15to120", "conv120", "conv15"]
    assert len(shooter["contrasts"]) == 3
    for c in shooter["contrasts"]:
        truth = np.exp(LOG_ODDS[c["a"]] - LOG_ODDS[c["b"]])
        assert c["low"] < truth < c["high"], (c["a"], c["b"], truth, c["low"], c["high"])
        assert c["low"] < c["ratio"] < c["high"] and 0 <= c["p_holm"] <= 1
    for e in shooter["means"]:
        assert 0 < e["low"] < e["estimate"] < e["high"] < 1
    terms = {r["term"] for r in shooter["random_effects"]["sds"]}
    assert "intercept" in terms
    likert = model(report, "shooter/likert:smooth")
    assert likert["fitted"] and likert["ratio"] == "cumulative odds ratio" and likert["engine"] == "clmm"
    assert all(1 <= e["low"] <= e["estimate"] <= e["high"] <= 7 for e in likert["means"])
    # The report opens with the models and the sample size they need, before the conditions and
    # the papers' own analyses.
    sections = re.findall(r"^## (.*)$", md, flags=re.M)
    assert sections[0] == "Mixed models, trial by trial", sections
    assert sections[1].startswith("Sample size by simulation (mixed models)")
    assert sections[3].startswith("Shooter: hit rates, the paper's own analysis, replicated")
    planned = {m["model"]: m for m in report["power"]["models"]}
    assert report["power"]["available"] and report["power"]["pairs"] == "reference"
    assert [(c["a"], c["b"]) for c in planned["shooter/hit"]["contrasts"]] == [("conv120", "warp15to120"),
                                                                               ("conv15", "warp15to120")]
    assert "| warp15to120 / conv120 |" in md and "Holm" in md
    for name in ("mixed_models_contrasts.png", "mixed_models_means.png"):
        assert name in report["figures"] and f"]({name})" in md


def printed_estimates(stdout):
    """{(model heading, label): (estimate, low, high, p or None)} from the script's printout."""
    found, heading = {}, None
    for line in stdout.splitlines():
        if line.startswith("== "):
            heading = line
            continue
        m = re.match(r"^  (\S.*?)\s+(\S+) \[(\S+), (\S+)\](?:\s+p = (\S+))?$", line)
        if m and heading:
            found[(heading, m.group(1))] = tuple(float(v) if v else None for v in m.groups()[1:])
    return found


def test_the_written_script_reruns_to_the_same_estimates(simulated):
    base, report, _ = simulated
    out = base / "report"
    before = json.loads((out / "mixed_models.json").read_text(encoding="utf-8"))
    done = subprocess.run([rscript(), "mixed_models.R"], cwd=out, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    printed = printed_estimates(done.stdout)
    for m in report["mixed_models"]["models"]:
        heading = f"== {m['game']}: {m['label']} ({m['source']}) =="
        expected = {e["condition"]: (e["estimate"], e["low"], e["high"], None) for e in m["means"]}
        expected.update({f"{c['a']} / {c['b']}": (c["ratio"], c["low"], c["high"], c["p_holm"])
                         for c in m["contrasts"]})
        for label, values in expected.items():
            got = printed[(heading, label)]
            assert got == pytest.approx(values, rel=1e-5), (heading, label)
    again = json.loads((out / "mixed_models.json").read_text(encoding="utf-8"))
    assert again == before
    added = {"left_out", "script", "results", "models_file", "figures", "settings"}
    assert {k: v for k, v in report["mixed_models"].items() if k not in added} == json.loads(json.dumps(before))
    # The saved models, as the power simulation reads them.
    done = subprocess.run([rscript(), "--vanilla", "-e", 'x <- readRDS("mixed_models.rds")[["shooter/hit"]]; '
                           'cat(class(x$model)[1], x$reference, x$step, x$formula, is.character(x$formula), '
                           'nrow(x$data), levels(x$data$condition)[1], sep = "\\n")'],
                          cwd=out, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    shooter = model(report, "shooter/hit")
    assert done.stdout.splitlines() == ["glmerMod", "warp15to120", shooter["kept"], shooter["formula"], "TRUE",
                                        str(shooter["n_observations"]), "warp15to120"]


GLMMTMB = r"""
suppressPackageStartupMessages(library(glmmTMB))
args <- commandArgs(trailingOnly = TRUE)
d <- read.csv(args[1], colClasses = "character")
d <- d[d$game == "shooter" & d$scored_phase == "true", ]
d$hit <- as.integer(d$hit == "true")
d$condition <- factor(d$condition, levels = c(LEVELS))
m <- glmmTMB(hit ~ condition + (1 | participant), data = d, family = binomial)
cat(sprintf("%a\n", fixef(m)$cond))
"""


def test_a_singular_fit_steps_down_and_equals_glmmtmb(singular, tmp_path):
    base, report, md = singular
    shooter = model(report, "shooter/hit")
    steps = [(a["step"], a["kept"], " ".join(a["problems"])) for a in shooter["attempts"]]
    assert steps[0][0] == "maximal" and not steps[0][1] and "singular" in steps[0][2], steps
    assert shooter["kept"] == "random intercept" and steps[-1][1], steps
    assert shooter["formula"] == "hit ~ condition + (1 | participant)"
    assert "The maximal model, `hit ~ condition + (1 + condition | participant)`, was dropped: singular" in md
    assert "The random intercept model is kept." in md
    levels = ", ".join(f'"{c}"' for c in shooter["conditions"])
    theirs = [float.fromhex(v) for v in run_r(GLMMTMB.replace("LEVELS", levels),
                                              (base / "export" / "shots.csv").read_text(), tmp_path, "glmmTMB",
                                              INSTALL)]
    ours = [f["estimate"] for f in shooter["fixed_effects"]]
    assert ours == pytest.approx(theirs, abs=1e-3)


def test_overdispersed_counts_become_negative_binomial(singular):
    _, report, md = singular
    green = model(report, "matches/green_hits")
    assert green["engine"] == "negbin" and green["dispersion"]["overdispersed"]
    assert green["dispersion"]["ratio"] > 1.5 and green["ratio"] == "rate ratio"
    assert "Poisson dispersion: Pearson χ² = " in md and "negative binomial GLMM (lme4::glmer.nb, θ = " in md


@pytest.fixture(scope="module")
def awkward(tmp_path_factory):
    rscript()
    base = tmp_path_factory.mktemp("awkward")
    rng = np.random.default_rng(3)
    trials = simulate_hits(rng, {"warp15to120": 0.5, "conv120": 0.8}, 0.5, 0.0, 6, 20)
    trials = [(p, g, c, True if (p, c) == ("P1", "conv120") else h) for p, g, c, h in trials
              if (p, c) != ("P6", "conv120")]
    trials += [(p, "click", c, True) for p in ("P1", "P2") for c in ("conv60", "conv15") for _ in range(5)]
    listed = [("shooter", c) for c in ("warp15to120", "conv120", "conv15")] + [("click", "conv60"), ("click", "conv15")]
    write_export(base / "export", trials, listed=listed)
    report, md = analyse(base / "export", base / "report")
    return base, report, md


def test_separation_a_missing_condition_and_all_hits_are_sentences(awkward):
    _, report, md = awkward
    shooter = model(report, "shooter/hit")
    assert shooter["fitted"]
    assert ("conditions.csv lists conv15 for the shooter, but no participant has trials of it: not a level of the "
            "model.") in md
    assert "Separation: in 1 participant-and-condition cell every one of the trials went the same way (P1 hit every " \
           "one in conv120 (20 of 20))." in md
    assert "(P6 lacks conv120); the model uses each participant's other conditions." in md
    click = model(report, "click/hit")
    assert not click["fitted"] and click["notes"] == ["Every one of the 20 trials is a hit: there is no variation to "
                                                      "model."]


def test_without_r_the_report_says_what_to_install(awkward):
    base, _, _ = awkward
    out = base / "no-r"
    report, md = analyse(base / "export", out, "--rscript", base / "no-such-Rscript")
    sentence = report["mixed_models"]["left_out"]
    assert sentence.startswith(f"Left out: R's Rscript ({base / 'no-such-Rscript'}) was not found; install R and its "
                               "packages with `apt-get install r-base-core r-cran-lme4 r-cran-emmeans r-cran-ordinal")
    assert md.count(sentence) == 1
    assert "## Shooter: hit rates, the paper's own analysis" in md and (out / "mixed_models.R").is_file()
    assert not (out / "mixed_models.json").exists()


def test_without_rs_packages_the_report_names_them(awkward, monkeypatch):
    """R without its site library (where Debian's r-cran-* packages live): the script's own check."""
    base, _, _ = awkward
    monkeypatch.setenv("R_LIBS_SITE", str(base / "no-library"))
    monkeypatch.setenv("R_LIBS_USER", str(base / "no-library"))
    report, md = analyse(base / "export", base / "no-packages")
    sentence = report["mixed_models"]["left_out"]
    assert sentence == ("Left out: R lacks the package(s) lme4, emmeans, ordinal, jsonlite; install them with: apt-get "
                        "install r-cran-lme4 r-cran-emmeans r-cran-ordinal r-cran-jsonlite (Debian's packages), then "
                        "re-run the report or `Rscript mixed_models.R` beside it.")
    assert md.count(sentence) == 1 and "## Shooter: hit rates, the paper's own analysis" in md


def test_one_participant_and_no_trial_rows_are_sentences(tmp_path):
    rscript()
    rng = np.random.default_rng(5)
    trials = simulate_hits(rng, {"conv60": 0.5, "conv15": 0.1}, 0.5, 0.0, 3, 10)
    write_export(tmp_path / "one", trials, kinds={"P2": "bot", "P3": "bot"})
    report, md = analyse(tmp_path / "one", tmp_path / "one-report")
    assert model(report, "shooter/hit")["notes"] == [
        "Only one participant (P1) has trials here: a mixed model needs several to estimate how participants vary, "
        "so none is fitted."]
    assert "Fitted to the people only" in md
    write_export(tmp_path / "none", trials)
    write(tmp_path / "none" / "shots.csv", [SHOTS_HEADER])
    report, md = analyse(tmp_path / "none", tmp_path / "none-report")
    assert report["mixed_models"]["models"] == []
    assert "shots.csv has no trial rows of the scored phase: no per-trial models." in md


def test_a_rating_outside_its_scale_is_refused(tmp_path, capsys):
    trials = simulate_hits(np.random.default_rng(1), {"conv60": 0.5, "conv15": 0.1}, 0.5, 0.0, 2, 5)
    write_export(tmp_path, trials)
    write(tmp_path / "answers.csv", [ANSWERS_HEADER, "P1,P1.s,shooter,test,true,0,conv60,0,smooth,likert,Smooth,9,,"
                                                     "key,1,7,human"])
    code, _ = run_in_process(tmp_path, tmp_path / "out", mixed_models=True)
    assert code == 1
    err = capsys.readouterr().err.strip()
    assert err == (f"analyze: {tmp_path / 'answers.csv'}: line 2, column 'value' is 9, outside the question's scale 1 "
                   "to 7 (its scale_min and scale_max).")


def test_install_deps_installs_the_model_packages():
    """The packages the report's sentence names, and glmmTMB for this file's independent fit."""
    wanted = {"r-base-core", "r-cran-lme4", "r-cran-emmeans", "r-cran-ordinal", "r-cran-jsonlite", "r-cran-glmmtmb"}
    assert wanted <= installed_by_deps(), wanted - installed_by_deps()
    assert set(mixed_models.INSTALL.split()[2:]) == wanted - {"r-cran-glmmtmb"}
