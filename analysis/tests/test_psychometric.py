"""The psychometric fit against R's glm with psyphy's forced-choice links, which share no code with
ours: mafc.logit(2) and mafc.cloglog(2) with no lapse, logit.2asym and cloglog.2asym with a fixed
one. The trials travel as hexadecimal floats, so R fits the very doubles Python does."""
import os
import sys

import numpy as np
import pytest
import scipy.optimize

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))
from warplab_analysis import psychometric  # noqa: E402
from r_support import run_r  # noqa: E402

INSTALL = ("run scripts/install-deps.sh (it installs r-base-core and r-cran-psyphy, which this test needs to "
           "check the psychometric fit against R)")

R_SCRIPT = r"""
suppressPackageStartupMessages(library(psyphy))
for (line in readLines(commandArgs(trailingOnly = TRUE)[1])) {
  parts <- strsplit(line, " ", fixed = TRUE)[[1]]
  lapse <- as.numeric(parts[2])
  link <- switch(parts[1],
    logistic = if (lapse == 0) mafc.logit(2) else logit.2asym(g = 0.5, lam = lapse),
    weibull = if (lapse == 0) mafc.cloglog(2) else cloglog.2asym(g = 0.5, lam = lapse))
  u <- as.numeric(strsplit(parts[3], ",", fixed = TRUE)[[1]])
  y <- as.numeric(strsplit(parts[4], ",", fixed = TRUE)[[1]])
  # glm's own start can leave the .2asym links' range and diverge, and scoring from a poor one
  # can stall: it starts from the likeliest of a grid of locations and slopes over the levels.
  loglik <- function(b) { p <- link$linkinv(b[1] + b[2] * u); sum(dbinom(y, 1, p, log = TRUE)) }
  grid <- expand.grid(t = seq(min(u), max(u), length.out = 25),
                      s = exp(seq(log(0.5), log(200), length.out = 25)) / diff(range(u)))
  starts <- lapply(seq_len(nrow(grid)), function(i) c(-grid$s[i] * grid$t[i], grid$s[i]))
  start <- starts[[which.max(sapply(starts, loglik))]]
  m <- glm(cbind(y, 1 - y) ~ u, family = binomial(link), start = start,
           control = glm.control(epsilon = 1e-15, maxit = 500))
  cat(sprintf("%a %a\n", coef(m)[1], coef(m)[2]))
}
"""

LEVELS = np.array([3.0, 6.0, 9.0, 12.0, 18.0, 24.0, 36.0, 48.0])


def trials(rng, shape, scale, lapse, per_level, threshold=14.0, slope=2.5):
    x = np.repeat(LEVELS, per_level)
    if scale == "linear":
        slope = slope / 10.0  # per ms rather than per log unit
    p = psychometric.probability(x, threshold, slope, lapse, 0.5, shape, scale)
    return x, (rng.random(len(x)) < p).astype(float)


def cases():
    rng = np.random.default_rng(20261204)
    out = []
    for shape in psychometric.SHAPES:
        for scale in psychometric.SCALES:
            for lapse in (0.0, 0.03):
                for per_level in (20, 50):
                    x, y = trials(rng, shape, scale, lapse, per_level)
                    out.append((shape, scale, lapse, x, y))
    return out


def r_coefficients(batch, tmp_path):
    data = "".join(f"{shape} {lapse!r} {','.join(float(v).hex() for v in u)} {','.join(str(int(v)) for v in y)}\n"
                   for shape, lapse, u, y in batch)
    rows = [line.split() for line in run_r(R_SCRIPT, data, tmp_path, "psyphy", INSTALL)]
    assert len(rows) == len(batch), rows
    return [(float.fromhex(a), float.fromhex(b)) for a, b in rows]


def test_the_fit_is_rs_glm_with_psyphys_links(tmp_path):
    batch, ours = [], []
    for shape, scale, lapse, x, y in cases():
        f = psychometric.fit(x, y, lapse=lapse, shape=shape, scale=scale)
        u = x if scale == "linear" else np.log(x)
        batch.append((shape, lapse, u, y))
        ours.append((f["intercept"], f["coefficient"]))
    theirs = r_coefficients(batch, tmp_path)
    assert len(ours) == 16
    for (shape, scale, lapse, x, _), (a, b), (ra, rb) in zip(cases(), ours, theirs):
        where = f"{shape} on the {scale} scale, lapse {lapse}, {len(x)} trials"
        assert a == pytest.approx(ra, abs=1e-6, rel=1e-6), where
        assert b == pytest.approx(rb, abs=1e-6, rel=1e-6), where


def likelihood(shape, lapse, u, y, a, b):
    """The log-likelihood written out again, with the functions in their textbook form."""
    z = a + b * u
    f = 1.0 / (1.0 + np.exp(-z)) if shape == "logistic" else 1.0 - np.exp(-np.exp(z))
    p = np.clip(0.5 + (0.5 - lapse) * f, 1e-300, 1.0 - 1e-16)
    return float(np.sum(y * np.log(p) + (1.0 - y) * np.log1p(-p)))


def test_with_a_lapse_the_fit_settles_at_the_maximum_on_a_sessions_trials():
    """With a lapse the link is not canonical, and Fisher scoring -- R's glm too -- can circle the
    maximum of a session's few trials without settling. Nelder and Mead's simplex (scipy), which
    shares no code with the fit, from the fit's answer and from the function the trials were drawn
    from, finds no likelier point."""
    rng = np.random.default_rng(20261205)
    fitted = 0
    for shape in psychometric.SHAPES:
        for scale in psychometric.SCALES:
            for _ in range(5):
                x, y = trials(rng, shape, scale, 0.02, 8)
                u = x if scale == "linear" else np.log(x)
                try:
                    f = psychometric.fit(x, y, lapse=0.02, shape=shape, scale=scale)
                except ValueError as e:
                    assert "no maximum" in str(e)  # a step between two levels: the slope runs off
                    continue
                fitted += 1
                truth = 2.5 / 10.0 if scale == "linear" else 2.5
                starts = [(f["intercept"], f["coefficient"]), (-truth * (14.0 if scale == "linear" else np.log(14.0)),
                                                                truth)]
                best = max(-scipy.optimize.minimize(lambda b: -likelihood(shape, 0.02, u, y, *b), start,
                                                    method="Nelder-Mead",
                                                    options={"xatol": 1e-10, "fatol": 1e-13, "maxiter": 20000}).fun
                           for start in starts)
                assert f["log_likelihood"] >= best - 1e-9, (shape, scale)
                assert f["log_likelihood"] == pytest.approx(likelihood(shape, 0.02, u, y, f["intercept"],
                                                                       f["coefficient"]), abs=1e-9)
    assert fitted >= 15
    # Ten trials at each of eight levels that scoring circled for ever ("did not converge").
    x = np.repeat(np.arange(1.0, 9.0), 10)
    y = np.concatenate([np.r_[np.ones(k), np.zeros(10 - k)] for k in (6, 4, 7, 8, 10, 10, 10, 10)])
    f = psychometric.fit(x, y, lapse=0.02)
    simplex = scipy.optimize.minimize(lambda b: -likelihood("weibull", 0.02, np.log(x), y, *b), (-5.0, 3.0),
                                      method="Nelder-Mead", options={"xatol": 1e-10, "fatol": 1e-13, "maxiter": 20000})
    assert (f["intercept"], f["coefficient"]) == pytest.approx(tuple(simplex.x), rel=1e-6)


def test_the_fit_recovers_a_known_function_and_its_interval_holds_it():
    rng = np.random.default_rng(7)
    x, y = trials(rng, "weibull", "log", 0.0, 250)
    f = psychometric.fit(x, y)
    assert f["threshold"] == pytest.approx(14.0, rel=0.05)
    assert f["slope"] == pytest.approx(2.5, rel=0.15)
    truth = psychometric.stimulus_at(75.0, 14.0, 2.5)
    low, high, fitted, left_out = psychometric.bootstrap_interval(x, y, 75.0, resamples=200, seed=3)
    assert fitted + left_out == 200 and fitted >= 190
    assert low < truth < high
    assert high / low < 1.3, "2000 trials pin the 75 % point down"
    # Seeded: the same interval again.
    assert psychometric.bootstrap_interval(x, y, 75.0, resamples=200, seed=3) == (low, high, fitted, left_out)


def test_the_function_and_its_inverse_agree():
    for shape in psychometric.SHAPES:
        for scale in psychometric.SCALES:
            for pc in (55.0, 70.7, 75.0, 90.0):
                x = psychometric.stimulus_at(pc, 12.0, 2.0, 0.04, 0.5, shape, scale)
                assert psychometric.probability(x, 12.0, 2.0, 0.04, 0.5, shape, scale) == pytest.approx(pc / 100)
    # The classic Weibull of the stimulus, written out.
    assert psychometric.probability(7.0, 10.0, 2.5, 0.03) == pytest.approx(
        0.5 + 0.47 * (1 - np.exp(-(7.0 / 10.0) ** 2.5)), rel=1e-14)
    with pytest.raises(ValueError):
        psychometric.stimulus_at(97.0, 12.0, 2.0, 0.04)
    with pytest.raises(ValueError):
        psychometric.fit([5.0, 5.0], [1, 0])
    with pytest.raises(ValueError, match="keeps rising towards a step"):
        psychometric.fit([2.0, 2.0, 4.0, 4.0, 8.0, 8.0], [0, 0, 0, 1, 1, 1])


def test_install_deps_installs_psyphy():
    script = open(os.path.join(os.path.dirname(__file__), "..", "..", "scripts", "install-deps.sh")).read()
    block = script.split("packages=(", 1)[1].split("\n)", 1)[0]
    listed = {word for line in block.splitlines() for word in line.split("#", 1)[0].split()}
    assert "r-cran-psyphy" in listed
