// `warplab export RESULTS --out DIR`: the session files of a results folder as tidy CSVs.
#include <iostream>

#include "commands.h"
#include "export/export.h"

namespace warplab::app {

int runExport(const ParsedArgs& args) {
    if (args.positional().size() != 1)
        throw UsageError(args.positional().empty() ? "name the results folder to export"
                                                   : "export takes one results folder, got " +
                                 std::to_string(args.positional().size()) + " arguments");
    exporter::ExportOptions options;
    options.allPhases = args.flag("all-phases");
    options.includeIncomplete = args.flag("include-incomplete");
    options.includeFlagged = args.flag("include-flagged");
    options.studyDir = args.string("study", "");
    const exporter::ExportSummary summary =
        exporter::exportResults(args.positional()[0], args.string("out", "export"), options, std::cerr);
    for (const auto& path : summary.written) std::cout << path << "\n";
    return 0;
}

// The command's options, beside the code that reads them.
Command exportCommand() {
    return {{"export",
             "Merge every session file of a results folder (sub-folders too) into tidy CSVs for the\n"
             "analysis: sessions, shots/clicks, hit rates per participant x game x condition, matches,\n"
             "ratings, answers to the questions after blocks, and a study plan's participants\n"
             "(docs/export.md). Read-only; damaged files are reported and skipped.",
             "warplab export RESULTS [--out DIR] [--all-phases] [--include-incomplete] [--include-flagged]",
             {
                 {"out", "DIR", "where the CSVs go (created when missing)", "export"},
                 {"all-phases", "", "also practice rounds, acclimation and training (hit rates stay scored-only)", ""},
                 {"include-incomplete", "",
                  "also sessions that never finished (killed mid-way): their completed trials", ""},
                 {"include-flagged", "", "also sessions flagged during their run (e.g. too many missed frames)", ""},
                 {"study", "DIR", "the study plan (DIR/study.json) that participants.csv lists",
                  "RESULTS/.. when the sessions were run from a plan"},
             },
             true},
            &runExport};
}

}  // namespace warplab::app
