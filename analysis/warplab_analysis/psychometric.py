"""Psychometric functions of a forced-choice task, and their maximum-likelihood fit.

The function is the one the adaptive procedures use (adaptive/psychometric.h):

    p(x) = guess + (1 - guess - lapse) F(slope * (u(x) - u(threshold)))

with u the stimulus or its natural log, F the logistic 1 / (1 + e^-z) or the Weibull (Gumbel)
1 - exp(-e^z) -- on the log scale the classic Weibull of the stimulus, 1 - exp(-(x / t)^slope).
With the lapse fixed the fit is a generalised linear model in eta = a + b u, a = -slope u(t) and
b = slope: R's glm with the psyphy package's link mafc.logit(m) (logistic) or mafc.cloglog(m)
(Weibull) for guess = 1/m, which analysis/tests/test_psychometric.py checks it against. It is
found by Fisher scoring, as glm finds it, to a tighter tolerance, but near the maximum by Newton's
steps: with a lapse the link is not canonical, and on a session's few trials scoring (glm's too)
can circle the maximum without ever settling.
"""
import math

import numpy as np

SHAPES = ("logistic", "weibull")
SCALES = ("linear", "log")


def _u(x, scale):
    x = np.asarray(x, dtype=float)
    if scale == "linear":
        return x
    if np.any(x <= 0):
        raise ValueError("a psychometric function on the log scale needs stimuli above 0")
    return np.log(x)


def _cdf_and_density(z, shape):
    """F(z) and F'(z), written so that no large exponent overflows."""
    z = np.asarray(z, dtype=float)
    if shape == "logistic":
        f = 0.5 * (1.0 + np.tanh(0.5 * z))
        return f, f * (1.0 - f)
    ez = np.exp(np.minimum(z, 700.0))
    return -np.expm1(-ez), ez * np.exp(-ez)


def _clip(p):
    """p kept off 0 and 1, where a log-likelihood term is infinite (np.clip's result, without
    its overhead on the few numbers of a fit's levels)."""
    return np.minimum(np.maximum(p, 1e-300), 1.0 - 1e-16)


def _density_slope(z, density, shape):
    """F''(z), from z and F'(z)."""
    z = np.asarray(z, dtype=float)
    if shape == "logistic":
        return density * -np.tanh(0.5 * z)  # F' (1 - 2F)
    return density * -np.expm1(np.minimum(z, 700.0))  # F' (1 - e^z)


def probability(x, threshold, slope, lapse=0.0, guess=0.5, shape="weibull", scale="log"):
    """p(correct) at stimulus x (a number or an array)."""
    z = slope * (_u(x, scale) - _u(threshold, scale))
    return guess + (1.0 - guess - lapse) * _cdf_and_density(z, shape)[0]


def _z_at(percent_correct, lapse, guess, shape):
    """F's argument z at which the function gives percent_correct % correct: F^-1(q), with q the
    share of the way from the guess rate to 1 - lapse."""
    q = (percent_correct / 100.0 - guess) / (1.0 - guess - lapse)
    if not 0.0 < q < 1.0:
        raise ValueError(f"the function never reaches {percent_correct} % correct "
                         f"(guess rate {guess}, lapse {lapse})")
    return math.log(q / (1.0 - q)) if shape == "logistic" else math.log(-math.log1p(-q))


def stimulus_at(percent_correct, threshold, slope, lapse=0.0, guess=0.5, shape="weibull", scale="log"):
    """The stimulus at which the function gives percent_correct % correct."""
    u = float(_u(threshold, scale)) + _z_at(percent_correct, lapse, guess, shape) / slope
    return u if scale == "linear" else math.exp(u)


def location_at(percent_correct, stimulus, slope, lapse=0.0, guess=0.5, shape="weibull", scale="log"):
    """The function's threshold parameter (its location) that puts percent_correct % correct at
    `stimulus`: stimulus_at's inverse in its threshold. stimulus_at solves
    slope (u(x) - u(t)) = z for u(x); solved for u(t) instead, u(t) = u(x) - z / slope, a shift on
    the function's scale -- t = x - z / slope on the linear scale, t = x e^(-z / slope) on the log
    scale. Useful where a procedure reports the stimulus at its percent correct (QUEST+'s
    posterior mean) and the function is wanted."""
    u = float(_u(stimulus, scale)) - _z_at(percent_correct, lapse, guess, shape) / slope
    return u if scale == "linear" else math.exp(u)


def fit(stimuli, correct, guess=0.5, lapse=0.0, shape="weibull", scale="log", tolerance=1e-12, max_steps=200):
    """The maximum-likelihood threshold and slope of the trials (stimulus, correct 0/1), lapse fixed.

    Returns a dict: threshold, slope, intercept and coefficient (a and b of eta = a + b u, as R's
    glm reports them), log_likelihood, steps. Raises ValueError when there is nothing to fit (fewer
    than two distinct levels), when the likelihood has no maximum (every answer right above a
    level and wrong below it: the slope runs off to infinity) or when scoring does not settle.
    """
    if shape not in SHAPES or scale not in SCALES:
        raise ValueError(f"shape must be one of {SHAPES} and scale one of {SCALES}")
    every_u = _u(stimuli, scale)
    every_y = np.asarray(correct, dtype=float)
    if len(every_u) != len(every_y) or len(np.unique(every_u)) < 2:
        raise ValueError("a psychometric fit needs trials at two levels or more")
    # Binomial counts per level: the same likelihood as trial by trial, a term per level.
    u, at = np.unique(every_u, return_inverse=True)
    n = np.bincount(at).astype(float)
    y = np.bincount(at, weights=every_y)
    c = 1.0 - guess - lapse
    design = np.column_stack([np.ones_like(u), u])

    def log_likelihood(b):
        p = guess + c * _cdf_and_density(design @ b, shape)[0]
        p = _clip(p)
        return float(np.sum(y * np.log(p) + (n - y) * np.log1p(-p)))

    # Scoring from a poor start can leap to where every trial is certain and learn nothing: it
    # starts from the best of a coarse grid of locations within the levels and slopes across them.
    t, b = np.meshgrid(np.linspace(u.min(), u.max(), 25), np.geomspace(0.5, 200.0, 25) / float(np.ptp(u)))
    starts = np.column_stack([-(b * t).ravel(), b.ravel()])
    p = _clip(guess + c * _cdf_and_density(starts @ design.T, shape)[0])
    beta = starts[int(np.argmax(np.log(p) @ y + np.log1p(-p) @ (n - y)))]
    current = log_likelihood(beta)

    def at_a_step(b):
        fitted = guess + c * _cdf_and_density(design @ b, shape)[0]
        return bool(np.all((fitted - guess < 1e-6) | (1.0 - lapse - fitted < 1e-6)))

    for step in range(1, max_steps + 1):
        eta = design @ beta
        f, density = _cdf_and_density(eta, shape)
        p = _clip(guess + c * f)
        dp = c * density
        per_p = y / p - (n - y) / (1.0 - p)  # d log-likelihood / dp at each level
        score = design.T @ (per_p * dp)
        # Newton's step where the likelihood curves down in every direction (near its maximum),
        # else Fisher scoring's (glm's). With a lapse the link is not canonical, and scoring's
        # expected information can differ enough from the curvature that it circles the maximum,
        # each step a little longer than the last, and never settles.
        observed = (y / (p * p) + (n - y) / ((1.0 - p) ** 2)) * dp * dp - per_p * c * _density_slope(eta, density,
                                                                                                     shape)
        information = design.T @ (design * observed[:, None])
        # Positive definite: a 2 x 2 matrix with a positive corner and determinant.
        if not (information[0, 0] > 0.0 and information[0, 0] * information[1, 1] > information[0, 1] ** 2):
            weights = n * dp * dp / (p * (1.0 - p))
            information = design.T @ (design * weights[:, None])
        # Least squares rather than an inverse: where only one level's trials still carry weight
        # (a slope near a step) the information is all but singular.
        move = np.linalg.lstsq(information, score, rcond=None)[0]
        # The step, halved while it would lower the likelihood.
        for _ in range(60):
            trial = beta + move
            value = log_likelihood(trial)
            if value >= current - 1e-12:
                break
            move /= 2.0
        beta, previous, current = trial, current, value
        # Every fitted probability at the guess rate or at 1 - lapse: a step between two levels, which
        # only an infinite slope reaches. Checked once the likelihood stops rising, so that a fit
        # running off towards the step stops there rather than after max_steps.
        if abs(beta[1]) > 1e6 or (abs(current - previous) < 1e-12 and at_a_step(beta)):
            raise ValueError("the psychometric fit has no maximum: its likelihood keeps rising towards a step "
                             "between two levels, which only an infinite slope reaches")
        if np.max(np.abs(move)) < tolerance * (1.0 + np.max(np.abs(beta))) and abs(current - previous) < 1e-12:
            break
    else:
        raise ValueError(f"the psychometric fit did not converge in {max_steps} steps")
    a, b = float(beta[0]), float(beta[1])
    location = -a / b
    return {"threshold": location if scale == "linear" else math.exp(location), "slope": b,
            "intercept": a, "coefficient": b, "log_likelihood": current, "steps": step}


def bootstrap_interval(stimuli, correct, percent_correct, resamples=1000, seed=1, **function):
    """The 95 % percentile interval of the stimulus at percent_correct, over fits of trials drawn
    with replacement (resamples that cannot be fitted, or never reach it, are left out and
    counted). Returns (low, high, fitted, left_out)."""
    stimuli, correct = np.asarray(stimuli, dtype=float), np.asarray(correct, dtype=float)
    rng = np.random.default_rng(seed)
    lapse, guess = function.get("lapse", 0.0), function.get("guess", 0.5)
    shape, scale = function.get("shape", "weibull"), function.get("scale", "log")
    values, left_out = [], 0
    for _ in range(resamples):
        pick = rng.integers(0, len(stimuli), size=len(stimuli))
        try:
            f = fit(stimuli[pick], correct[pick], **function)
            values.append(stimulus_at(percent_correct, f["threshold"], f["slope"], lapse, guess, shape, scale))
        except (ValueError, np.linalg.LinAlgError):
            left_out += 1
    if not values:
        return math.nan, math.nan, 0, left_out
    low, high = np.percentile(values, [2.5, 97.5])
    return float(low), float(high), len(values), left_out
