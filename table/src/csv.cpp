#include "table/csv.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

namespace warplab::table {
namespace {

// Length of the valid UTF-8 sequence starting at s[i], or 0 when it is not one (overlong
// forms, surrogates and code points past U+10FFFF are invalid too).
std::size_t utf8Length(const std::string& s, std::size_t i) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
    const unsigned char c = byte(i);
    if (c < 0x80) return 1;
    std::size_t n;
    unsigned min;
    unsigned cp;
    if ((c & 0xE0) == 0xC0)
        n = 2, min = 0x80, cp = c & 0x1F;
    else if ((c & 0xF0) == 0xE0)
        n = 3, min = 0x800, cp = c & 0x0F;
    else if ((c & 0xF8) == 0xF0)
        n = 4, min = 0x10000, cp = c & 0x07;
    else
        return 0;
    if (i + n > s.size()) return 0;
    for (std::size_t k = 1; k < n; ++k) {
        if ((byte(i + k) & 0xC0) != 0x80) return 0;
        cp = (cp << 6) | (byte(i + k) & 0x3F);
    }
    if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
    return n;
}

}  // namespace

bool isValidUtf8(const std::string& text) {
    for (std::size_t i = 0; i < text.size();) {
        const std::size_t n = utf8Length(text, i);
        if (n == 0) return false;
        i += n;
    }
    return true;
}

std::string csvText(const std::string& text) {
    std::string valid;
    valid.reserve(text.size() + 2);
    for (std::size_t i = 0; i < text.size();) {
        const std::size_t n = utf8Length(text, i);
        if (n == 0) {
            valid += "\xEF\xBF\xBD";  // U+FFFD REPLACEMENT CHARACTER
            ++i;
        } else {
            valid.append(text, i, n);
            i += n;
        }
    }
    // OWASP's "CSV injection" advice: these first characters start a formula in Excel,
    // LibreOffice and Google Sheets. A text that already begins with ' gets one too, so that
    // the escape is one-to-one: "=1" is written '=1 and "'=1" is written ''=1, and dropping
    // one leading ' gives back every original.
    if (!valid.empty() && std::string("=+-@\t\r'").find(valid.front()) != std::string::npos) valid.insert(0, "'");
    if (valid.find_first_of(",\"\r\n") == std::string::npos) return valid;
    std::string quoted = "\"";
    for (char c : valid) {
        if (c == '"') quoted += '"';
        quoted += c;
    }
    return quoted + '"';
}

std::string csvNumber(double value) {
    if (std::isnan(value)) return "";
    if (std::isinf(value)) return value > 0 ? "Inf" : "-Inf";
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

CsvFile::CsvFile(std::string path, const std::vector<std::string>& header)
    : path_(std::move(path)),
      partial_(path_ + ".partial"),
      file_(partial_, std::ios::binary | std::ios::trunc),
      out_(&file_),
      columns_(header.size()) {
    if (!file_) throw std::runtime_error("cannot write '" + partial_ + "'");
    writeHeader(header);
}

CsvFile::CsvFile(std::ostream& out, const std::vector<std::string>& header, std::string name)
    : path_(std::move(name)), out_(&out), columns_(header.size()), closed_(true) {
    writeHeader(header);
}

void CsvFile::writeHeader(const std::vector<std::string>& header) {
    for (const auto& name : header) text(name);
    endRow();
    rows_ = 0;
}

CsvFile::~CsvFile() {
    if (!closed_) {
        file_.close();
        std::remove(partial_.c_str());
    }
}

void CsvFile::cell(const std::string& written) {
    if (cellsInRow_++ > 0) *out_ << ',';
    *out_ << written;
}

CellWriter& CellWriter::text(const std::string& value) {
    cell(csvText(value));
    return *this;
}
CellWriter& CellWriter::number(double value) {
    cell(csvNumber(value));
    return *this;
}
CellWriter& CellWriter::integer(std::int64_t value) {
    cell(std::to_string(value));
    return *this;
}
CellWriter& CellWriter::boolean(bool value) {
    cell(value ? "true" : "false");
    return *this;
}
CellWriter& CellWriter::empty() {
    cell("");
    return *this;
}
CellWriter& CellWriter::formatted(const std::string& number) {
    if (number.find_first_of(",\"\r\n") != std::string::npos)
        throw std::logic_error("'" + number + "' is not a number's text");
    cell(number);
    return *this;
}

CsvFile& CsvFile::cells(const Cells& row) {
    for (const std::string& written : row.written()) cell(written);
    return *this;
}

void CsvFile::endRow() {
    if (cellsInRow_ != columns_)
        throw std::logic_error(path_ + ": a row of " + std::to_string(cellsInRow_) + " cells under a header of " +
                               std::to_string(columns_));
    // CRLF is RFC 4180's line end, but LF is what R, pandas and spreadsheets all accept and
    // what diff and grep expect.
    *out_ << '\n';
    cellsInRow_ = 0;
    ++rows_;
}

void CsvFile::close() {
    if (partial_.empty()) {
        out_->flush();
        return;
    }
    file_.flush();
    const bool ok = static_cast<bool>(file_);
    file_.close();
    if (!ok || file_.fail()) throw std::runtime_error("writing '" + partial_ + "' failed (disk full?)");
    if (std::rename(partial_.c_str(), path_.c_str()) != 0)
        throw std::runtime_error("cannot rename '" + partial_ + "' to '" + path_ + "'");
    closed_ = true;
}

Cells Cells::rearranged(const std::vector<int>& at) const {
    Cells out;
    for (const int k : at) out.cells_.push_back(k < 0 ? std::string() : cells_.at(static_cast<std::size_t>(k)));
    return out;
}

}  // namespace warplab::table
