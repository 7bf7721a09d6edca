// `warplab conditions PROTOCOL [--csv]`: the conditions a protocol runs, each with its parts, its
// frame pacing and the view and scene latency its schedule gives at the protocol's refresh -- the
// numbers of the README's latency table, for any condition a lab writes.
#include <algorithm>
#include <cstdio>
#include <iostream>

#include "commands.h"
#include "condition/schedule.h"
#include "export/export.h"
#include "game/registry.h"

namespace warplab::app {
namespace {

// "0 – 66.7 ms (0 – 8 frames)"
std::string range(const condition::ConditionSchedule::Range& r, double refreshHz) {
    char text[96];
    std::snprintf(text, sizeof text, "%.1f - %.1f ms (%.3g - %.3g frames)", r.min * 1000.0, r.max * 1000.0,
                  r.min * refreshHz, r.max * refreshHz);
    return text;
}

// The second line of a condition: its pacing over the stats horizon, as conditions.csv has it.
// "120 fps (1% low 120, 5% low 120); frame time 8.3 / 8.3 / 8.3 / 8.3 ms, 0 stutters; view 0 / 4.2 / 7.9 / 8.3 ms, scene ..."
std::string pacingLine(const condition::PacingStats& p) {
    const condition::FrameTimeSummary& f = p.frameTimes;
    auto latency = [](const condition::LatencyDistribution& d) {
        char text[96];
        std::snprintf(text, sizeof text, "%.1f / %.1f / %.1f / %.1f", d.min * 1000.0, d.median * 1000.0, d.p95 * 1000.0,
                      d.max * 1000.0);
        return std::string(text);
    };
    char text[256];
    std::snprintf(text, sizeof text,
                  "%.4g fps (1%% low %.4g, 5%% low %.4g); frame time %.1f / %.1f / %.1f / %.1f ms, %lld stutter%s; "
                  "latency min / median / p95 / max: view %s ms, scene %s ms",
                  f.meanFps, f.low1Fps, f.low5Fps, f.medianS * 1000.0, f.p95S * 1000.0, f.p99S * 1000.0,
                  f.maxS * 1000.0, static_cast<long long>(f.stutters), f.stutters == 1 ? "" : "s",
                  latency(p.viewS).c_str(), latency(p.sceneS).c_str());
    return text;
}

int runConditions(const ParsedArgs& args) {
    if (args.positional().size() != 1) throw UsageError("conditions needs one PROTOCOL file");
    const auto study = game::loadStudy(args.positional().front());
    const auto rows = exporter::conditionsOf(*study);
    if (args.flag("csv")) {
        exporter::writeConditionTable(std::cout, rows);
        return 0;
    }
    std::printf("%s: the %s game on a %g Hz display (one refresh = %.2f ms)\n", study->name().c_str(),
                study->game().c_str(), study->refreshHz(), 1000.0 / study->refreshHz());
    std::printf(
        "Each condition's second line: its pacing over %g s of display time (a drawn cadence at seed 0):\n"
        "new images per second, 1%% and 5%% lows, frame time median / p95 / p99 / max, stutters\n"
        "(frame times over twice the median), and latency of a step at a uniform instant.\n\n",
        condition::kPacingStatsHorizonS);
    std::printf("%-20s %8s %9s %-14s %-9s %-34s %s\n", "condition", "renders", "lag", "fill", "late warp",
                "view latency (mouse step)", "scene latency (change of motion)");
    for (const auto& r : rows) {
        const condition::Condition& c = r.summary.condition;
        std::string fill = c.fill;
        if (c.fillKind() != condition::Fill::Hold)
            fill += " " + condition::number(c.fillHz.value_or(study->refreshHz()));
        std::printf("%-20s %5s Hz %2lld frames %-14s %-9s %-34s %s\n", c.name.c_str(),
                    condition::number(c.renderHz).c_str(), static_cast<long long>(r.summary.lagFrames), fill.c_str(),
                    condition::lateWarpName(c.lateWarp), range(r.summary.viewS, r.summary.refreshHz).c_str(),
                    range(r.summary.sceneS, r.summary.refreshHz).c_str());
        std::printf("    %s\n", pacingLine(r.pacing).c_str());
        if (!r.analysed) std::printf("    training only: the part the study analyses (the test) does not run it\n");
        if (!c.description.empty()) std::printf("    %s\n", c.description.c_str());
    }
    return 0;
}

}  // namespace

Command conditionsCommand() {
    CommandSpec spec{"conditions",
                     "Print the conditions a protocol runs: their parts, frame pacing and view and scene latency.",
                     "warplab conditions PROTOCOL [--csv]",
                     {{"csv", "", "print CSV with conditions.csv's columns instead of a table", ""}},
                     true};
    return {spec, &runConditions};
}

}  // namespace warplab::app
