// bench.csv byte for byte: its header, and rows whose every column says something (a
// correspondence, stages, a negative SSIM, an exact frame's infinite PSNR) or nothing (NaN and
// "does not apply" as empty cells). analysis/plot_bench.py and earlier runs' files read these
// bytes, so a change to how the bench writes them must show here.
#include <gtest/gtest.h>

#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "summary.h"

namespace warplab::bench {
namespace {

const std::string kHeader =
    "sequence,method,frame,time_s,psnr_db,ssim,border_mae,border_px,disocc_mae,disocc_px,corr_all_lt_0p1,"
    "corr_all_lt_0p5,corr_all_lt_1,corr_hit_lt_0p1,corr_hit_lt_0p5,corr_hit_lt_1,pass_ms,gpu_ms,conventional_ms,"
    "source_ms,triangles,stage_ms,budget_share,family,age_mean_ms,age_p95_ms\n";

// bench.csv as runBench writes it: the header, then `rows`.
std::string csvOf(const std::vector<Row>& rows) {
    std::ostringstream out;
    table::CsvFile csv(out, table::headerOf(csvColumns()));
    for (const Row& r : rows) writeRow(csv, r);
    return out.str();
}

Row everyColumn() {
    Row r;
    r.sequence = "pan";
    r.method = "warp-splat";
    r.frame = 3;
    r.time = 0.125;
    r.psnr = std::numeric_limits<double>::infinity();
    r.ssim = -0.25;
    r.borderMae = 1.23456;
    r.borderPx = 42;
    r.disoccMae = 0.5;
    r.disoccPx = 7;
    r.hasCorr = true;
    r.corr.allLt0p1 = 0.5;
    r.corr.allLt0p5 = 0.75;
    r.corr.allLt1 = 1.0;
    r.corr.hitLt0p1 = 0.25;
    r.corr.hitLt0p5 = 0.125;
    r.corr.hitLt1 = 0.0;
    r.passMs = 12.375;
    r.gpuMs = 2.5;
    r.conventionalMs = 30.0;
    r.sourceMs = 31.25;
    r.triangles = 1234.0;
    r.stages = {{"splat", 1.5}, {"resolve", 0.25}};
    r.budgetShare = 0.125;
    r.family = "whole frames";
    r.ageMeanMs = 33.3333333;
    r.ageP95Ms = 62.5;
    return r;
}

TEST(BenchCsv, WritesTheHeaderAndEveryColumnOfARow) {
    EXPECT_EQ(csvOf({everyColumn()}),
              kHeader +
                  "pan,warp-splat,3,0.125000,inf,-0.25000,1.235,42,0.500,7,0.5000,0.7500,1.0000,0.2500,0.1250,0.0000,"
                  "12.375,2.500,30.000,31.250,1234,splat=1.500;resolve=0.250,0.125000,whole frames,33.333,62.500\n");
}

TEST(BenchCsv, WritesWhatDoesNotApplyAsEmptyCells) {
    Row r;  // NaN measures, no correspondence, no stages
    r.sequence = "thin";
    r.method = "hold15";
    EXPECT_EQ(csvOf({r}), kHeader + "thin,hold15,0,0.000000,,,,0,,0,,,,,,,,,,,,,,,,\n");
}

}  // namespace
}  // namespace warplab::bench
