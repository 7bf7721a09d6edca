#!/usr/bin/python3
"""Speed against error: one labelled point per upconversion method from `warplab bench`'s CSV.

Usage: /usr/bin/python3 analysis/plot_bench.py BENCH_CSV OUT_PNG [--title T]

x: median pass_ms over all of the method's rows (log scale: methods span ~0.01 to ~100 ms).
y: PSNR of the mean squared error over the method's frames (each frame's MSE recovered from
   its psnr_db; an identical frame, PSNR = inf, has MSE 0). Averaging MSE rather than dB keeps
   exact frames from dominating; a method exact on every frame is drawn at 100 dB.
Small markers show the same per (method, sequence), shaped by sequence; the dashed line is
the median conventional_ms, the cost of rendering a frame conventionally.

With --budget-png it also draws the equal-budget figure: RMS error (0..255) against shaded
samples per second (budget_share times --samples-per-frame times the display rate folded into it
by the caller), one point per method, one line per family (whole frames, pixel lattice,
adaptive samples) through each family's least error at each budget.

Bad input (missing file, unreadable CSV, missing column, no rows) ends in one sentence on
stderr naming the file or column, and exit status 1.
"""
import argparse
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker as ticker  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

REQUIRED = ["sequence", "method", "pass_ms", "psnr_db", "conventional_ms"]
NUMERIC = ["pass_ms", "psnr_db", "conventional_ms"]
PSNR_CAP_DB = 100.0
SEQUENCE_MARKERS = ["o", "s", "^", "D", "v", "P", "X", "<", ">", "h", "*", "p"]


class BadInput(Exception):
    pass


def load(path):
    try:
        table = pd.read_csv(path, dtype={"sequence": str, "method": str})
    except FileNotFoundError:
        raise BadInput(f"{path}: no such file.")
    except pd.errors.EmptyDataError:
        raise BadInput(f"{path}: the file is empty, expected a header line with {', '.join(REQUIRED)}.")
    except (pd.errors.ParserError, UnicodeDecodeError, OSError) as e:
        raise BadInput(f"{path}: cannot be read as CSV ({str(e).strip().splitlines()[0]}).")
    for column in REQUIRED:
        if column not in table.columns:
            raise BadInput(f"{path}: missing column '{column}'.")
    if table.empty:
        raise BadInput(f"{path}: no data rows.")
    for column in NUMERIC:
        # Empty fields mean "not applicable" (NaN); 'inf' parses as infinity. Anything else
        # that is not a number is bad data, named rather than silently dropped.
        values = pd.to_numeric(table[column], errors="coerce")
        bad = values.isna() & table[column].notna() & (table[column].astype(str).str.strip() != "")
        if bad.any():
            row = int(np.flatnonzero(bad.to_numpy())[0]) + 2  # 1-based, after the header
            raise BadInput(f"{path}: line {row}, column '{column}' is not a number: {table[column][bad].iloc[0]!r}.")
        table[column] = values
    table["sequence"] = table["sequence"].fillna("")
    table["method"] = table["method"].fillna("")
    return table


def summarise(rows):
    """(median pass_ms, PSNR of the mean MSE, 1 if exact everywhere and so drawn at the cap)."""
    passes = rows["pass_ms"].dropna()
    psnr = rows["psnr_db"].dropna()
    x = float(passes.median()) if len(passes) else math.nan
    if not len(psnr):
        return x, math.nan, 0
    mse = (255.0 ** 2) / np.power(10.0, psnr.to_numpy(dtype=float) / 10.0)  # inf dB -> 0
    mean_mse = float(mse.mean())
    if mean_mse == 0.0:
        return x, PSNR_CAP_DB, 1
    return x, min(PSNR_CAP_DB, 10.0 * math.log10(255.0 ** 2 / mean_mse)), 0


def plottable(x, y):
    return math.isfinite(x) and x > 0 and math.isfinite(y)


def place_labels(ax, fig, points):
    """Method names beside their points, nudged down until they overlap no earlier label."""
    renderer = fig.canvas.get_renderer()
    placed = []
    for name, x, y in sorted(points, key=lambda p: -p[2]):
        for step in range(12):
            text = ax.annotate(name, (x, y), xytext=(7, 3 - 9 * step), textcoords="offset points", fontsize=8,
                               va="center", ha="left")
            box = text.get_window_extent(renderer).expanded(1.02, 1.1)
            if not any(box.overlaps(other) for other in placed):
                break
            text.remove()
        placed.append(box)


def plot(table, out_png, title):
    methods = list(dict.fromkeys(table["method"]))  # first-appearance order: the bench's order
    sequences = list(dict.fromkeys(table["sequence"]))
    colours = plt.get_cmap("tab10" if len(methods) <= 10 else "tab20")
    fig, ax = plt.subplots(figsize=(10, 6.5), dpi=120)
    notes = []
    skipped = []
    capped_total = 0
    labels = []
    for m, method in enumerate(methods):
        rows = table[table["method"] == method]
        colour = colours(m % colours.N)
        for s, sequence in enumerate(sequences):
            x, y, _ = summarise(rows[rows["sequence"] == sequence])
            if plottable(x, y):
                ax.scatter([x], [y], marker=SEQUENCE_MARKERS[s % len(SEQUENCE_MARKERS)], s=22, color=colour,
                           alpha=0.45, linewidths=0, zorder=2)
        x, y, capped = summarise(rows)
        capped_total += capped
        if not plottable(x, y):
            skipped.append(method)
            continue
        ax.scatter([x], [y], marker="o", s=70, color=colour, edgecolors="black", linewidths=0.8, zorder=3)
        labels.append((method, x, y))

    conventional = table["conventional_ms"].dropna()
    conventional = conventional[np.isfinite(conventional) & (conventional > 0)]
    median = float(conventional.median()) if len(conventional) else None
    if median is not None:
        ax.axvline(median, linestyle="--", color="0.35", linewidth=1.2, zorder=1)
    else:
        notes.append("no conventional_ms values: no conventional-frame line")

    ax.set_xscale("log")
    # Plain numbers at 1-2-5 steps: decades alone leave most points between two labels.
    ax.xaxis.set_major_locator(ticker.LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    ax.xaxis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}"))
    ax.xaxis.set_minor_formatter(ticker.NullFormatter())
    ax.set_xlabel("pass time per displayed frame, median over all frames (ms, log scale)")
    ax.set_ylabel("PSNR of the mean MSE against the ground-truth render (dB)")
    ax.set_title(title or "Speed against error", fontsize=11)
    ax.grid(True, which="both", linewidth=0.4, alpha=0.5)
    if labels:
        ax.margins(x=0.15, y=0.08)
    else:
        notes.append("no method has both a pass time and a PSNR")
    fig.canvas.draw()  # fixes the axes limits so label positions and boxes can be measured
    if median is not None:
        # Beside the line, on whichever side has room.
        right = ax.transAxes.inverted().transform(ax.transData.transform((median, 1.0)))[0] < 0.8
        ax.annotate(f"conventional frame\n(median {median:.3g} ms)", (median, 1.0), xycoords=("data", "axes fraction"),
                    xytext=(4 if right else -4, -4), textcoords="offset points", va="top",
                    ha="left" if right else "right", fontsize=8, color="0.3",
                    bbox=dict(facecolor="white", edgecolor="none", alpha=0.8, pad=1))
    place_labels(ax, fig, labels)

    handles = [plt.Line2D([], [], linestyle="none", marker="o", markersize=8, markerfacecolor="white",
                          markeredgecolor="black", label="method, all sequences")]
    handles += [plt.Line2D([], [], linestyle="none", marker=SEQUENCE_MARKERS[s % len(SEQUENCE_MARKERS)], markersize=6,
                           color="0.45", label=sequence or "(no sequence)") for s, sequence in enumerate(sequences)]
    ax.legend(handles=handles, title="sequence", fontsize=8, title_fontsize=8, loc="best", framealpha=0.9)

    if capped_total:
        notes.append(f"{capped_total} point(s) identical to ground truth on every frame, drawn at {PSNR_CAP_DB:g} dB")
    if skipped:
        notes.append("not plotted (no pass time or no PSNR): " + ", ".join(skipped))
    if notes:
        fig.text(0.01, 0.01, "Note: " + "; ".join(notes) + ".", fontsize=7.5, color="0.25", ha="left", va="bottom",
                 wrap=True)
    fig.tight_layout(rect=(0, 0.04 if notes else 0, 1, 1))
    fig.savefig(out_png)
    plt.close(fig)


FAMILY_STYLES = {"whole frames": ("tab:blue", "o"), "pixel lattice": ("tab:orange", "s"),
                 "adaptive samples": ("tab:green", "^")}


def plot_budget(table, out_png, title, samples_per_share):
    """Error against shaded samples per second, a line per family through its best at each budget."""
    for column in ("budget_share", "family"):
        if column not in table.columns:
            raise BadInput(f"missing column '{column}' (a bench.csv from before the equal-budget columns).")
    table = table.copy()
    table["budget_share"] = pd.to_numeric(table["budget_share"], errors="coerce")
    fig, ax = plt.subplots(figsize=(9, 6), dpi=120)
    labels = []
    for family in dict.fromkeys(table["family"].fillna("")):
        if not family:
            continue
        colour, marker = FAMILY_STYLES.get(family, ("0.4", "D"))
        rows = table[table["family"] == family]
        points = []
        for method in dict.fromkeys(rows["method"]):
            mrows = rows[rows["method"] == method]
            share = float(mrows["budget_share"].median())
            _, psnr, _ = summarise(mrows)
            if not (math.isfinite(share) and share > 0 and math.isfinite(psnr)):
                continue
            rms = 255.0 * 10.0 ** (-psnr / 20.0)
            x = share * samples_per_share
            points.append((x, rms, method))
            ax.scatter([x], [rms], color=colour, marker=marker, s=45, edgecolors="black", linewidths=0.6, zorder=3)
            labels.append((method, x, rms))
        best = {}
        for x, rms, _ in points:
            best[x] = min(rms, best.get(x, math.inf))
        xs = sorted(best)
        if xs:
            ax.plot(xs, [best[x] for x in xs], color=colour, linewidth=1.5, label=family, zorder=2)
    ax.set_xscale("log", base=2)
    # A tick at each budget in the run, named by its share of the display's pixels per frame too.
    budgets = sorted({x for _, x, _ in labels})
    if budgets:
        ax.set_xticks(budgets)
        ax.set_xticklabels([f"{x / 1e6:.3g} M\n(1/{samples_per_share / x:.0f})" if x < samples_per_share * 0.99
                            else f"{x / 1e6:.3g} M\n(all)" for x in budgets])
        ax.xaxis.set_minor_formatter(ticker.NullFormatter())
    ax.set_xlabel("shaded samples per second (log scale)")
    ax.set_ylabel("RMS error against the ideal frame (0..255)")
    ax.set_title(title or "Error at equal shading budgets", fontsize=11)
    ax.grid(True, which="both", linewidth=0.4, alpha=0.5)
    ax.margins(x=0.2, y=0.1)
    fig.canvas.draw()
    place_labels(ax, fig, labels)
    ax.legend(title="family (line: its least error at each budget)", fontsize=8, title_fontsize=8, loc="best")
    fig.tight_layout()
    fig.savefig(out_png)
    plt.close(fig)


def main(argv=None):
    parser = argparse.ArgumentParser(description="Plot warplab bench's speed against error.")
    parser.add_argument("bench_csv", help="the CSV `warplab bench` writes")
    parser.add_argument("out_png", help="where to write the plot (PNG)")
    parser.add_argument("--title", default=None, help="plot title (the bench passes its GL renderer and size)")
    parser.add_argument("--budget-png", default=None, help="also write the equal-budget figure here")
    parser.add_argument("--samples-per-share", type=float, default=1.0,
                        help="shaded samples per second at a budget share of 1 (width x height x display rate)")
    args = parser.parse_args(argv)
    try:
        table = load(args.bench_csv)
        plot(table, args.out_png, args.title)
        if args.budget_png:
            plot_budget(table, args.budget_png, args.title, args.samples_per_share)
    except BadInput as e:
        print(f"plot_bench.py: {e}", file=sys.stderr)
        return 1
    except OSError as e:
        print(f"plot_bench.py: cannot write {args.out_png}: {e.strerror or e}.", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
