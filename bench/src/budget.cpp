#include "budget.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "stats.h"

namespace warplab::bench {
namespace {

// "1/8" for a share that is the inverse of a whole number, else the share itself.
std::string shareText(double share) {
    const double inverse = 1.0 / share;
    if (std::abs(inverse - std::round(inverse)) < 1e-6)
        return std::round(inverse) == 1.0 ? "1" : "1/" + field(std::round(inverse), 0);
    return field(share, 3);
}

}  // namespace

ShadedSweep timeShadedMethods(Rig& rig, const BenchOptions& options, const BenchPlan& plan) {
    ShadedSweep times;
    const auto& sequence = *plan.sequences.front();
    for (const auto& m : plan.methods) {
        const renderer::MethodInfo& info = m->info();
        if (info.shadedShare <= 0.0) continue;
        for (int cost : options.shadingSweep) {
            renderer::UpconversionInput input;
            input.shading = rig.shading;
            input.shading.shadingCost = cost;
            // The history frames before t = 0's neighbour, then the timed frame.
            const int k = info.historyFrames;
            std::vector<scene::FrameDescription> frames;
            for (int j = 0; j <= k; ++j) frames.push_back(sequence.at(j / options.refreshHz));
            for (int j = 0; j <= k; ++j) {
                input.displayTime = j / options.refreshHz;
                input.camera = frames[static_cast<std::size_t>(j)].camera;
                input.scene = &frames[static_cast<std::size_t>(j)].scene;
                m->produce(input, rig.display);
            }
            times[info.name].push_back(
                median(timeRepeats(rig.timer, options.repeats, [&] { m->produce(input, rig.display); })));
        }
    }
    return times;
}

std::string budgetMarkdown(const BenchOptions& options, const BenchPlan& plan, const std::vector<Row>& rows,
                           const ShadingSweep& sweep, const ShadedSweep& shaded) {
    struct Line {
        const renderer::MethodInfo* info;
        double share;
        std::string family;
        double rms, psnr, ssim, border, disocc, pass, ageMean, ageP95;
        std::vector<double> cost;  // ms per displayed frame at each sweep cost
    };
    std::vector<Line> lines;
    for (const auto& m : plan.methods) {
        const renderer::MethodInfo& info = m->info();
        std::vector<double> psnr, ssim, pass, ageMean, ageP95;
        double borderSum = 0, disoccSum = 0;
        std::size_t borderPx = 0, disoccPx = 0;
        Line line{&info, kNaN, "", kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, {}};
        for (const Row& r : rows) {
            if (r.method != info.name) continue;
            line.share = r.budgetShare;
            line.family = r.family;
            psnr.push_back(r.psnr);
            ssim.push_back(r.ssim);
            pass.push_back(r.passMs);
            ageMean.push_back(r.ageMeanMs);
            ageP95.push_back(r.ageP95Ms);
            if (r.borderPx > 0 && !std::isnan(r.borderMae))
                borderSum += r.borderMae * r.borderPx, borderPx += r.borderPx;
            if (r.disoccPx > 0 && !std::isnan(r.disoccMae))
                disoccSum += r.disoccMae * r.disoccPx, disoccPx += r.disoccPx;
        }
        if (psnr.empty() || info.exposureSamples > 0) continue;  // motion blur is judged against another truth
        line.psnr = psnrOfMeanMse(psnr);
        // Dayal et al.'s measure (section 7): the root of the mean squared error, 0..255.
        line.rms = std::isinf(line.psnr) ? 0.0 : 255.0 * std::pow(10.0, -line.psnr / 20.0);
        line.ssim = mean(ssim);
        line.border = borderPx > 0 ? borderSum / borderPx : kNaN;
        line.disocc = disoccPx > 0 ? disoccSum / disoccPx : kNaN;
        line.pass = median(pass);
        line.ageMean = mean(ageMean);
        line.ageP95 = mean(ageP95);
        // A displayed frame's cost: the method's own pass where it shades every frame; else its
        // share of a conventional source (one every n displayed frames) and its pass on the rest.
        for (std::size_t c = 0; c < sweep.size(); ++c) {
            if (info.shadedShare > 0.0) {
                const auto it = shaded.find(info.name);
                line.cost.push_back(it != shaded.end() && c < it->second.size() ? it->second[c] : kNaN);
            } else {
                const double n = options.refreshHz / info.sourceRateHz;
                line.cost.push_back((sweep[c].second + (n - 1.0) * line.pass) / n);
            }
        }
        lines.push_back(line);
    }
    // Largest budget first; within a budget, least error first.
    std::stable_sort(lines.begin(), lines.end(), [](const Line& a, const Line& b) {
        return a.share > b.share + 1e-9 || (std::abs(a.share - b.share) <= 1e-9 && a.rms < b.rms);
    });

    std::ostringstream md;
    const double pixels = static_cast<double>(options.width) * options.height;
    md << "\n## Equal shading budgets\n\n"
       << "Each method grouped by the share of the display's pixels it shades per displayed frame, and so by "
          "the shaded samples per second at this size and "
       << field(options.refreshHz, 0)
       << " Hz: whole frames less often (holds, warps, reprojection: the share is their source rate over the "
          "display's), a lattice of pixels every frame (spatio-temporal upsampling), or adaptively placed "
          "samples every frame (frameless). Error against the conventional frame at the displayed instant: RMS "
          "over the frames (0..255, Dayal et al.'s measure), PSNR, SSIM, MAE where the 15 Hz source shows "
          "nothing (border) or something else (disocc). Cost per displayed frame: a frame-rate method's share "
          "of its conventional source (sweep frame, "
       << plan.sequences.front()->name()
       << " at t = 0) plus its pass on the other frames; a method that shades every frame, its own pass "
          "(geometry, partial shading and filter) on the same frame. Age: how long before the displayed "
          "instant the newest shading behind a pixel was made (for a method that needs the next source, how long "
          "the frame waits for it), mean and 95th percentile over the pixels, averaged over the frames.\n\n"
       << "| budget | samples/s | method | family | RMS | PSNR dB | SSIM | border MAE | disocc MAE |";
    for (const auto& [cost, ms] : sweep) md << " ms/frame at shading " << cost << " |";
    md << " age mean ms | age p95 ms |\n|---|---:|---|---|---:|---:|---:|---:|---:|";
    for (std::size_t c = 0; c < sweep.size(); ++c) md << "---:|";
    md << "---:|---:|\n";
    md << "| 1 | " << field(pixels * options.refreshHz / 1e6, 1)
       << " M | conventional | every frame | 0 | inf | 1 |  |  |";
    for (const auto& [cost, ms] : sweep) md << " " << field(ms, 3) << " |";
    md << " 0 | 0 |\n";
    for (const Line& l : lines) {
        md << "| " << shareText(l.share) << " | " << field(l.share * pixels * options.refreshHz / 1e6, 2) << " M | "
           << l.info->name << " | " << l.family << " | " << field(l.rms, 2) << " | "
           << (std::isinf(l.psnr) ? std::string("inf") : field(l.psnr, 2)) << " | " << field(l.ssim, 4) << " | "
           << field(l.border, 2) << " | " << field(l.disocc, 2) << " |";
        for (double c : l.cost) md << " " << field(c, 3) << " |";
        md << " " << field(l.ageMean, 1) << " | " << field(l.ageP95, 1) << " |\n";
    }
    return md.str();
}

}  // namespace warplab::bench
