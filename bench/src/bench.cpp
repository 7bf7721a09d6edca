#include "bench/bench.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <stdexcept>

#include "budget.h"
#include "measure.h"
#include "plan.h"
#include "plot.h"
#include "summary.h"

namespace warplab::bench {
namespace {

// One line per display frame measured, with the time the rest of the run should take.
class Progress {
public:
    Progress(std::ostream& out, std::size_t totalFrames) : out_(out), totalFrames_(totalFrames) {}
    void frameDone(const std::string& sequence, int k) {
        ++doneFrames_;
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
        out_ << "bench: " << sequence << " frame " << k << " (" << doneFrames_ << "/" << totalFrames_ << "), "
             << std::fixed << std::setprecision(0) << elapsed << " s elapsed, ~"
             << elapsed / doneFrames_ * (totalFrames_ - doneFrames_) << " s left\n"
             << std::defaultfloat << std::flush;
    }

private:
    std::ostream& out_;
    std::size_t totalFrames_, doneFrames_ = 0;
    std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
};

}  // namespace

BenchOptions quickBenchOptions() {
    BenchOptions options;
    options.width = 320;
    options.height = 180;
    options.framesPerSequence = 8;
    options.repeats = 3;
    options.shadingSweep = {0, 256};
    return options;
}

void runBench(const BenchOptions& options, const renderer::DataPaths& paths, const renderer::GlInfo& gl,
              std::ostream& out, std::ostream& progress) {
    // Everything that can be refused is refused before the first frame.
    const BenchPlan plan = makePlan(options, paths);
    for (const std::string& why : plan.skipped) progress << "bench: skipped: " << why << "\n";
    std::filesystem::create_directories(options.outDir);
    const std::string csvPath = options.outDir + "/bench.csv";
    // Written straight to bench.csv and flushed after every display frame, so that a long run's
    // rows can be read while it runs and outlive it when it is cut short.
    std::ofstream csvFile = openCsv(csvPath);
    table::CsvFile csv(csvFile, table::headerOf(csvColumns()), csvPath);

    Rig rig(options, plan, paths);
    rig.warmUp(plan.sequences.front()->at(0.0));
    ConventionalTimes times;
    std::vector<Row> rows;
    Progress frames(progress, plan.totalFrames);
    for (std::size_t si = 0; si < plan.sequences.size(); ++si) {
        const auto& sequence = *plan.sequences[si];
        for (const int k : plan.samplesPerSequence[si]) {
            for (const Row& row : measureDisplayFrame(rig, options, plan, sequence, k, times)) {
                writeRow(csv, row);
                rows.push_back(row);
            }
            csvFile.flush();
            frames.frameDone(sequence.name(), k);
        }
    }
    if (!csvFile) throw std::runtime_error("writing '" + csvPath + "' failed");

    const ShadingSweep sweep = timeShadingSweep(rig, options, plan);
    std::string summary = summaryMarkdown(options, gl, plan, times, rows, sweep);
    summary += budgetMarkdown(options, plan, rows, sweep, timeShadedMethods(rig, options, plan)) +
        "\nbudget_vs_error.png draws the table: error against shaded samples per second, a line per family.\n";
    const std::string plotNote =
        writePlot(paths, csvPath, options.outDir + "/speed_vs_error.png",
                  gl.renderer + ", " + std::to_string(options.width) + "x" + std::to_string(options.height),
                  options.outDir + "/budget_vs_error.png",
                  static_cast<double>(options.width) * options.height * options.refreshHz);
    if (!plotNote.empty()) summary += "\nspeed_vs_error.png and budget_vs_error.png " + plotNote + "\n";
    std::ofstream(options.outDir + "/summary.md") << summary;
    out << summary;
}

}  // namespace warplab::bench
