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
    const exporter::ExportSummary summary = exporter::exportResults(args.positional()[0], args.string("out", "export"), options, std::cerr);
    for (const auto& path : summary.written) std::cout << path << "\n";
    return 0;
}

}  // namespace warplab::app
