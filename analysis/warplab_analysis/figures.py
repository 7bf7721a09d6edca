"""The report's figures (PNG, matplotlib's Agg backend, so no display is needed).

- hit rate per participant, one marker per condition, not joined (participants are categories;
  seed 004 Figure 32); beyond PER_PARTICIPANT_LIMIT participants, one box of the participants'
  hit rates per condition instead;
- histograms of upconverting − other condition hit-rate differences, one panel per pair (Figures
  33–34), in bins of 0.05 (five percentage points, as the thesis discusses them) aligned on 0;
- the matches' per-condition mean ± SD of each measure, reference condition highlighted (the
  numbers of seed 000 Table 2);
- each condition's frame times against time over its pacing horizon (frametimes.csv), the graph
  MangoHud and CapFrameX draw, one panel per condition on one frame-time scale;
- each condition's view and scene latency of a step falling uniformly in time (latency.csv), as
  histograms drawn exactly from the spans, a row per condition on one latency scale;
- the discrimination task's psychometric curves, a panel per participant, a colour per procedure.
Each condition keeps one colour in every figure: its place in `palette`, every condition the
export's table lists in the report's condition order (conditions.ConditionTable.all_conditions).
"""
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.lines  # noqa: E402
import matplotlib.ticker  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .psychometric import probability  # noqa: E402

BIN_WIDTH = 0.05
# Up to this many participants the hit-rate figure gives each a column (0.38 in, so 26 in and
# about 2,900 px wide at most); beyond it the columns would be unreadable slivers, and at 1,700
# participants wider than matplotlib draws (2^16 px), so each condition gets one box instead.
PER_PARTICIPANT_LIMIT = 60
MARKERS = ["o", "s", "^", "D", "v", "P", "X", "<", ">", "h", "*", "p"]


def colour(condition, palette):
    """One colour per condition: those the condition table lists by their place in the condition
    order, others by name."""
    cmap = plt.get_cmap("tab10")
    if condition in palette:
        return cmap(palette.index(condition) % 10)
    return plt.get_cmap("Dark2")(sum(map(ord, condition)) % 8)


def hit_rates_figure(path, game, participants, conditions, hit_rates, measure, palette, labels=None):
    """measure: what the rate counts, e.g. "hits / shots" or "green hits / clicks" (games.csv);
    labels: each condition's legend entry (the condition's name where absent)."""
    labels = labels or {}
    if len(participants) > PER_PARTICIPANT_LIMIT:
        hit_rates_summary_figure(path, game, participants, conditions, hit_rates, measure, palette, labels)
        return
    fig, ax = plt.subplots(figsize=(max(7.0, 0.38 * len(participants) + 3.0), 5.0), dpi=110)
    x = np.arange(len(participants))
    # Conditions side by side within a participant's column: equal hit rates (common with few
    # shots) would otherwise hide one condition's marker behind another's.
    dodge = min(0.25, 0.6 / max(1, len(conditions)))
    for k, condition in enumerate(conditions):
        y = [hit_rates[p][condition]["hit_rate"] if condition in hit_rates[p] else math.nan for p in participants]
        # Points only: participants are categories, not a series, so no line joins one to the next.
        ax.plot(x + (k - (len(conditions) - 1) / 2) * dodge, y, marker=MARKERS[k % len(MARKERS)], linestyle="none",
                markersize=6, color=colour(condition, palette), label=labels.get(condition, condition))
    ax.set_xticks(x)
    ax.set_xticklabels(participants, rotation=90 if max(map(len, participants)) > 3 else 0, fontsize=8)
    ax.set_xlim(-0.5, len(participants) - 0.5)
    ax.set_ylim(0, 1.02)
    ax.set_xlabel("participant")
    ax.set_ylabel(f"hit rate ({measure})")
    ax.set_title(f"{game}: hit rate per participant and condition")
    ax.grid(True, axis="y", linewidth=0.4, alpha=0.5)
    # Beside the axes, not over them: with points only, any corner may hold a participant's rate.
    ax.legend(title="condition", fontsize=8, title_fontsize=8, loc="upper left", bbox_to_anchor=(1.0, 1.0),
              framealpha=0.9)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def hit_rates_summary_figure(path, game, participants, conditions, hit_rates, measure, palette, labels):
    """One box per condition (quartiles, whiskers at 1.5 IQR) over every participant's hit rate,
    with each participant a faint dot beside it: the spread of Figure 32 when a column each is too
    many."""
    fig, ax = plt.subplots(figsize=(max(7.0, 1.1 * len(conditions) + 3.0), 5.0), dpi=110)
    rng = np.random.default_rng(0)  # the dots' jitter: the same figure on every run
    for k, condition in enumerate(conditions):
        y = np.array([hit_rates[p][condition]["hit_rate"] for p in participants if condition in hit_rates[p]])
        if len(y) == 0:
            continue
        ax.scatter(k + 0.3 + rng.uniform(-0.08, 0.08, len(y)), y, s=3, alpha=min(0.6, 30 / len(y) + 0.05),
                   color=colour(condition, palette), linewidths=0)
        box = ax.boxplot([y], positions=[k], widths=0.35, patch_artist=True, showfliers=False,
                         medianprops={"color": "black"})
        for patch in box["boxes"]:
            patch.set_facecolor(colour(condition, palette))
            patch.set_alpha(0.8)
    ax.set_xticks(np.arange(len(conditions)))
    ax.set_xticklabels([labels.get(c, c) for c in conditions], rotation=30, ha="right", fontsize=8)
    ax.set_xlim(-0.6, len(conditions) - 0.2)
    ax.set_ylim(0, 1.02)
    ax.set_xlabel("condition")
    ax.set_ylabel(f"hit rate ({measure})")
    ax.set_title(f"{game}: hit rate per condition over {len(participants)} participants (box: quartiles; dots: "
                 "participants)", fontsize=10)
    ax.grid(True, axis="y", linewidth=0.4, alpha=0.5)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def bins(values):
    low = math.floor(min(values) / BIN_WIDTH + 1e-9) * BIN_WIDTH
    high = math.ceil(max(values) / BIN_WIDTH - 1e-9) * BIN_WIDTH
    if high - low < BIN_WIDTH / 2:  # every value on one bin edge (e.g. all ties: 0)
        low, high = low - BIN_WIDTH, high + BIN_WIDTH
    return np.linspace(low, high, int(round((high - low) / BIN_WIDTH)) + 1)


def differences_figure(path, game, panels, palette):
    """panels: [((upconverting condition, other condition), [differences])]."""
    columns = min(3, len(panels))
    rows = math.ceil(len(panels) / columns)
    fig, axes = plt.subplots(rows, columns, figsize=(4.2 * columns, 3.4 * rows), dpi=110, squeeze=False)
    for ax, ((condition, other), values) in zip(axes.flat, panels):
        if values:
            ax.hist(values, bins=bins(values), color=colour(condition, palette), edgecolor="black", linewidth=0.6)
            ax.axvline(0.0, color="0.3", linestyle="--", linewidth=0.9)
        else:
            ax.text(0.5, 0.5, "no participant has both conditions", ha="center", va="center", transform=ax.transAxes,
                    fontsize=8)
        ax.set_title(f"{condition} − {other}", fontsize=9)
        ax.set_xlabel("hit-rate difference")
        ax.set_ylabel("participants")
        ax.yaxis.get_major_locator().set_params(integer=True)
    for ax in list(axes.flat)[len(panels):]:
        ax.set_visible(False)
    fig.suptitle(f"{game}: hit-rate differences, upconversion against each other condition (bins of {BIN_WIDTH:g})",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def matches_figure(path, matches, palette):
    """Each measure of the matches (analyze.analyse_matches): per condition the mean ± SD across
    participants, a panel per measure."""
    measures = list(matches["measures"].values())
    conditions = matches["conditions"]
    columns = min(4, len(measures))
    rows = math.ceil(len(measures) / columns)
    fig, axes = plt.subplots(rows, columns, figsize=(3.6 * columns, 3.4 * rows), dpi=110, squeeze=False)
    x = np.arange(len(conditions))
    for k, (ax, measure) in enumerate(zip(axes.flat, measures)):
        means = [measure["conditions"][c]["mean"] for c in conditions]
        sds = [measure["conditions"][c]["sd"] for c in conditions]
        means = [math.nan if v is None else v for v in means]
        sds = [0.0 if v is None else v for v in sds]
        bars = ax.bar(x, means, yerr=sds, capsize=3, color=[colour(c, palette) for c in conditions],
                      edgecolor="black", linewidth=0.5, error_kw={"linewidth": 0.8})
        if matches["reference_condition"] in conditions:
            bars[conditions.index(matches["reference_condition"])].set_linewidth(2.0)
        ax.set_xticks(x)
        ax.set_xticklabels(conditions, rotation=60, ha="right", fontsize=7)
        label = measure["label"]
        ax.set_title(label if len(label) <= 34 else label[:32] + "…", fontsize=9)
        if k % columns == 0:
            ax.set_ylabel("mean ± SD of participants' averages", fontsize=8)
        ax.grid(True, axis="y", linewidth=0.4, alpha=0.5)
    for ax in list(axes.flat)[len(measures):]:
        ax.set_visible(False)
    whose = f"{matches['game']} game" if matches["game"] else "matches"
    fig.suptitle(f"{whose}: mean ± SD across participants (reference {matches['reference_condition']}, bold outline)",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def frame_times_figure(path, series, palette):
    """series: {(game, condition, refresh_hz): ([time_s], [frame_time_ms])}. One panel per condition,
    stacked, sharing both axes, so a hitch or an uneven cadence stands out against a steady one.
    Returns the shared frame-time axis's limits (ms): up to the longest frame time of any."""
    keys = list(series)
    # Set once for all: a limit set panel by panel stops at the first panel's frame times, and a
    # later condition's hitches would run off the top.
    longest = max((max(frame_times) for _, frame_times in series.values() if frame_times), default=1.0)
    fig, axes = plt.subplots(len(keys), 1, figsize=(9.0, 1.5 * len(keys) + 1.0), dpi=110, squeeze=False,
                             sharex=True, sharey=True)
    for ax, key in zip(axes.flat, keys):
        game, condition, refresh = key
        times, frame_times = series[key]
        ax.step(times, frame_times, where="pre", color=colour(condition, palette), linewidth=0.9)
        ax.text(0.01, 0.9, f"{condition} ({game}, {refresh:g} Hz)", transform=ax.transAxes, fontsize=8, va="top",
                bbox={"facecolor": "white", "alpha": 0.8, "linewidth": 0})
        ax.set_ylabel("ms", fontsize=8)
        ax.grid(True, linewidth=0.4, alpha=0.5)
    axes.flat[0].set_ylim(0, 1.08 * longest)
    axes.flat[-1].set_xlabel("time over the condition's horizon (s)")
    fig.suptitle("frame time of each new image (frametimes.csv)", fontsize=10)
    fig.tight_layout()
    fig.savefig(path)
    limits = axes.flat[-1].get_ylim()
    plt.close(fig)
    return limits



# Bins fine enough that a refresh period (4.2 ms at 240 Hz) spans several, few enough to see:
# about LATENCY_BINS across the widest latency, at a width of 1, 2 or 5 times a power of ten ms.
LATENCY_BINS = 250
# The least share the log scale shows: a hitch's tail (a 100 ms stall every 2 s holds 5 % of the
# steps over 100 ms, 0.05 % a ms) stays visible beside the bulk's tens of percent.
LATENCY_FLOOR_PERCENT = 1e-3


def latency_bin_width(most_ms):
    rough = max(most_ms, 1e-3) / LATENCY_BINS
    power = 10.0 ** math.floor(math.log10(rough))
    return next(k * power for k in (1, 2, 5, 10) if k * power >= rough * (1 - 1e-9))


def latency_shares(spans, edges):
    """The share of steps whose latency falls in each bin [edges[i], edges[i+1]): each span
    (from, to, weight) holds its weight uniformly between from and to, so this is exact."""
    low, high, weight = (np.array(column, dtype=float) for column in zip(*spans))
    below = np.clip((edges[:, None] - low) / (high - low), 0.0, 1.0) @ weight
    return np.diff(below)


def latency_figure(path, distributions, palette):
    """distributions: {(game, condition, refresh_hz): {"view"|"scene": [(from_ms, to_ms, weight)]}}
    (inputs.load_latency). A row per condition, view then scene latency, every panel on one
    latency axis and one logarithmic share axis, so a condition's delay, spread and tail read
    against the others'."""
    keys = list(distributions)
    kinds = (("view", "view latency (a step in mouse input)"), ("scene", "scene latency (a step in the scene's motion)"))
    most = max(to for key in keys for spans in distributions[key].values() for _, to, _ in spans)
    width = latency_bin_width(most)
    edges = np.arange(0.0, most + width, width)
    fig, axes = plt.subplots(len(keys), 2, figsize=(10.0, 1.1 * len(keys) + 1.3), dpi=110, squeeze=False,
                             sharex=True, sharey=True, layout="constrained")
    for row, key in enumerate(keys):
        game, condition, refresh = key
        for column, (kind, title) in enumerate(kinds):
            ax = axes[row][column]
            spans = distributions[key].get(kind)
            if spans:
                shares = np.maximum(100.0 * latency_shares(spans, edges), LATENCY_FLOOR_PERCENT / 10)
                ax.stairs(shares, edges, baseline=LATENCY_FLOOR_PERCENT / 10, fill=True,
                          color=colour(condition, palette), alpha=0.85)
                ax.axvline(max(to for _, to, _ in spans), color="black", linewidth=0.6, linestyle=":")
            ax.set_yscale("log")
            ax.grid(True, linewidth=0.4, alpha=0.5)
            ax.tick_params(labelsize=7)
            if row == 0:
                ax.set_title(title, fontsize=9)
        axes[row][0].set_ylabel(f"{condition}\n{game}, {refresh:g} Hz", rotation=0, ha="right", va="center",
                                fontsize=8)
    for ax in axes[-1]:
        ax.set_xlabel("latency (ms)", fontsize=8)
    axes[0][0].set_xlim(0.0, edges[-1] * 1.03)  # room for the longest's dotted line beside the frame
    axes[0][0].set_ylim(LATENCY_FLOOR_PERCENT, 100.0)
    axes[0][0].set_yticks([1e-3, 1e-1, 10.0], ["0.001 %", "0.1 %", "10 %"])
    axes[0][0].yaxis.set_minor_locator(matplotlib.ticker.NullLocator())
    fig.suptitle(f"latency of a step falling uniformly in time: % of steps per {width:g} ms bin, log scale; "
                 "dotted: the longest (latency.csv)", fontsize=9)
    fig.savefig(path)
    plt.close(fig)


# How far beyond the levels tried the stimulus axis reaches for a threshold or an interval's end,
# as a share of the levels' span on the axis's scale (on a log axis at least a factor of 2, so that
# levels close together still leave room; on a linear one, with a single level, that share of its
# size). Beyond it they are cut at the axis: a bootstrap interval of a weak session may reach 10^5
# frames, and an axis that spans it squeezes every level into a corner.
INTERVAL_REACH = 0.35


def stimulus_limits(levels, values, log):
    """The stimulus axis's limits: every level tried, and every threshold and interval's end up to
    the cut (INTERVAL_REACH), with a little room beyond. On a log axis a value at or below 0 lies
    beyond the cut."""
    def to(v):
        v = np.asarray(v, dtype=float)
        if not log:
            return v
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(v > 0, np.log(np.maximum(v, 1e-300)), -np.inf)

    core = to(levels if len(levels) else [v for v in values if math.isfinite(v)] or [1.0])
    low, high = float(core.min()), float(core.max())
    if log:
        reach = max(INTERVAL_REACH * (high - low), math.log(2.0))
    else:
        reach = INTERVAL_REACH * ((high - low) or max(abs(high), 1.0))
    shown = np.concatenate([core, np.clip(to([v for v in values if not math.isnan(v)]), low - reach, high + reach)])
    low, high = float(shown.min()), float(shown.max())
    pad = 0.06 * (high - low or 1.0)
    limits = (low - pad, high + pad)
    return (math.exp(limits[0]), math.exp(limits[1])) if log else limits


def proportion_floor(rows):
    """The proportion axis's lower limit: a little below the guess rate, or below the lowest
    proportion correct -- a level tried once and answered wrong is at 0, under any guess rate, and
    is data the figure must show."""
    return max(-0.04, min([row["guess"] - 0.08 for row in rows]
                          + [level["correct"] / level["n"] - 0.04 for row in rows for level in row["levels"]]))


def discrimination_figure(path, dimension, participants, rows, procedures):
    """Each participant's psychometric curves of one stimulus dimension (discrimination.analyse's
    rows), a panel each: per procedure (a colour each) the proportion correct at every level tried,
    marker area proportional to its trials; the MLE fit (solid), or where the trials give none the
    function of the procedure's own estimate (dashed; QUEST+'s posterior means); the MLE threshold
    at its percent correct with its bootstrap interval, and the procedure's own threshold with its
    credible interval. One scale for every panel, so that thresholds compare across participants;
    logarithmic where every procedure's function is on the log scale."""
    columns = min(5, max(1, math.ceil(math.sqrt(len(participants)))))
    panel_rows = math.ceil(len(participants) / columns)
    legend_rows = 2
    legend = 0.08 + 0.19 * legend_rows  # inches of the legend, under the axis label
    # At least 6.4 in wide, so that the title and the axis label fit over a single panel.
    fig, axes = plt.subplots(panel_rows, columns, figsize=(max(6.4, 3.1 * columns), 2.5 * panel_rows + 1.2 + legend),
                             dpi=110, squeeze=False, sharex=True, sharey=True)
    colours = {p: plt.get_cmap("tab10")(k % 10) for k, p in enumerate(procedures)}
    # Each threshold's interval a little above or below its percent correct, one place per procedure
    # and estimate, so that no two intervals at one percent correct hide each other.
    places = [(p, kind) for p in procedures for kind in ("mle", "export")]
    offsets = {place: 0.022 * (k - (len(places) - 1) / 2) for k, place in enumerate(places)}
    stimuli = [level["stimulus"] for row in rows for level in row["levels"]]
    values = []  # every threshold and interval's end
    for row in rows:
        for estimate, low, high in (("mle", "bootstrap_low", "bootstrap_high"),
                                    ("export", "threshold_low", "threshold_high")):
            got = row[estimate]
            if got and got["threshold"] is not None:
                values += [v for v in (got["threshold"], got[low], got[high]) if v is not None]
    log = all(row["scale"] == "log" for row in rows) and all(v > 0 for v in stimuli)
    limits = stimulus_limits(stimuli, values, log)
    grid = np.geomspace(*limits, 300) if log else np.linspace(*limits, 300)
    # Area, not radius, in proportion to the trials: the eye reads a marker's size as its area.
    most = max((level["n"] for row in rows for level in row["levels"]), default=1)
    for ax, participant in zip(axes.flat, participants):
        for row in [r for r in rows if r["participant"] == participant]:
            discrimination_panel(ax, row, colours[row["procedure"]],
                                 {kind: offsets[(row["procedure"], kind)] for kind in ("mle", "export")}, grid, most,
                                 limits)
        ax.set_title(participant, fontsize=9)
        ax.grid(True, linewidth=0.4, alpha=0.5)
        ax.tick_params(labelsize=7)
    for ax in list(axes.flat)[len(participants):]:
        ax.set_visible(False)
    first = axes.flat[0]
    if log:
        first.set_xscale("log")
        # 1, 2, 5 in each decade, written as numbers: a span of levels is often within one decade,
        # where the default would label only its power of ten.
        first.xaxis.set_major_locator(matplotlib.ticker.LogLocator(base=10.0, subs=(1.0, 2.0, 5.0)))
        first.xaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:g}"))
        first.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    first.set_xlim(*limits)
    first.set_ylim(proportion_floor(rows), 1.03)
    units = next(iter({row["units"] for row in rows}), "")
    height = fig.get_figheight()
    # Over the legend; tight_layout (matplotlib 3.6 and later) keeps the panels' tick labels above it.
    fig.supxlabel(f"{dimension}: difference from the reference ({units})", fontsize=9, y=legend / height,
                  va="bottom")
    fig.supylabel("proportion correct", fontsize=9)
    # The legend under the axis label, the title above the panels: neither can cover the other,
    # however few panels the figure is wide.
    handles = [matplotlib.lines.Line2D([], [], color=colours[p], marker="o", linestyle="none", label=p)
               for p in procedures]
    handles += [matplotlib.lines.Line2D([], [], color="0.25", linestyle="-", label="MLE fit"),
                matplotlib.lines.Line2D([], [], color="black", marker="|", markersize=9, markeredgewidth=2.0,
                                        linestyle="none", label="MLE threshold, bootstrap interval")]
    if any(row["export"]["threshold"] is not None for row in rows):
        handles += [matplotlib.lines.Line2D([], [], color="0.25", linestyle="--",
                                            label="procedure's estimate (no MLE fit)"),
                    matplotlib.lines.Line2D([], [], color="black", marker="D", markersize=5, markerfacecolor="white",
                                            linestyle="none", label="procedure's threshold, credible interval")]
    fig.legend(handles=handles, fontsize=8, loc="lower center", ncol=math.ceil(len(handles) / legend_rows),
               frameon=False, bbox_to_anchor=(0.5, 0.0), columnspacing=1.2, handletextpad=0.4)
    fig.suptitle(f"{dimension}: proportion correct per level (marker area: trials); thresholds at their percent "
                 "correct\nwith 95 % intervals, cut at the axis (open triangle)", fontsize=9, x=0.02, ha="left")
    fig.tight_layout(rect=(0, legend / height, 1, 1))
    fig.savefig(path)
    plt.close(fig)


def discrimination_panel(ax, row, colour_of_row, offsets, grid, most, limits):
    levels = row["levels"]
    ax.scatter([level["stimulus"] for level in levels], [level["correct"] / level["n"] for level in levels],
               s=[60.0 * level["n"] / most + 4.0 for level in levels], color=colour_of_row, alpha=0.55,
               edgecolors="none", zorder=2)
    if row["scale"] == "log":
        grid = grid[grid > 0]  # a linear axis beside a linear-scale procedure may reach 0 and below
    fit, own = row["mle"], row["export"]
    # The function: the trials' own where they have one; else the one the procedure concluded,
    # dashed, so that a row without a fit still shows where its procedure put the threshold.
    if fit is not None:
        curve = (fit["location"], fit["slope"], fit["lapse"], "-")
    elif own["location"] is not None:
        curve = (own["location"], own["slope"], own["lapse"] if own["lapse"] is not None else row["fit_lapse"], "--")
    else:
        curve = None
    if curve:
        location, slope, lapse, style = curve
        ax.plot(grid, probability(grid, location, slope, lapse, row["guess"], row["shape"], row["scale"]),
                color=colour_of_row, linewidth=1.2, linestyle=style, zorder=3)
    y = row["percent_correct"] / 100.0
    if fit is not None:
        threshold_marker(ax, fit["threshold"], fit["bootstrap_low"], fit["bootstrap_high"], y + offsets["mle"],
                         colour_of_row, limits, {"marker": "|", "markersize": 11, "markeredgewidth": 2.0,
                                                 "color": "black"})
    if own["threshold"] is not None:
        threshold_marker(ax, own["threshold"], own["threshold_low"], own["threshold_high"], y + offsets["export"],
                         colour_of_row, limits, {"marker": "D", "markersize": 4.5, "markeredgewidth": 1.0,
                                                 "markerfacecolor": "white", "color": "black"})


def threshold_marker(ax, threshold, low, high, y, colour_of_row, limits, marker):
    """A threshold on its interval at height y; an interval's end beyond the axis drawn to the axis,
    with an open triangle there pointing on."""
    if low is not None and high is not None and math.isfinite(low) and math.isfinite(high):
        ax.plot([max(low, limits[0]), min(high, limits[1])], [y, y], color=colour_of_row, linewidth=2.4, alpha=0.8,
                solid_capstyle="butt", zorder=4)
        for end, edge, pointing in ((low, limits[0], "<"), (high, limits[1], ">")):
            if (end < edge) if pointing == "<" else (end > edge):
                ax.plot([edge], [y], marker=pointing, markersize=5, markerfacecolor="white",
                        markeredgecolor=colour_of_row, clip_on=False, zorder=5)
    ax.plot([threshold], [y], linestyle="none", zorder=6, **marker)
