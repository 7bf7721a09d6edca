"""The mixed models' figures (mixed_models.json's fitted models, one panel each):

- the contrasts: every pair of conditions as a ratio (odds, rate or cumulative odds) with its
  unadjusted 95 % CI on a log axis, 1 (no difference) marked, the Holm-adjusted p beside it;
- the means: each condition's estimated marginal mean with its 95 % CI beside the raw points it
  summarises, one per participant (their proportion of hits, mean count or mean answer there),
  so that what the model estimates can be read against the data.
Conditions keep the colours of the report's other figures (figures.colour).
"""
import math
import textwrap

import numpy as np

from .figures import colour, plt

import matplotlib.ticker  # noqa: E402  (after figures, which chose the Agg backend)

# Panels of the means figure per row; the contrasts figure stacks its panels, one per row, since
# its labels are long.
MEANS_COLUMNS = 3
# A contrast's row height (inches): its label, bar and p stay apart however many pairs a model has.
CONTRAST_ROW_IN = 0.32
RATIO_COLOUR = "#1f3b73"
Y_LABELS = {"probability": "proportion of hits", "count": "count per match", "mean answer": "answer"}


def wrapped(text, fig):
    """A title in lines that fit the figure's width (about 11 characters an inch at 10 pt)."""
    return textwrap.fill(text, width=max(30, int(fig.get_figwidth() * 11)))


def fitted_models(section):
    return [m for m in section.get("models", []) if m.get("fitted")]


def panel_title(model, width):
    return textwrap.shorten(f"{model['game']}: {model['label']}", width=width, placeholder="…")


def p_text(p):
    if p is None:
        return ""
    return "p < 0.0001" if p < 1e-4 else f"p = {p:.2g}" if p < 0.01 else f"p = {p:.3f}"


def contrasts_figure(path, section, palette):
    """One panel per model with contrasts, stacked, each a row per pair a / b."""
    models = [m for m in fitted_models(section) if m["contrasts"]]
    heights = [max(1.2, CONTRAST_ROW_IN * len(m["contrasts"]) + 0.7) for m in models]
    fig, axes = plt.subplots(len(models), 1, figsize=(8.5, sum(heights) + 0.6), dpi=110, squeeze=False,
                             gridspec_kw={"height_ratios": heights})
    for ax, model in zip(axes[:, 0], models):
        contrasts = model["contrasts"]
        y = np.arange(len(contrasts))[::-1]
        finite = [c for c in contrasts if c["low"] is not None and c["high"] is not None]
        for row, c in zip(y, contrasts):
            if c["ratio"] is None:
                continue
            low = c["low"] if c["low"] is not None else c["ratio"]
            high = c["high"] if c["high"] is not None else c["ratio"]
            ax.plot([low, high], [row, row], color="0.25", linewidth=1.4, solid_capstyle="butt")
            ax.plot([c["ratio"]], [row], marker="o", color=RATIO_COLOUR, markersize=6, linestyle="none")
        ax.axvline(1.0, color="0.4", linestyle="--", linewidth=0.9)
        ax.set_xscale("log")
        span = [v for c in finite for v in (c["low"], c["high"]) if v > 0] + [1.0]
        low, high = min(span), max(span)
        pad = (high / low) ** 0.08 if high > low else 2.0
        ax.set_xlim(low / pad, high * pad)
        # Ratios read as numbers (0.5, 1, 2), not powers of ten: at 1-2-5 steps, finer over a short span.
        subs = (1.0, 2.0, 5.0) if high / low > 8 else (1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 7.0)
        ax.xaxis.set_major_locator(matplotlib.ticker.LogLocator(base=10, subs=subs))
        ax.xaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:g}"))
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.set_yticks(y)
        ax.set_yticklabels([f"{c['a']} / {c['b']}" for c in contrasts], fontsize=8)
        ax.set_ylim(-0.7, len(contrasts) - 0.3)
        secondary = ax.secondary_yaxis("right")
        secondary.set_yticks(y)
        secondary.set_yticklabels([p_text(c["p_holm"]) for c in contrasts], fontsize=7)
        secondary.tick_params(length=0)
        ax.set_title(panel_title(model, 80), fontsize=9, loc="left")
        ax.set_xlabel(f"{model['ratio']} (a / b), 95 % CI unadjusted; right: Holm-adjusted p", fontsize=8)
        ax.tick_params(axis="x", labelsize=8)
        ax.grid(True, axis="x", which="both", linewidth=0.3, alpha=0.5)
    # Placed in inches from the top: a tall figure's default (2 % of its height) leaves a gap.
    fig.suptitle(wrapped("Mixed models: every pair of conditions (log scale; 1 = no difference)", fig), fontsize=10,
                 y=1 - 0.1 / fig.get_figheight(), va="top")
    fig.tight_layout(rect=(0, 0, 1, 1 - 0.3 / fig.get_figheight()))  # room for the title
    fig.savefig(path)
    plt.close(fig)


def means_figure(path, section, palette):
    """A panel per model: per condition the participants' raw values (dots) and the model's mean
    with its 95 % CI (black, to the right of them)."""
    models = fitted_models(section)
    columns = min(MEANS_COLUMNS, len(models))
    rows = math.ceil(len(models) / columns)
    widest = max(len(m["conditions"]) for m in models)
    fig, axes = plt.subplots(rows, columns, figsize=(max(3.8, 0.75 * widest + 1.6) * columns, 3.9 * rows), dpi=110,
                             squeeze=False)
    rng = np.random.default_rng(0)  # the dots' jitter: the same figure on every run
    for k, (ax, model) in enumerate(zip(axes.flat, models)):
        conditions = model["conditions"]
        means = {e["condition"]: e for e in model["means"]}
        for x, condition in enumerate(conditions):
            points = [p["mean"] for p in model["participant_points"] if p["condition"] == condition]
            ax.scatter(x - 0.12 + rng.uniform(-0.07, 0.07, len(points)), points, s=12, alpha=0.55,
                       color=colour(condition, palette), linewidths=0)
            e = means.get(condition)
            if e and e["estimate"] is not None:
                low = e["estimate"] - e["low"] if e["low"] is not None else 0.0
                high = e["high"] - e["estimate"] if e["high"] is not None else 0.0
                ax.errorbar([x + 0.16], [e["estimate"]], yerr=[[low], [high]], fmt="D", color="black", markersize=5,
                            capsize=3, linewidth=1.1)
        ax.set_xticks(np.arange(len(conditions)))
        ax.set_xticklabels(conditions, rotation=35, ha="right", fontsize=7)
        ax.set_xlim(-0.6, len(conditions) - 0.4)
        if model["means_scale"] == "probability":
            ax.set_ylim(-0.02, 1.02)
        ax.set_ylabel(Y_LABELS.get(model["means_scale"], model["means_scale"]), fontsize=8)
        ax.tick_params(axis="y", labelsize=7)
        ax.set_title(panel_title(model, 42), fontsize=9)
        ax.grid(True, axis="y", linewidth=0.4, alpha=0.5)
    for ax in list(axes.flat)[len(models):]:
        ax.set_visible(False)
    fig.suptitle(wrapped("Mixed models: estimated mean per condition with 95 % CI (black) beside each "
                         "participant's own (dots)", fig), fontsize=10)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
