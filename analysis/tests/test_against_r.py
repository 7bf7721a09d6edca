"""The report's signed-rank p against R, an implementation that shares no code with ours.

Up to stats.WILCOXON_EXACT_LIMIT non-zero differences: exactRankTests::wilcox.exact(d, exact =
TRUE), the exact conditional distribution given the mid-ranks (Hothorn's shift algorithm, where
ours convolves half-ranks). Beyond it: wilcox.test(d, exact = FALSE, correct = TRUE), the normal
approximation with tie-corrected variance and continuity correction. Both drop zero differences.

The vectors are mostly tied and zero-laden, as the click game's are: a few participants, each
difference one of a condition's mean ratings (1 to 7, over one to three matches) minus another's.
R is run once for the whole batch; the values travel as hexadecimal floats, so R ranks the very
doubles Python does.
"""
import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))
from warplab_analysis import stats  # noqa: E402
from r_support import installed_by_deps, run_r  # noqa: E402

INSTALL = ("run scripts/install-deps.sh (it installs r-base-core and r-cran-exactranktests, which this test "
           "needs to check the report's statistics against R)")

R_SCRIPT = r"""
suppressPackageStartupMessages(library(exactRankTests))
lines <- readLines(commandArgs(trailingOnly = TRUE)[1])
for (line in lines) {
  parts <- strsplit(line, " ", fixed = TRUE)[[1]]
  d <- as.numeric(strsplit(parts[2], ",", fixed = TRUE)[[1]])
  p <- if (parts[1] == "exact") wilcox.exact(d, exact = TRUE)$p.value else
    suppressWarnings(wilcox.test(d, exact = FALSE, correct = TRUE)$p.value)
  cat(sprintf("%a\n", p))
}
"""


def mean_rating_differences(rng, participants):
    """Per participant: mean of 1-3 ratings (1-7) in one condition minus the mean in another."""
    def mean_rating():
        return float(np.mean(rng.integers(1, 8, size=rng.integers(1, 4))))
    return [mean_rating() - mean_rating() for _ in range(participants)]


def vectors():
    rng = np.random.default_rng(20240501)
    handmade = [
        [0.0, 1.0, -1.0, 2.0, 0.0],  # three participants' worth after the zeros go
        [0.5, 0.5, 0.0, -0.5, 1.0, 1.0, 1.0],
        [1.0, 1.0, 1.0],  # every |d| tied, one sign
        [-2.0, -2.0, 0.0, -1.0],
        [1 / 3, 1 / 3, -1 / 3, 0.0, 2 / 3, 2 / 3, -2 / 3, 1.0],
        [5.5 - 4.0, 4.0 - 5.5, 6.0 - 6.0, 7.0 - 5.5],  # observed T+ at the mean: p = 1
        [3.0, -1.0, 2.0, 4.0, -5.0, 6.0],  # no ties
        [0.25] * 12 + [-0.25] * 2 + [0.0] * 3,
    ]
    demo_like = [mean_rating_differences(rng, n) for n in (3, 4, 5, 6, 8, 10, 12, 16, 20, 30, 50)]
    # Large and heavily tied: small integers, a fifth of them zero.
    large = {n: list(rng.integers(-4, 5, size=n).astype(float)) for n in (120, 230, 400)}
    # Exactly at the limit after the zeros go, and one past it.
    at_limit = list(rng.integers(1, 6, size=stats.WILCOXON_EXACT_LIMIT) * rng.choice([-1.0, 1.0],
                                                                                   size=stats.WILCOXON_EXACT_LIMIT))
    past_limit = at_limit + [3.0]
    return handmade + demo_like + list(large.values()) + [at_limit + [0.0, 0.0], past_limit,
                                                          [1.0] * 150 + [-2.0] * 51 + [0.0] * 5]


def r_p_values(batch, tmp_path):
    data = "".join(f"{method} {','.join(float(x).hex() for x in d)}\n" for method, d in batch)
    values = [float.fromhex(line) for line in run_r(R_SCRIPT, data, tmp_path, "exactRankTests", INSTALL)]
    assert len(values) == len(batch), values
    return values


def test_wilcoxon_p_is_rs(tmp_path):
    ours = []
    for d in vectors():
        p, method = stats.wilcoxon_signed_rank(d)
        nonzero = sum(x != 0 for x in d)
        assert method == ("exact" if nonzero <= stats.WILCOXON_EXACT_LIMIT else "normal"), (nonzero, method)
        ours.append((method, d, p))
    methods = {method for method, _, _ in ours}
    assert methods == {"exact", "normal"}, "the batch must exercise both ways of finding p"
    theirs = r_p_values([(method, d) for method, d, _ in ours], tmp_path)
    wrong = [f"{method} p of {d[:8]}{'...' if len(d) > 8 else ''} (n = {len(d)}): ours {p!r}, R's {r!r}"
             for (method, d, p), r in zip(ours, theirs) if not p == pytest.approx(r, rel=1e-9, abs=0)]
    assert not wrong, "\n".join(wrong)


def test_install_deps_installs_r():
    """The project's test command runs scripts/install-deps.sh first: R must be in its list."""
    assert {"r-base-core", "r-cran-exactranktests"} <= installed_by_deps(), "scripts/install-deps.sh does not install R"
