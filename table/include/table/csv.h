// Writing tidy CSV files that R, pandas and spreadsheets read the same way: UTF-8, a header
// row, RFC 4180 quoting, '.' decimals, numbers that read back bit for bit, an empty cell for
// "not applicable", and no text cell that a spreadsheet would run as a formula.
#pragma once

#include <cstdint>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

namespace warplab::table {

// True when `text` is well-formed UTF-8 (no stray, cut, overlong or surrogate sequences).
bool isValidUtf8(const std::string& text);

// One text cell as written: invalid UTF-8 bytes become U+FFFD; a cell beginning with = + - @
// (or a tab or carriage return) gets a leading ' so that a spreadsheet shows it as text
// instead of evaluating it, and so does one beginning with ' (the escape stays one-to-one:
// strip one leading ' to read the original); a cell holding , " or a line break is quoted,
// quotes doubled.
std::string csvText(const std::string& text);
// The shortest decimal that reads back as the same double; "" for NaN; "Inf"/"-Inf".
std::string csvNumber(double value);

// Where a row's cells go, each formatted as written above: a CSV file, or a row kept for a
// file written later (Cells).
class CellWriter {
public:
    virtual ~CellWriter() = default;
    CellWriter& text(const std::string& value);
    CellWriter& number(double value);
    CellWriter& integer(std::int64_t value);
    CellWriter& boolean(bool value);  // "true" / "false": R and pandas both read these as logical
    CellWriter& empty();
    // A number its caller formatted (a measurement to the decimals it has), written as it is;
    // throws std::logic_error when it holds , " or a line break, which would split the cell.
    CellWriter& formatted(const std::string& number);

protected:
    virtual void cell(const std::string& written) = 0;
};

// One row's cells, formatted and kept: a table one module fills and another writes (a game's
// own tables, which export writes beside its columns).
class Cells final : public CellWriter {
public:
    const std::vector<std::string>& written() const { return cells_; }
    std::size_t size() const { return cells_.size(); }
    // These cells in another order: cell at[k] as cell k, an empty one where at[k] is negative
    // (a row of one game's columns written under a header with every game's).
    Cells rearranged(const std::vector<int>& at) const;

private:
    void cell(const std::string& written) override { cells_.push_back(written); }
    std::vector<std::string> cells_;
};

// A CSV file written to PATH.partial and renamed into place by close(): a failed or
// interrupted export never leaves a half-written file under the final name.
class CsvFile final : public CellWriter {
public:
    CsvFile(std::string path, const std::vector<std::string>& header);
    // Rows straight to `out` (a command's standard output, or a file its caller keeps open and
    // flushes): nothing to rename. `name` is what path() and errors call it.
    CsvFile(std::ostream& out, const std::vector<std::string>& header, std::string name = "standard output");
    ~CsvFile();  // without close(): removes the partial file
    CsvFile(const CsvFile&) = delete;
    CsvFile& operator=(const CsvFile&) = delete;

    // The cells of a row kept for later, as they were written.
    CsvFile& cells(const Cells& row);
    // Ends the row; throws std::logic_error when it has another number of cells than the header.
    void endRow();

    std::int64_t rows() const { return rows_; }
    const std::string& path() const { return path_; }
    // Flushes, checks the write succeeded and renames into place; SessionError-style
    // std::runtime_error naming the path otherwise.
    void close();

private:
    void cell(const std::string& written) override;
    void writeHeader(const std::vector<std::string>& header);
    std::string path_, partial_;
    std::ofstream file_;
    std::ostream* out_;
    std::size_t columns_ = 0, cellsInRow_ = 0;
    std::int64_t rows_ = 0;
    bool closed_ = false;
};

}  // namespace warplab::table
