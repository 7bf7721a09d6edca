// Private to export/: the CSV writer and column tables of table/, under the names export's
// files and tables are written with.
#pragma once

#include "table/columns.h"
#include "table/csv.h"

namespace warplab::exporter {

using table::CellWriter;
using table::Column;
using table::CsvFile;
using table::headerOf;
using table::writeCells;

}  // namespace warplab::exporter
