#include "archive.h"

#include "session/records.h"

#include <cstring>
#include <type_traits>

namespace warplab::session::detail {
namespace {

void putI64(std::string& out, std::int64_t v) {
    char b[8];
    std::memcpy(b, &v, sizeof b);
    out.append(b, sizeof b);
}
void putText(std::string& out, const std::string& v) {
    putI64(out, static_cast<std::int64_t>(v.size()));
    out += v;
}

class Cursor {
public:
    explicit Cursor(const std::string& bytes) : bytes_(bytes) {}
    bool more() const { return at_ < bytes_.size(); }
    std::int64_t i64() {
        std::int64_t v;
        std::memcpy(&v, bytes_.data() + at_, sizeof v);
        at_ += sizeof v;
        return v;
    }
    std::string text() {
        const auto n = static_cast<std::size_t>(i64());
        std::string v = bytes_.substr(at_, n);
        at_ += n;
        return v;
    }

private:
    const std::string& bytes_;
    std::size_t at_ = 0;
};

template <typename R>
void putRows(std::string& out, const std::vector<R>& rows) {
    putI64(out, static_cast<std::int64_t>(rows.size()));
    for (const R& r : rows)
        forEachField(r, [&](const auto&, const auto& v) {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, std::string>)
                putText(out, v);
            else if constexpr (std::is_same_v<T, double>) {
                std::int64_t bits;
                std::memcpy(&bits, &v, sizeof bits);
                putI64(out, bits);
            } else
                putI64(out, static_cast<std::int64_t>(v));
        });
}

template <typename R>
std::vector<R> takeRows(Cursor& in) {
    std::vector<R> rows(static_cast<std::size_t>(in.i64()));
    for (R& r : rows)
        forEachField(r, [&](const auto&, auto& v) {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, std::string>)
                v = in.text();
            else if constexpr (std::is_same_v<T, double>) {
                const std::int64_t bits = in.i64();
                std::memcpy(&v, &bits, sizeof v);
            } else
                v = static_cast<T>(in.i64());
        });
    return rows;
}

}  // namespace

void Archive::append(const CommitRows& c) {
    putI64(bytes_, c.inputRows);
    putI64(bytes_, c.frameRows);
    putI64(bytes_, c.eventRows);
    putI64(bytes_, c.lastFrame ? 1 : 0);
    putI64(bytes_, c.lastFrame.value_or(0));
    putI64(bytes_, c.checksum);
    putText(bytes_, c.committedAt);
    putRows(bytes_, c.inputs);
    putRows(bytes_, c.frames);
    putRows(bytes_, c.events);
    ++commits_;
}

void Archive::forEach(const std::function<void(const CommitRows&)>& f) const {
    Cursor in(bytes_);
    while (in.more()) {
        CommitRows c;
        c.inputRows = in.i64();
        c.frameRows = in.i64();
        c.eventRows = in.i64();
        const bool hasLastFrame = in.i64() != 0;
        const std::int64_t lastFrame = in.i64();
        if (hasLastFrame) c.lastFrame = lastFrame;
        c.checksum = in.i64();
        c.committedAt = in.text();
        c.inputs = takeRows<InputRecord>(in);
        c.frames = takeRows<FrameRecord>(in);
        c.events = takeRows<EventRecord>(in);
        f(c);
    }
}

}  // namespace warplab::session::detail
