// The session records' column tables, and replay's comparison that walks them.
#include "session/records.h"

#include "schema.h"

#include <cstring>
#include <locale>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

namespace warplab::session {

// Table order is the order of the columns in the file and of the checksum's serialisation:
// changing it (or a column) is a format version bump (docs/session-format.md).
template <>
const std::vector<Field<InputRecord>>& fieldsOf<InputRecord>() {
    using R = InputRecord;
    static const std::vector<Field<R>> fields = {
        {"frame", &R::frame},      {"display_time", &R::displayTime}, {"mouse_dx", &R::mouseDx},
        {"mouse_dy", &R::mouseDy}, {"buttons", &R::buttons},          {"keys", &R::keys},
        {"text", &R::text},
    };
    return fields;
}

template <>
const std::vector<Field<FrameRecord>>& fieldsOf<FrameRecord>() {
    using R = FrameRecord;
    static const std::vector<Field<R>> fields = {
        {"frame", &R::frame},
        {"mode", &R::condition},
        {"kind", &R::kind},
        {"frame_ms", &R::frameMs},
        {"render_ms", &R::renderMs},
        {"missed_vsyncs", &R::missedVsyncs},
        {"camera_yaw", &R::cameraYaw},
        {"camera_pitch", &R::cameraPitch},
        {"detail_json", &R::detailJson, /*jsonObject=*/true},
    };
    return fields;
}

template <>
const std::vector<Field<EventRecord>>& fieldsOf<EventRecord>() {
    using R = EventRecord;
    static const std::vector<Field<R>> fields = {
        {"frame", &R::frame},
        {"type", &R::type},
        {"phase", &R::phase},
        {"trial", &R::trial},
        {"mode", &R::condition},
        {"event_time", &R::eventTime},
        {"world_outcome", &R::worldOutcome},
        {"displayed_outcome", &R::displayedOutcome},
        {"detail_json", &R::detailJson, /*jsonObject=*/true},
    };
    return fields;
}

namespace {

using Json = nlohmann::json;

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// "" is the object with no keys; anything but an object is nullopt.
std::optional<Json> parseObject(const std::string& text) {
    if (text.empty()) return Json::object();
    Json parsed = Json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (!parsed.is_object()) return std::nullopt;
    return parsed;
}

// JSON values compared as replay needs them: numbers by value, doubles bit for bit (an
// integer stands for the double of the same value; two integers compare exactly), everything
// else structurally with the same rule inside.
bool sameJson(const Json& a, const Json& b) {
    if (a.is_number() && b.is_number()) {
        if (a.is_number_float() || b.is_number_float()) return sameBits(a.get<double>(), b.get<double>());
        return a == b;
    }
    if (a.type() != b.type()) return false;
    if (a.is_array()) {
        if (a.size() != b.size()) return false;
        for (std::size_t i = 0; i < a.size(); ++i)
            if (!sameJson(a[i], b[i])) return false;
        return true;
    }
    if (a.is_object()) {
        if (a.size() != b.size()) return false;
        for (auto it = a.begin(); it != a.end(); ++it) {
            const auto other = b.find(it.key());
            if (other == b.end() || !sameJson(it.value(), *other)) return false;
        }
        return true;
    }
    return a == b;
}

class Difference {
public:
    Difference() {
        out_.imbue(std::locale::classic());
        out_.precision(17);
    }
    bool found() const { return found_; }
    std::string text() const { return out_.str(); }

    template <class T>
    void number(const char* column, T logged, T replayed) {
        if (logged != replayed) say(column, logged, replayed);
    }
    void number(const char* column, double logged, double replayed) {
        // Bit for bit: replay is exact or it is wrong.
        if (!sameBits(logged, replayed)) say(column, logged, replayed);
    }
    void text(const char* column, const std::string& logged, const std::string& replayed) {
        if (logged != replayed) say(column, "'" + logged + "'", "'" + replayed + "'");
    }
    void jsonObject(const char* column, const std::string& logged, const std::string& replayed) {
        if (logged == replayed) return;
        const auto a = parseObject(logged), b = parseObject(replayed);
        if (!a || !b) return text(column, logged, replayed);
        // Both are std::map-backed: walk the two sorted key lists together.
        auto i = a->begin(), j = b->begin();
        while (i != a->end() || j != b->end()) {
            const bool takeA = j == b->end() || (i != a->end() && i.key() <= j.key());
            const bool takeB = i == a->end() || (j != b->end() && j.key() <= i.key());
            const std::string key = takeA ? i.key() : j.key();
            const std::string name = "detail." + key;
            if (!takeB) return say(name.c_str(), i.value().dump(), std::string("(absent)"));
            if (!takeA) return say(name.c_str(), std::string("(absent)"), j.value().dump());
            if (!sameJson(i.value(), j.value())) return say(name.c_str(), i.value().dump(), j.value().dump());
            ++i;
            ++j;
        }
    }

private:
    template <class A>
    void say(const char* column, const A& logged, const A& replayed) {
        out_ << "field '" << column << "' logged " << logged << ", replayed " << replayed;
        found_ = true;
    }

    std::ostringstream out_;
    bool found_ = false;
};

template <class R>
std::string firstDifferenceOf(const R& logged, const R& replayed) {
    Difference d;
    for (const Field<R>& field : fieldsOf<R>()) {
        std::visit(
            [&](auto member) {
                const auto& a = logged.*member;
                const auto& b = replayed.*member;
                using T = std::decay_t<decltype(a)>;
                if constexpr (std::is_same_v<T, std::string>) {
                    if (field.storage == Storage::JsonObject)
                        d.jsonObject(field.column, a, b);
                    else
                        d.text(field.column, a, b);
                } else {
                    d.number(field.column, a, b);
                }
            },
            field.member);
        if (d.found()) break;
    }
    return d.text();
}

}  // namespace

bool isJsonObjectOrEmpty(const std::string& text) {
    // The writer checks every frame's detail: accept() validates without building the value,
    // and valid JSON that opens with '{' is an object.
    if (text.empty()) return true;
    const std::size_t first = text.find_first_not_of(" \t\n\r");
    return first != std::string::npos && text[first] == '{' && Json::accept(text);
}

std::string firstDifference(const InputRecord& logged, const InputRecord& replayed) {
    return firstDifferenceOf(logged, replayed);
}
std::string firstDifference(const FrameRecord& logged, const FrameRecord& replayed) {
    return firstDifferenceOf(logged, replayed);
}
std::string firstDifference(const EventRecord& logged, const EventRecord& replayed) {
    return firstDifferenceOf(logged, replayed);
}

}  // namespace warplab::session

namespace warplab::session::detail {

std::string resumedText(const std::vector<Resumption>& resumed) {
    nlohmann::json list = nlohmann::json::array();
    for (const Resumption& r : resumed)
        list.push_back({{"session_id", r.sessionId},
                        {"file", r.file},
                        {"started_at", r.startedAt},
                        {"player", r.player},
                        {"frame", r.frame},
                        {"resumed_at", r.resumedAt}});
    return list.dump();
}

bool parseResumed(const std::string& text, std::vector<Resumption>& out) {
    const auto list = nlohmann::json::parse(text, nullptr, false);
    if (!list.is_array()) return false;
    out.clear();
    for (const auto& item : list) {
        if (!item.is_object()) return false;
        Resumption r;
        for (auto [key, member] :
             {std::pair{"session_id", &r.sessionId}, std::pair{"file", &r.file}, std::pair{"started_at", &r.startedAt},
              std::pair{"player", &r.player}, std::pair{"resumed_at", &r.resumedAt}}) {
            const auto it = item.find(key);
            if (it == item.end() || !it->is_string()) return false;
            *member = it->get<std::string>();
        }
        const auto frame = item.find("frame");
        if (frame == item.end() || !frame->is_number_integer() || frame->get<std::int64_t>() < 0) return false;
        r.frame = frame->get<std::int64_t>();
        out.push_back(std::move(r));
    }
    return true;
}

}  // namespace warplab::session::detail
