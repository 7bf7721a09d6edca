"""How many participants a study needs for the report's two-sided exact sign test (α = 0.05) to
find a pilot's hit-rate difference with 80 % power.

Model: participants are independent; each one's difference is tied with probability t, and
when not tied it is positive with probability p+. Both are taken from the pilot (its tie share
and its share of positive among untied participants) as if they were the true values. With n
participants the untied count M is Binomial(n, 1 − t); given M = m the report drops the ties and
rejects when the two-sided p of the positive count is ≤ α, i.e. when that count is ≤ c_m or
≥ m − c_m. So

    power(n) = Σ_m Binom(m; n, 1 − t) · [P(X ≤ c_m) + P(X ≥ m − c_m)],  X ~ Binomial(m, p+).

Exact power saw-tooths in n (c_m grows in steps, so one more participant can lower it), hence
"needed" is the smallest n whose power and every larger n's up to the cap reach the target.
"""
import functools

import numpy as np
import scipy.stats

from .stats import sign_test_two_sided_p

ALPHA = 0.05
TARGET_POWER = 0.8
CAP = 1000


def critical_counts(cap=CAP, alpha=ALPHA):
    """c_m for m = 0..cap: the largest count whose two-sided sign-test p is ≤ alpha; −1 when none is.

    The p values are the report's own (stats.sign_test_two_sided_p). c_m never falls as m grows
    (one more flip only lowers P(X ≤ k)), so each m starts from the previous c. A p of exactly
    0.05 cannot occur (p is a multiple of 2^−m), so at α = 0.05 "≤" and "<" agree.
    """
    return _critical_counts(cap, alpha)  # one cache entry however the caller passes the arguments


@functools.lru_cache(maxsize=None)
def _critical_counts(cap, alpha):  # about 1500 binomtest calls: seconds, so once per process
    c, counts = -1, []
    for m in range(cap + 1):
        while sign_test_two_sided_p(c + 1, m) <= alpha:
            c += 1
        counts.append(c)
    counts = np.array(counts)
    counts.setflags(write=False)  # shared by every caller through the cache
    return counts


def fewest_untied(cap=CAP, alpha=ALPHA):
    """The fewest untied participants that can reject at all (6 at α = 0.05: 2 · 0.5^6 < 0.05)."""
    return int(np.argmax(critical_counts(cap, alpha) >= 0))


def power_curve(p_plus, tie_share, cap=CAP, alpha=ALPHA):
    """power(n) for n = 0..cap (index n) of the two-sided sign test, as in the module docstring."""
    m = np.arange(cap + 1)
    c = critical_counts(cap, alpha)
    # P(reject | m untied); c = −1 gives cdf(−1) = 0 and sf(m) = 0, i.e. no rejection.
    reject = scipy.stats.binom.cdf(c, m, p_plus) + scipy.stats.binom.sf(m - c - 1, m, p_plus)
    # Row n, column m: P(m of n participants untied); zero for m > n, where scipy's binomial
    # density divides by zero on its way to that 0.
    with np.errstate(divide="ignore"):
        untied = scipy.stats.binom.pmf(m[None, :], m[:, None], 1.0 - tie_share)
    return untied @ reject


def sample_size(positive, negative, ties, cap=CAP, alpha=ALPHA, target=TARGET_POWER):
    """The planning answer for one pair from its pilot sign counts (a > b, a < b, tied).

    needed: smallest n with power ≥ target there and at every larger n up to cap; first: where
    power first reaches target; both None with `note` saying why (no pilot, no difference to
    detect, or not reached by cap).
    """
    participants = positive + negative + ties
    untied = positive + negative
    result = {"pilot_participants": participants, "p_plus": positive / untied if untied else None,
              "tie_share": ties / participants if participants else None,
              "extreme": untied > 0 and positive in (0, untied), "needed": None, "first": None,
              "power_at_needed": None, "note": None, "alpha": alpha, "target_power": target, "cap": cap}
    if participants == 0:
        result["note"] = "no participant has both conditions"
    elif untied == 0 or 2 * positive == untied:
        result["note"] = "no difference to detect"
    else:
        power = power_curve(result["p_plus"], result["tie_share"], cap, alpha)
        short = np.flatnonzero(power < target)  # n = 0 is always short: power(0) = 0
        if short[-1] == cap:
            result["note"] = f"more than {cap}"
        else:
            needed = int(short[-1]) + 1
            result.update(needed=needed, first=int(np.argmax(power >= target)),
                          power_at_needed=float(power[needed]))
    return result
