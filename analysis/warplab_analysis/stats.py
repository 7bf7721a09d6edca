"""The tests: exact sign tests on hit rates (seed 004 §7.1), type-7 quartiles (seed 004 Table 3),
and the click game's paired tests and repeated-measures ANOVA (seed 000 §8, Table 2).

Sign-test tails are sums of binomial coefficients over 2^n in exact rational arithmetic, so
they equal R's binom.test to the last bit or two (the thesis quotes R's digits); signs and
ties of hit-rate differences are decided on integers, hits_a·shots_b against hits_b·shots_a,
so 2/4 against 3/6 is a tie however floating point rounds the two rates.
"""
import math
import warnings
from fractions import Fraction

import numpy as np
import scipy.stats

QUARTILE_KEYS = ("min", "q25", "median", "q75", "max")


def sign_test_two_sided_p(positive, n):
    """Two-sided p of `positive` successes in n fair coin flips: scipy's binomtest; 1.0 when n = 0.

    On its own so that planning.py's power computation rejects exactly where the report's test does.
    """
    if n == 0:
        return 1.0
    return float(scipy.stats.binomtest(positive, n, 0.5, alternative="two-sided").pvalue)


def sign_test_p(positive, n):
    """(p_greater, p_less, p_two_sided) of `positive` successes in n fair coin flips; all 1.0 when n = 0."""
    if n == 0:
        return 1.0, 1.0, 1.0
    total = 2 ** n
    p_greater = float(Fraction(sum(math.comb(n, k) for k in range(positive, n + 1)), total))
    p_less = float(Fraction(sum(math.comb(n, k) for k in range(0, positive + 1)), total))
    return p_greater, p_less, sign_test_two_sided_p(positive, n)


def quartiles(values):
    """min, 25 %, median, 75 %, max by R's default (type 7, numpy's 'linear'); None without values."""
    if len(values) == 0:
        return None
    q = np.percentile(np.asarray(values, dtype=float), [0, 25, 50, 75, 100])
    return dict(zip(QUARTILE_KEYS, (float(v) for v in q)))


def rate_difference(counts_a, counts_b):
    """(sign, hit rate a − b) of two (hits, shots) pairs; the sign, and 0.0 for a tie, from integers."""
    (hits_a, shots_a), (hits_b, shots_b) = counts_a, counts_b
    left, right = hits_a * shots_b, hits_b * shots_a
    if left == right:
        return 0, 0.0
    return (1 if left > right else -1), hits_a / shots_a - hits_b / shots_b


def hit_rate_sign_test(game, a, b, participants):
    """Sign test of hit rate a − b over the participants with both conditions, in the order given, and the
    sample size a study would need to find this difference (planning.sample_size, this data as pilot).

    participants: {participant: {condition: (hits, shots)}}; `differences` keeps its order.
    """
    differences = {}
    signs = {1: 0, -1: 0, 0: 0}
    for participant, rates in participants.items():
        if a in rates and b in rates:
            sign, differences[participant] = rate_difference(rates[a], rates[b])
            signs[sign] += 1
    positive, negative, ties = signs[1], signs[-1], signs[0]
    n = positive + negative
    p_greater, p_less, p_two_sided = sign_test_p(positive, n)
    from . import planning  # here, not at the top: planning builds on this module's sign test
    return {
        "game": game, "a": a, "b": b, "n": n, "positive": positive, "negative": negative, "ties": ties,
        "p_greater": p_greater, "p_less": p_less, "p_two_sided": p_two_sided,
        "diff_quartiles": quartiles(list(differences.values())),
        "participants": len(differences), "differences": differences,
        "planning": planning.sample_size(positive, negative, ties),
    }


# Up to this many non-zero differences the signed-rank p is the exact conditional one; the
# distribution has at most n (n + 1) + 1 points in half-ranks, so this is milliseconds.
WILCOXON_EXACT_LIMIT = 200


def wilcoxon_signed_rank(differences):
    """Two-sided p of Wilcoxon's signed-rank test and how it was found ("exact" or "normal").

    Zero differences are dropped (Wilcoxon's own rule); p = 1 when none remain. Tied |d| get
    their mid-rank, and the p is then that of the exact conditional distribution: given the
    ranks, each of the 2^n sign patterns is equally likely under the null, and p is the share
    whose statistic T+ (the sum of the positive differences' ranks) lies at least as far from
    its mean as the observed one. Counted in half-ranks, so every T+ is an integer. scipy's
    exact table assumes untied ranks and is wrong for mid-ranks; R's coin and exactRankTests
    compute this distribution. Beyond WILCOXON_EXACT_LIMIT differences: the normal
    approximation with the tie-corrected variance sum(rank^2) / 4 and a continuity correction
    of 1/2, as R's wilcox.test.
    """
    d = np.asarray(differences, dtype=float)
    d = d[d != 0]
    n = len(d)
    if n == 0:
        return 1.0, "exact"
    ranks = scipy.stats.rankdata(np.abs(d))
    if n > WILCOXON_EXACT_LIMIT:
        t = float(ranks[d > 0].sum())
        mean = n * (n + 1) / 4.0
        sd = float(np.sqrt(np.sum(ranks ** 2) / 4.0))
        z = max(abs(t - mean) - 0.5, 0.0) / sd
        return float(min(1.0, 2.0 * scipy.stats.norm.sf(z))), "normal"
    halves = np.rint(2 * ranks).astype(np.int64)
    total = int(halves.sum())
    # dist[k] = P(T+ = k half-ranks), built one difference at a time.
    dist = np.zeros(total + 1)
    dist[0] = 1.0
    reach = 0
    for h in halves:
        new = dist * 0.5
        new[h:reach + h + 1] += 0.5 * dist[:reach + 1]
        dist = new
        reach += int(h)
    observed = int(halves[d > 0].sum())
    # Symmetric about total / 2: as far or farther from it, on either side (integers, so the
    # comparison is exact).
    far = np.abs(2 * np.arange(total + 1) - total) >= abs(2 * observed - total)
    return float(min(1.0, dist[far].sum())), "exact"


def paired_tests(condition_values, reference_values):
    """A condition against the reference on aligned per-participant values: paired t, Wilcoxon, sign test.

    Paired t: None below two pairs; t = 0, p = 1 when every difference is zero; t = ±inf, p = 0
    when the differences are one non-zero constant. Wilcoxon: wilcoxon_signed_rank (zero
    differences dropped, mid-ranks, exact up to WILCOXON_EXACT_LIMIT; which one in
    "wilcoxon_method"). Sign test: exact, ties dropped.
    """
    x = np.asarray(condition_values, dtype=float)
    y = np.asarray(reference_values, dtype=float)
    d = x - y
    n = len(d)
    result = {"n": n, "mean_diff": float(d.mean()) if n else None, "t": None, "df": n - 1 if n >= 2 else None,
              "p_t": None}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # scipy's precision and approximation notices: said in the report
        if n >= 2:
            if np.all(d == 0):
                result["t"], result["p_t"] = 0.0, 1.0
            else:
                test = scipy.stats.ttest_rel(x, y)
                result["t"], result["p_t"] = float(test.statistic), float(test.pvalue)
        result["p_wilcoxon"], result["wilcoxon_method"] = wilcoxon_signed_rank(d)
    positive, negative = int(np.sum(d > 0)), int(np.sum(d < 0))
    result.update(positive=positive, negative=negative, ties=n - positive - negative,
                  p_sign=sign_test_p(positive, positive + negative)[2])
    return result


def rm_anova(values, conditions):
    """One-way repeated-measures ANOVA over `modes` with statsmodels' AnovaRM.

    values: {participant: {condition: value}}; a participant lacking a finite value for any condition is
    dropped. Returns F, df_num, df_den, p, participants, dropped; the statistics are None below
    two participants or two modes. Raises ImportError without statsmodels.
    """
    from statsmodels.stats.anova import AnovaRM
    import pandas as pd

    complete = [p for p, row in values.items() if all(c in row and math.isfinite(row[c]) for c in conditions)]
    result = {"F": None, "df_num": None, "df_den": None, "p": None, "participants": len(complete),
              "dropped": len(values) - len(complete)}
    if len(complete) < 2 or len(conditions) < 2:
        return result
    # Integer codes: the ids and mode names never reach statsmodels' formula machinery.
    frame = pd.DataFrame([{"subject": s, "condition": k, "value": values[p][condition]}
                          for s, p in enumerate(complete) for k, condition in enumerate(conditions)])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        row = AnovaRM(frame, "value", "subject", within=["condition"]).fit().anova_table.iloc[0]
    result.update(F=float(row["F Value"]), df_num=float(row["Num DF"]), df_den=float(row["Den DF"]),
                  p=float(row["Pr > F"]))
    # No residual variation (every participant shifted the same way between conditions, e.g. a
    # scripted player's ratings): F divides by rounding noise. Say infinite (or undefined when
    # the conditions do not differ either) rather than print a 30-digit F.
    y = np.array([[values[p][condition] for condition in conditions] for p in complete], dtype=float)
    grand = y.mean()
    ss_conditions = len(complete) * float(((y.mean(axis=0) - grand) ** 2).sum())
    ss_error = float(((y - y.mean(axis=1, keepdims=True) - y.mean(axis=0) + grand) ** 2).sum())
    if ss_error <= 1e-12 * max(float(((y - grand) ** 2).sum()), 1e-300):
        result.update(F=math.inf, p=0.0) if ss_conditions > 0 else result.update(F=None, p=None)
    return result


def describe(values):
    """mean, sd (ddof = 1), n of the finite values; None where undefined."""
    v = np.asarray([x for x in values if x is not None and math.isfinite(x)], dtype=float)
    return {"mean": float(v.mean()) if len(v) else None, "sd": float(v.std(ddof=1)) if len(v) >= 2 else None,
            "n": int(len(v))}
