"""The signed-rank test on tied data: exact by the conditional distribution with mid-ranks,
checked against enumerating every sign pattern; the normal approximation beyond the exact
limit against R's wilcox.test formula (tie-corrected variance, continuity correction)."""
import itertools
import math
import os
import sys

import numpy as np
import pytest
import scipy.stats

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))
from warplab_analysis import stats  # noqa: E402


def enumerated_p(d):
    """Every one of the 2^n sign patterns of the non-zero |d|'s mid-ranks, equally likely."""
    d = np.asarray([x for x in d if x != 0], dtype=float)
    if len(d) == 0:
        return 1.0
    ranks = scipy.stats.rankdata(np.abs(d))
    mean = ranks.sum() / 2
    observed = abs(ranks[d > 0].sum() - mean)
    hits = sum(abs(sum(r for r, s in zip(ranks, signs) if s) - mean) >= observed - 1e-9
               for signs in itertools.product((0, 1), repeat=len(d)))
    return hits / 2 ** len(d)


@pytest.mark.parametrize("d", [
    [1, 1, 2, 2, 3, 3, -1, 4],  # ties among the positive and across signs
    [0.5, 0.5, 0.5, -0.5],  # every |d| tied: the sign test's p
    [2, -2, 0, 0, 3, 1, 1, -4, 5, 5],  # zeros dropped
    [1, 2, 3, 4, 5],  # no ties: 2 / 2^5
])
def test_exact_p_is_the_enumerated_conditional_p(d):
    p, method = stats.wilcoxon_signed_rank(d)
    assert method == "exact"
    assert p == pytest.approx(enumerated_p(d), rel=1e-12)


def test_ties_are_not_judged_by_the_untied_table():
    # Four equal |d|, one positive: mid-ranks 2.5 each, so T+ = 2.5 k with k ~ Binomial(4, 1/2):
    # p = 1 - P(k = 2) = 10/16. The untied table (scipy 1.10's exact mode) said 0.375.
    p, _ = stats.wilcoxon_signed_rank([1, -1, -1, -1])
    assert p == pytest.approx(10 / 16, rel=1e-12)


def test_beyond_the_exact_limit_the_normal_approximation_is_rs():
    rng = np.random.default_rng(7)
    d = rng.integers(-5, 6, size=stats.WILCOXON_EXACT_LIMIT + 40).astype(float)
    p, method = stats.wilcoxon_signed_rank(d)
    assert method == "normal"
    nz = d[d != 0]
    ranks = scipy.stats.rankdata(np.abs(nz))
    n = len(nz)
    z = (abs(ranks[nz > 0].sum() - n * (n + 1) / 4) - 0.5) / math.sqrt(np.sum(ranks ** 2) / 4)
    assert p == pytest.approx(2 * scipy.stats.norm.sf(z), rel=1e-12)


def test_no_difference_left_is_p_one():
    assert stats.wilcoxon_signed_rank([0, 0, 0]) == (1.0, "exact")
