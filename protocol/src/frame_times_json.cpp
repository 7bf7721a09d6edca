// A condition's "frame_times" (docs/frame-pacing.md, "Traces"): a real game's frame times, read
// from a trace file beside the protocol or, in the copy a session stores, from the frame times
// written inline, so that a session replays without the file.
#include <openssl/evp.h>

#include <cstdio>
#include <filesystem>

#include "protocol/fields.h"

namespace warplab::protocol::fields {
namespace {

const std::vector<const char*> kFrameTimesKeys{"file", "format", "sha256", "offset_s", "mean_hz", "ms"};
// A trace file is read whole; its frame times are bounded (kMaxTraceFrames), so its size is too.
constexpr std::size_t kMaxTraceBytes = 64u << 20;

// SHA-256 of the file's bytes, as `sha256sum` prints it, so a lab can name the exact recording.
std::string sha256Hex(const std::string& bytes) {
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int size = 0;
    if (EVP_Digest(bytes.data(), bytes.size(), digest, &size, EVP_sha256(), nullptr) != 1)
        throw std::runtime_error("SHA-256 of a trace file failed in OpenSSL");
    std::string hex;
    char pair[3];
    for (unsigned int i = 0; i < size; ++i) {
        std::snprintf(pair, sizeof pair, "%02x", digest[i]);
        hex += pair;
    }
    return hex;
}

// The trace's path: as written when absolute, else beside the protocol file.
std::string besideProtocol(const std::string& protocolPath, const std::string& file) {
    const std::filesystem::path path(file);
    if (path.is_absolute()) return file;
    return (std::filesystem::path(protocolPath).parent_path() / path).string();
}

}  // namespace

void Reader::frameTimes(const Json& value, const std::string& path, condition::Condition& c) const {
    const Json* trace = object(value, path, "frame_times");
    const std::string where = joinPath(path, "frame_times");
    requireKnownKeys(*trace, where, kFrameTimesKeys);
    if (!trace->contains("file") && !trace->contains("ms"))
        fail(where,
             "needs file: the trace file to play (MangoHud CSV, PresentMon CSV or one frame time in ms per line)");
    auto t = std::make_shared<condition::FrameTrace>();
    string(trace, where, "file", t->file);
    std::vector<const char*> formats(std::begin(condition::kTraceFormats), std::end(condition::kTraceFormats));
    choice(trace, where, "format", formats, t->format);
    string(trace, where, "sha256", t->sha256);
    number(trace, where, "offset_s", {0, false, 86400, false}, t->offsetS);
    if (trace->contains("mean_hz")) {
        double hz = 0.0;
        number(trace, where, "mean_hz", {0, true, kRefreshLimitHz, false}, hz);
        t->meanHz = hz;
    }
    if (const Json* ms = array(trace, where, "ms", "frame times in ms")) {
        // The frame times themselves: what a stored protocol copy keeps. file, format and sha256
        // then only say where they came from.
        const std::string list = joinPath(where, "ms");
        if (ms->size() > condition::kMaxTraceFrames)
            fail(list,
                 "holds " + std::to_string(ms->size()) + " frame times, more than a trace may (" +
                     std::to_string(condition::kMaxTraceFrames) + ")");
        for (std::size_t i = 0; i < ms->size(); ++i)
            t->recordedMs.push_back(
                numberAt((*ms)[i], elementPath(list, i), {0, true, condition::kMaxTraceFrameMs, false}));
    } else {
        const std::string filePath = besideProtocol(source().path, t->file);
        const strict::FileText text = strict::readRegularFile(filePath, kMaxTraceBytes, "trace file");
        const std::string named = "'" + t->file + "'";
        if (!text.problem.empty()) fail(joinPath(where, "file"), named + " " + text.problem);
        const std::string hash = sha256Hex(text.text);
        if (!t->sha256.empty() && t->sha256 != hash)
            fail(joinPath(where, "sha256"),
                 "is " + t->sha256 + ", but the file " + named + " has SHA-256 " + hash +
                     ": the trace has changed since the protocol named it");
        t->sha256 = hash;
        try {
            if (t->format.empty()) t->format = condition::detectTraceFormat(text.text);
            t->recordedMs = condition::parseTrace(text.text, t->format);
        } catch (const condition::TraceError& e) {
            fail(joinPath(where, "file"),
                 named + (e.line() ? " line " + std::to_string(e.line()) : std::string()) + " " + e.what());
        }
    }
    c.frameTimes = t;
    c.renderHz = t->playedHz();
}

void writeFrameTimes(Json& o, const condition::Condition& c) {
    if (!c.frameTimes) return;
    const condition::FrameTrace& t = *c.frameTimes;
    Json& j = o["frame_times"];
    if (!t.file.empty()) j["file"] = t.file;
    if (!t.format.empty()) j["format"] = t.format;
    if (!t.sha256.empty()) j["sha256"] = t.sha256;
    if (t.offsetS != 0.0) j["offset_s"] = t.offsetS;
    if (t.meanHz) j["mean_hz"] = *t.meanHz;
    j["ms"] = t.recordedMs;
}

}  // namespace warplab::protocol::fields
