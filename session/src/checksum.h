// Private to session/: the per-commit checksums the writer stores and the reader verifies.
#pragma once

#include "schema.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>

namespace warplab::session::detail {

// SQLite has no page checksums: a file cut inside a page reads back with zeros in place of
// the lost bytes and no error. So every commit carries a checksum of its own rows (and the
// header one of its own), and the reader keeps only commits that verify. FNV-1a 64 over a
// fixed little-endian serialisation of each row's fields in table order, spelled out in
// docs/session-format.md.
class Checksum {
public:
    void i64(std::int64_t v) {
        auto u = static_cast<std::uint64_t>(v);
        for (int i = 0; i < 8; ++i, u >>= 8) byte(static_cast<unsigned char>(u & 0xff));
    }
    void f64(double v) {
        // NaN is stored as NULL and read back as the quiet NaN, so hash that one.
        if (std::isnan(v)) v = std::numeric_limits<double>::quiet_NaN();
        std::uint64_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        i64(static_cast<std::int64_t>(bits));
    }
    void text(const std::string& v) {
        i64(static_cast<std::int64_t>(v.size()));
        for (const char c : v) byte(static_cast<unsigned char>(c));
    }
    std::uint64_t value() const { return h_; }

private:
    void byte(unsigned char b) { h_ = (h_ ^ b) * 0x100000001b3ull; }
    std::uint64_t h_ = 0xcbf29ce484222325ull;
};

// Integers as 8-byte integers, doubles as their bits, texts (JSON ones too) as length and
// bytes; the events' id is not hashed.
template <typename Row>
void hashRow(Checksum& c, const Table<Row>& table, const Row& r) {
    for (const Field<Row>& field : table.fields)
        std::visit(
            [&](auto member) {
                const auto& v = r.*member;
                using T = std::decay_t<decltype(v)>;
                if constexpr (std::is_same_v<T, std::string>)
                    c.text(v);
                else if constexpr (std::is_same_v<T, double>)
                    c.f64(v);
                else
                    c.i64(static_cast<std::int64_t>(v));
            },
            field.member);
}

// One running checksum per table for the rows of the commit being built. From format version
// 3 on a commit's checksum also hashes the checksum of the commit before it (the header's for
// the first), so a commit verifies only after its own session's commits, in order.
struct CommitChecksum {
    Checksum input, frames, events;
    std::int64_t value(std::optional<std::int64_t> previous) const {
        Checksum c;
        if (previous) c.i64(*previous);
        c.i64(static_cast<std::int64_t>(input.value()));
        c.i64(static_cast<std::int64_t>(frames.value()));
        c.i64(static_cast<std::int64_t>(events.value()));
        return static_cast<std::int64_t>(c.value());
    }
};

}  // namespace warplab::session::detail
