#include "summary.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "stats.h"

namespace warplab::bench {
namespace {

// The run's settings, and whether another process seems to have loaded the machine.
void writeSettings(std::ostream& md, const BenchOptions& options, const renderer::GlInfo& gl, const BenchPlan& plan,
                   const ConventionalTimes& times) {
    const auto& sequences = plan.sequences;
    const std::size_t totalFrames = plan.totalFrames;
    const double maskRateHz = plan.maskRateHz;
    const bool anyBanded = plan.anyBanded;
    const renderer::GuardBand& band = plan.band;
    const std::vector<double>& conventionalSpread = times.spread;
    const std::vector<double>& conventionalFrames = times.frames;
    const std::vector<double>& bandedFrames = times.banded;
    md << "# warplab bench\n\n"
       << "- GL: " << gl.renderer << " (" << gl.version << ", " << gl.backend << ")\n"
       << "- size: " << options.width << "x" << options.height << ", display " << options.refreshHz << " Hz, "
       << "shading cost " << options.shadingCost << ", " << options.repeats
       << " timed repeats per pass after an untimed one (medians)\n"
       << "- antialiasing: "
       << (options.supersampling > 1
               ? std::to_string(options.supersampling) + "x" + std::to_string(options.supersampling) + " supersampling"
               : std::string("none"))
       << " for every conventional frame, ground truth included\n"
       << "- frames: " << totalFrames << " sampled display frames over " << sequences.size() << " sequences\n"
       << "- masks: border MAE over pixels off-screen in the frame's latest " << maskRateHz
       << " Hz source, disocc MAE over pixels hidden there; the same pixels for every method, weighted by pixel "
          "count over the frames\n";
    // Another process on the machine shows as repeats of one conventional frame that disagree,
    // or, when its load changes slowly, as conventional frames of one size that cost very
    // different amounts over the run (content alone spread them 1.8x, 90th to 10th
    // percentile, in an unloaded quick run; a compile beside it made that 6x).
    const double spread = median(conventionalSpread);
    std::vector<double> sortedFrames = conventionalFrames;
    std::sort(sortedFrames.begin(), sortedFrames.end());
    const auto percentile = [&](double q) {
        return sortedFrames[static_cast<std::size_t>(q * static_cast<double>(sortedFrames.size() - 1))];
    };
    const double runSpread = sortedFrames.empty() ? 1.0 : percentile(0.9) / percentile(0.1);
    if (anyBanded) {
        const double plain = median(conventionalFrames), banded = median(bandedFrames);
        const double pixels = static_cast<double>(options.width + 2 * band.x) * (options.height + 2 * band.y) /
            (static_cast<double>(options.width) * options.height);
        md << "- guard band: " << options.guardBand * 100 << " % per side (" << band.x << " and " << band.y
           << " px) for the sources of the methods that take one, " << field(pixels, 2)
           << "x the pixels; such a source costs " << field(banded, 3) << " ms against " << field(plain, 3)
           << " ms without (median over the frames, ratio " << field(banded / plain, 2) << ")\n";
    }
    for (const std::string& why : plan.skipped) md << "- skipped: " << why << "\n";
    md << "- conventional frames: repeats of one frame median slowest/fastest " << field(spread, 3)
       << "; over the run 90th/10th percentile " << field(runSpread, 3) << "\n";
    if (spread > 1.3 || runSpread > 3.0)
        md << "\n**Warning:** the conventional frame's time varied "
           << (spread > 1.3 ? "between repeats" : "over the run")
           << " more than content explains: something else is loading this machine, so the times are noisy.\n";
}

// What a method is given, so methods are compared at equal cost in renders: the rate of its
// conventional sources, how late it is shown them (a late warp's queue), "+ next" when it also
// waits for the next one (a frame of latency), and how many times the lowest rate's renders it
// needs.
std::string sourcesText(const renderer::MethodInfo& info, double maskRateHz) {
    std::string text = field(info.sourceRateHz, 0) + " Hz";
    if (info.sourceLagS > 0.0) text += ", " + field(1000.0 * info.sourceLagS, 1) + " ms late";
    if (info.needsNext) text += " + next";
    if (info.sourceRateHz > maskRateHz) text += " (" + field(info.sourceRateHz / maskRateHz, 0) + "x the renders)";
    return text;
}

// One line of the table: `info`'s rows of sequence `seq`, or of every sequence when it is empty.
void summarise(std::ostream& md, const std::string& seq, const renderer::MethodInfo& info, const std::vector<Row>& rows,
               double maskRateHz) {
    const std::string& method = info.name;
    std::vector<double> pass, conv, psnr, ssim, all05, hit05, triangles;
    double borderSum = 0, disoccSum = 0;
    std::size_t borderPx = 0, disoccPx = 0;
    for (const Row& r : rows) {
        if ((!seq.empty() && r.sequence != seq) || r.method != method) continue;
        pass.push_back(r.passMs);
        conv.push_back(r.conventionalMs);
        psnr.push_back(r.psnr);
        ssim.push_back(r.ssim);
        if (r.borderPx > 0 && !std::isnan(r.borderMae)) borderSum += r.borderMae * r.borderPx, borderPx += r.borderPx;
        if (r.disoccPx > 0 && !std::isnan(r.disoccMae)) disoccSum += r.disoccMae * r.disoccPx, disoccPx += r.disoccPx;
        triangles.push_back(r.triangles);
        if (r.hasCorr) all05.push_back(r.corr.allLt0p5), hit05.push_back(r.corr.hitLt0p5);
    }
    const double p = median(pass), c = median(conv);
    const double combined = psnrOfMeanMse(psnr);
    const std::string psnrText = std::isinf(combined) ? "inf (exact)" : field(combined, 2);
    auto pct = [](double v) { return std::isnan(v) ? std::string("") : field(100.0 * v, 1) + "%"; };
    md << "| " << (seq.empty() ? "**all**" : seq) << " | " << method << " | " << sourcesText(info, maskRateHz) << " | "
       << field(p, 3) << " | " << field(p / c, 3) << " | " << psnrText << " | " << field(mean(ssim), 4) << " | "
       << field(borderPx > 0 ? borderSum / borderPx : kNaN, 2) << " | "
       << field(disoccPx > 0 ? disoccSum / disoccPx : kNaN, 2) << " | " << pct(mean(all05)) << " | " << pct(mean(hit05))
       << " | " << field(median(triangles), 0) << " |\n";
}

// Per method x sequence, then per method over all sequences.
void writeTable(std::ostream& md, const BenchPlan& plan, const std::vector<Row>& rows) {
    const auto& sequences = plan.sequences;
    const auto& methods = plan.methods;
    md << "\n| sequence | method | sources | median pass ms | ratio to conventional | PSNR dB | mean SSIM | border MAE "
          "| "
          "disocc MAE | corr all <0.5 px | corr hit <0.5 px | triangles |\n"
          "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const auto& s : sequences)
        for (const auto& m : methods) summarise(md, s->name(), m->info(), rows, plan.maskRateHz);
    // Over all sequences, methods of equal source rate together, lowest first.
    std::vector<const renderer::MethodInfo*> byRate;
    for (const auto& m : methods) byRate.push_back(&m->info());
    std::stable_sort(byRate.begin(), byRate.end(), [](const auto* a, const auto* b) {
        return a->sourceRateHz < b->sourceRateHz ||
            (a->sourceRateHz == b->sourceRateHz && !a->needsNext && b->needsNext);
    });
    for (const auto* info : byRate) summarise(md, "", *info, rows, plan.maskRateHz);
}

// "splat=12.345;resolve=4.567": a pass's stages for one CSV field, in the method's order.
std::string stagesField(const std::vector<renderer::StageTime>& stages) {
    std::string text;
    for (const auto& st : stages) text += (text.empty() ? "" : ";") + st.name + "=" + field(st.wallMs, 3);
    return text;
}

// The methods whose pass has stages (warp-splat: splat, resolve), over all sequences: each
// stage's median and its share of the median pass.
void writeStages(std::ostream& md, const BenchPlan& plan, const std::vector<Row>& rows) {
    bool header = false;
    for (const auto& m : plan.methods) {
        const std::string& method = m->info().name;
        std::vector<double> pass;
        std::vector<std::string> names;
        std::vector<std::vector<double>> ms;
        for (const Row& r : rows) {
            if (r.method != method || r.stages.empty()) continue;
            pass.push_back(r.passMs);
            for (std::size_t i = 0; i < r.stages.size(); ++i) {
                if (i == names.size()) names.push_back(r.stages[i].name), ms.emplace_back();
                ms[i].push_back(r.stages[i].wallMs);
            }
        }
        if (names.empty()) continue;
        if (!header) {
            md << "\nPasses timed in stages (each stage ended by glFinish; medians over all sequences):\n\n"
                  "| method | median pass ms | stages: median ms (share of the pass) |\n|---|---:|---|\n";
            header = true;
        }
        const double p = median(pass);
        std::string text;
        for (std::size_t i = 0; i < names.size(); ++i) {
            const double stage = median(ms[i]);
            text += (i ? ", " : "") + names[i] + " " + field(stage, 3) + " (" + field(100.0 * stage / p, 0) + " %)";
        }
        md << "| " << method << " | " << field(p, 3) << " | " << text << " |\n";
    }
}

// Where upconversion starts to pay: which methods' passes are cheaper than a conventional frame
// at each shading cost.
void writeSweep(std::ostream& md, const BenchPlan& plan, const std::vector<Row>& rows, const ShadingSweep& sweep) {
    const auto& sequences = plan.sequences;
    const auto& methods = plan.methods;
    md << "\nA 15->120 Hz method renders one conventional frame and makes seven, so per displayed frame it costs "
          "(C + 7M)/8 against C for rendering every frame: it pays whenever its pass M is cheaper than a "
          "conventional frame C.\n\n| shading cost | conventional frame ms ("
       << sequences.front()->name() << ", t = 0) | methods cheaper than it |\n|---:|---:|---|\n";
    for (const auto& [cost, ms] : sweep) {
        std::string cheaper;
        for (const auto& m : methods) {
            std::vector<double> pass;
            for (const Row& r : rows)
                if (r.method == m->info().name) pass.push_back(r.passMs);
            if (median(pass) < ms) cheaper += (cheaper.empty() ? "" : ", ") + m->info().name;
        }
        md << "| " << cost << " | " << field(ms, 3) << " | " << cheaper << " |\n";
    }
}

}  // namespace

const std::vector<table::Column<Row>>& csvColumns() {
    using F = table::CellWriter;
    using R = Row;
    // A measure to `digits` decimals, as field() prints it: empty when it does not apply.
    const auto measure = [](double Row::*value, int digits) {
        return [value, digits](F& f, const R& r) { f.formatted(field(r.*value, digits)); };
    };
    // A share of correspondences, empty for a method that reports none.
    const auto corr = [](double CorrespondenceStats::*share) {
        return [share](F& f, const R& r) { f.formatted(r.hasCorr ? field(r.corr.*share) : std::string()); };
    };
    static const std::vector<table::Column<Row>> columns = {
        {"sequence", [](F& f, const R& r) { f.text(r.sequence); }},
        {"method", [](F& f, const R& r) { f.text(r.method); }},
        {"frame", [](F& f, const R& r) { f.integer(r.frame); }},
        {"time_s", measure(&R::time, 6)},
        {"psnr_db", measure(&R::psnr, 3)},
        {"ssim", measure(&R::ssim, 5)},
        {"border_mae", measure(&R::borderMae, 3)},
        {"border_px", [](F& f, const R& r) { f.integer(static_cast<std::int64_t>(r.borderPx)); }},
        {"disocc_mae", measure(&R::disoccMae, 3)},
        {"disocc_px", [](F& f, const R& r) { f.integer(static_cast<std::int64_t>(r.disoccPx)); }},
        {"corr_all_lt_0p1", corr(&CorrespondenceStats::allLt0p1)},
        {"corr_all_lt_0p5", corr(&CorrespondenceStats::allLt0p5)},
        {"corr_all_lt_1", corr(&CorrespondenceStats::allLt1)},
        {"corr_hit_lt_0p1", corr(&CorrespondenceStats::hitLt0p1)},
        {"corr_hit_lt_0p5", corr(&CorrespondenceStats::hitLt0p5)},
        {"corr_hit_lt_1", corr(&CorrespondenceStats::hitLt1)},
        {"pass_ms", measure(&R::passMs, 3)},
        {"gpu_ms", measure(&R::gpuMs, 3)},
        {"conventional_ms", measure(&R::conventionalMs, 3)},
        {"source_ms", measure(&R::sourceMs, 3)},
        {"triangles", measure(&R::triangles, 0)},
        {"stage_ms", [](F& f, const R& r) { f.text(stagesField(r.stages)); }},
        {"budget_share", measure(&R::budgetShare, 6)},
        {"family", [](F& f, const R& r) { f.text(r.family); }},
        {"age_mean_ms", measure(&R::ageMeanMs, 3)},
        {"age_p95_ms", measure(&R::ageP95Ms, 3)},
    };
    return columns;
}

std::ofstream openCsv(const std::string& path) {
    std::ofstream csv(path);
    if (!csv) throw std::runtime_error("cannot write '" + path + "'");
    return csv;
}

void writeRow(table::CsvFile& csv, const Row& r) {
    table::writeCells(csv, csvColumns(), r);
    csv.endRow();
}

ShadingSweep timeShadingSweep(Rig& rig, const BenchOptions& options, const BenchPlan& plan) {
    auto& conventional = rig.conventional;
    const auto& sequences = plan.sequences;
    ShadingSweep sweep;
    const scene::FrameDescription frame = sequences.front()->at(0.0);
    for (int cost : options.shadingSweep) {
        renderer::ShadingOptions s;
        s.shadingCost = cost;
        conventional.setShading(s);
        sweep.emplace_back(cost, median(timeRepeats(rig.timer, options.repeats, [&] {
                               conventional.render(frame, rig.truthFrame.gbuffer);
                           })));
    }
    conventional.setShading(rig.shading);
    return sweep;
}

std::string summaryMarkdown(const BenchOptions& options, const renderer::GlInfo& gl, const BenchPlan& plan,
                            const ConventionalTimes& times, const std::vector<Row>& rows, const ShadingSweep& sweep) {
    std::ostringstream md;
    writeSettings(md, options, gl, plan, times);
    writeTable(md, plan, rows);
    writeStages(md, plan, rows);
    writeSweep(md, plan, rows, sweep);
    std::string header;
    for (const std::string& name : table::headerOf(csvColumns())) header += (header.empty() ? "" : ",") + name;
    md << "\nColumns of bench.csv: " << header
       << ". Empty = does not apply; psnr_db inf = identical to ground truth; stage_ms lists a pass's stages "
          "as name=ms;name=ms. PSNR in the table is that of the "
          "mean squared error over the frames. Ratios divide medians measured in this run.\n";
    return md.str();
}

}  // namespace warplab::bench
