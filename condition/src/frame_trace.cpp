#include "condition/frame_trace.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <numeric>

#include "condition/condition.h"

namespace warplab::condition {
namespace {

std::string trim(const std::string& s) {
    std::size_t a = 0, b = s.size();
    while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
    while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
    return s.substr(a, b - a);
}

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t end = text.find('\n', start);
        std::string line = text.substr(start, end == std::string::npos ? std::string::npos : end - start);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        out.push_back(std::move(line));
        if (end == std::string::npos) break;
        start = end + 1;
    }
    return out;
}

std::vector<std::string> fields(const std::string& line) {
    std::vector<std::string> out;
    std::size_t start = 0;
    for (;;) {
        const std::size_t comma = line.find(',', start);
        out.push_back(trim(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
        if (comma == std::string::npos) return out;
        start = comma + 1;
    }
}

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

bool isNumber(const std::string& s, double& out) {
    if (s.empty()) return false;
    errno = 0;
    char* end = nullptr;
    out = std::strtod(s.c_str(), &end);
    return end == s.c_str() + s.size() && errno == 0;
}

// A frame time as a trace gives it, checked: a positive, finite number of ms up to the limit.
// toMs: what one of the trace's units is in ms (MangoHud 0.6 logs microseconds).
double frameMs(const std::string& cell, std::size_t line, const std::string& what, double toMs = 1.0) {
    double value = 0.0;
    if (!isNumber(cell, value) || !std::isfinite(value))
        throw TraceError(line, what + " is \"" + cell.substr(0, 40) + "\", not a number of milliseconds");
    const double ms = value * toMs;
    if (!(ms > 0.0) || ms > kMaxTraceFrameMs)
        throw TraceError(line,
                         what + " is " + number(ms) + " ms; a frame time must be above 0 and at most " +
                             number(kMaxTraceFrameMs) + " ms");
    return ms;
}

// The index of the first of `names` among a header's columns (case-insensitive), or npos.
std::size_t column(const std::vector<std::string>& header, std::initializer_list<const char*> names) {
    for (const char* name : names)
        for (std::size_t i = 0; i < header.size(); ++i)
            if (lower(header[i]) == lower(name)) return i;
    return std::string::npos;
}

// MangoHud's frame-time column, in ms; the log starts with a line of system fields
// (os,cpu,gpu,...), their values, and in some versions a "----DATA----" line.
constexpr const char* kMangoHudColumn = "frametime";
// PresentMon's: msBetweenPresents (1.x), MsBetweenPresents (2.x, and CapFrameX's CSV), FrameTime
// (2.x's newer metrics).
constexpr std::initializer_list<const char*> kPresentMonColumns = {"msBetweenPresents", "FrameTime"};
constexpr const char* kEmpty = "is empty: a trace needs at least one frame time";
// How far into a MangoHud log its column header may be.
constexpr std::size_t kMangoHudHeaderWithin = 6;

// MangoHud writes its column in lower case; PresentMon 2's FrameTime is another column.
bool isMangoHudHeader(const std::vector<std::string>& header) {
    return std::find(header.begin(), header.end(), kMangoHudColumn) != header.end();
}
bool isPresentMonHeader(const std::vector<std::string>& header) {
    return column(header, kPresentMonColumns) != std::string::npos;
}

void checkLength(std::size_t frames, std::size_t line) {
    if (frames > kMaxTraceFrames)
        throw TraceError(line,
                         "is past the " + std::to_string(kMaxTraceFrames) +
                             "th frame, more than a trace may hold; cut the file to the stretch to play");
}

std::vector<double> columnValues(const std::vector<std::string>& text, std::size_t headerLine, std::size_t col,
                                 const std::string& what, bool skipFirstZero,
                                 const std::vector<std::size_t>& sameAcrossRows, double toMs = 1.0) {
    const std::size_t width = fields(text[headerLine]).size();
    std::vector<double> ms;
    std::vector<std::string> first;
    for (std::size_t i = headerLine + 1; i < text.size(); ++i) {
        if (trim(text[i]).empty()) continue;
        const std::vector<std::string> row = fields(text[i]);
        if (row.size() != width)
            throw TraceError(
                i + 1, "has " + std::to_string(row.size()) + " fields where the header has " + std::to_string(width));
        std::vector<std::string> key;
        for (const std::size_t k : sameAcrossRows) key.push_back(row[k]);
        if (first.empty() && ms.empty()) first = key;
        if (key != first) {
            std::string a, b;
            for (std::size_t k = 0; k < key.size(); ++k) {
                a += (k ? " " : "") + first[k];
                b += (k ? " " : "") + key[k];
            }
            throw TraceError(i + 1,
                             "is a frame of another swap chain (" + b + ", the first rows' " + a +
                                 "): record one process (PresentMon --process_name) or split the "
                                 "file with --multi_csv");
        }
        double value = 0.0;
        if (skipFirstZero && ms.empty() && isNumber(row[col], value) && value == 0.0) {
            skipFirstZero = false;
            continue;
        }
        skipFirstZero = false;
        ms.push_back(frameMs(row[col], i + 1, what, toMs));
        checkLength(ms.size(), i + 1);
    }
    return ms;
}

std::size_t indexOf(const std::vector<std::string>& header, const char* name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
}

// The median of a row's frametime x fps: about 1000 when frametime is in ms (MangoHud 0.7 on),
// 10^6 when it is in microseconds (MangoHud 0.6, as Debian 12 ships it).
double medianTimesFps(const std::vector<std::string>& text, std::size_t headerLine, std::size_t timeCol,
                      std::size_t fpsCol) {
    std::vector<double> products;
    for (std::size_t i = headerLine + 1; i < text.size(); ++i) {
        const std::vector<std::string> row = fields(text[i]);
        double t = 0.0, fps = 0.0;
        if (row.size() > std::max(timeCol, fpsCol) && isNumber(row[timeCol], t) && isNumber(row[fpsCol], fps))
            products.push_back(t * fps);
    }
    if (products.empty()) return 1000.0;
    const auto middle = products.begin() + static_cast<std::ptrdiff_t>(products.size() / 2);
    std::nth_element(products.begin(), middle, products.end());
    return *middle;
}

// A log written every log_interval (100 ms by default) holds one frame per interval, not every
// frame: its frame times fall far short of the time its `elapsed` column (ns) spans.
void requireEveryFrame(const std::vector<std::string>& text, std::size_t headerLine, const std::vector<double>& ms) {
    const std::size_t col = indexOf(fields(text[headerLine]), "elapsed");
    std::vector<double> elapsed;
    for (std::size_t i = headerLine + 1; i < text.size(); ++i) {
        const std::vector<std::string> row = fields(text[i]);
        double e = 0.0;
        if (col < row.size() && isNumber(row[col], e)) elapsed.push_back(e);
    }
    if (elapsed.size() != ms.size() || ms.size() < 3) return;
    const double rows = static_cast<double>(ms.size() - 1);
    const double spanMs = (elapsed.back() - elapsed.front()) / 1e6;
    const double framesMs = std::accumulate(ms.begin() + 1, ms.end(), 0.0);
    if (framesMs < 0.5 * spanMs)
        throw TraceError(0,
                         "holds a row every " + number(spanMs / rows) + " ms but frames of " + number(framesMs / rows) +
                             " ms: MangoHud logged one frame each log_interval, not every frame; record with "
                             "log_interval=0");
}

std::vector<double> mangoHud(const std::vector<std::string>& text) {
    for (std::size_t i = 0; i < text.size() && i < kMangoHudHeaderWithin; ++i) {
        const std::vector<std::string> header = fields(text[i]);
        if (!isMangoHudHeader(header)) continue;
        const std::size_t col = indexOf(header, kMangoHudColumn), fps = indexOf(header, "fps");
        const bool micro = fps < header.size() && medianTimesFps(text, i, col, fps) > 30000.0;
        const std::vector<double> ms =
            columnValues(text, i, col, micro ? "frametime (microseconds, as MangoHud 0.6 logs it)" : kMangoHudColumn,
                         false, {}, micro ? 1e-3 : 1.0);
        requireEveryFrame(text, i, ms);
        return ms;
    }
    throw TraceError(0,
                     std::string("is not a MangoHud log: none of its first ") + std::to_string(kMangoHudHeaderWithin) +
                         " lines is a header with a " + kMangoHudColumn + " column");
}

std::vector<double> presentMon(const std::vector<std::string>& text) {
    const std::vector<std::string> header = fields(text.front());
    const std::size_t col = column(header, kPresentMonColumns);
    if (col == std::string::npos)
        throw TraceError(1,
                         "is not a PresentMon header: it has no msBetweenPresents, MsBetweenPresents or "
                         "FrameTime column");
    std::vector<std::size_t> chain;
    for (const char* name : {"Application", "ProcessID", "SwapChainAddress"})
        if (const std::size_t k = column(header, {name}); k != std::string::npos) chain.push_back(k);
    return columnValues(text, 0, col, header[col], true, chain);
}

std::vector<double> list(const std::vector<std::string>& text) {
    std::vector<double> ms;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const std::string line = trim(text[i]);
        if (line.empty() || line[0] == '#') continue;
        ms.push_back(frameMs(line, i + 1, "the frame time"));
        checkLength(ms.size(), i + 1);
    }
    return ms;
}

}  // namespace

double FrameTrace::scale() const {
    if (!meanHz || recordedMs.empty()) return 1.0;
    const double mean =
        std::accumulate(recordedMs.begin(), recordedMs.end(), 0.0) / static_cast<double>(recordedMs.size());
    return 1000.0 / *meanHz / mean;
}

double FrameTrace::playedHz() const {
    if (meanHz) return *meanHz;
    const double total = std::accumulate(recordedMs.begin(), recordedMs.end(), 0.0);
    return 1000.0 * static_cast<double>(recordedMs.size()) / total;
}

double FrameTrace::longestPlayedMs() const {
    return recordedMs.empty() ? 0.0 : *std::max_element(recordedMs.begin(), recordedMs.end()) * scale();
}

std::size_t FrameTrace::firstFrame() const {
    if (recordedMs.empty()) return 0;
    const double k = scale();
    const double total = std::accumulate(recordedMs.begin(), recordedMs.end(), 0.0) * k;
    const double into = std::fmod(offsetS * 1000.0, total);
    double t = 0.0;
    for (std::size_t i = 0; i < recordedMs.size(); ++i) {
        t += recordedMs[i] * k;
        if (t > into) return i;
    }
    return 0;
}

std::string detectTraceFormat(const std::string& text) {
    bool blank = true;
    for (const std::string& raw : lines(text)) blank = blank && trim(raw).empty();
    if (blank) throw TraceError(0, kEmpty);
    for (const std::string& raw : lines(text)) {
        const std::string line = trim(raw);
        if (line.empty() || line[0] == '#') continue;
        const std::vector<std::string> header = fields(line);
        double value = 0.0;
        if (header.size() == 1 && isNumber(line, value)) return "list";
        if (lower(header.front()) == "os" || isMangoHudHeader(header)) return "mangohud";
        if (isPresentMonHeader(header)) return "presentmon";
        break;
    }
    throw TraceError(0,
                     "is not a frame-time trace warplab reads: a MangoHud CSV log (a header with frametime), "
                     "a PresentMon CSV (msBetweenPresents, MsBetweenPresents or FrameTime) or one frame time "
                     "in ms per line");
}

std::vector<double> parseTrace(const std::string& text, const std::string& format) {
    std::vector<std::string> all = lines(text);
    while (!all.empty() && trim(all.back()).empty()) all.pop_back();
    if (all.empty()) throw TraceError(0, kEmpty);
    std::vector<double> ms;
    if (format == "mangohud")
        ms = mangoHud(all);
    else if (format == "presentmon")
        ms = presentMon(all);
    else if (format == "list")
        ms = list(all);
    else
        throw TraceError(0, "has no format \"" + format + "\" (known: mangohud, presentmon, list)");
    if (ms.empty()) throw TraceError(0, "holds no frame times after its header");
    return ms;
}

}  // namespace warplab::condition
