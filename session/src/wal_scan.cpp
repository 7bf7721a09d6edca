#include "wal_scan.h"

#include <chrono>
#include <cstddef>
#include <fstream>
#include <iterator>
#include <thread>
#include <utility>
#include <vector>

namespace warplab::session::detail {
namespace {

std::uint32_t bigEndian32(const unsigned char* p) {
    return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}

// SQLite's WAL checksum over n bytes (a multiple of 8), continuing from s[0], s[1]; words are
// big-endian when the log's magic number says so, else little-endian.
void walChecksum(bool bigEndianWords, const unsigned char* p, std::size_t n, std::uint32_t s[2]) {
    for (std::size_t i = 0; i + 8 <= n; i += 8) {
        std::uint32_t x0 = bigEndian32(p + i), x1 = bigEndian32(p + i + 4);
        if (!bigEndianWords) {
            x0 = __builtin_bswap32(x0);
            x1 = __builtin_bswap32(x1);
        }
        s[0] += x0 + s[1];
        s[1] += x1 + s[0];
    }
}

std::optional<WalLoss> scanWal(const std::string& walPath) {
    std::ifstream in(walPath, std::ios::binary);
    const std::vector<unsigned char> log((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    constexpr std::size_t kHeader = 32, kFrameHeader = 24;
    if (log.size() < kHeader) return std::nullopt;  // nothing was logged yet
    const std::uint32_t magic = bigEndian32(log.data());
    std::uint32_t pageSize = bigEndian32(log.data() + 8);
    if (pageSize == 1) pageSize = 65536;
    std::uint32_t sum[2] = {0, 0};
    walChecksum(magic & 1, log.data(), 24, sum);
    const bool headerOk = (magic == 0x377f0682 || magic == 0x377f0683) && pageSize >= 512 && pageSize <= 65536 &&
        (pageSize & (pageSize - 1)) == 0 && sum[0] == bigEndian32(log.data() + 24) &&
        sum[1] == bigEndian32(log.data() + 28);
    if (!headerOk)  // a header is only ever written whole, before any frame
        return log.size() > kHeader + kFrameHeader ? std::optional<WalLoss>(WalLoss{0, 0}) : std::nullopt;

    const std::uint32_t salt1 = bigEndian32(log.data() + 16), salt2 = bigEndian32(log.data() + 20);
    const std::size_t frameSize = kFrameHeader + pageSize;
    const auto ofThisLog = [&](std::size_t at) {
        return bigEndian32(log.data() + at + 8) == salt1 && bigEndian32(log.data() + at + 12) == salt2;
    };
    std::size_t at = kHeader;
    for (; at + frameSize <= log.size(); at += frameSize) {
        const unsigned char* frame = log.data() + at;
        if (!ofThisLog(at) || bigEndian32(frame) == 0) break;
        walChecksum(magic & 1, frame, 8, sum);
        walChecksum(magic & 1, frame + kFrameHeader, pageSize, sum);
        if (sum[0] != bigEndian32(frame + 16) || sum[1] != bigEndian32(frame + 20)) break;
    }
    WalLoss loss{static_cast<std::int64_t>(at), 0};
    for (std::size_t later = at + frameSize; later + frameSize <= log.size(); later += frameSize)
        loss.commits += ofThisLog(later) && bigEndian32(log.data() + later + 4) != 0;
    return loss.commits > 0 ? std::optional<WalLoss>(loss) : std::nullopt;
}

}  // namespace

std::optional<WalLoss> lostInWal(const std::string& walPath) {
    auto first = scanWal(walPath);
    for (int look = 0; first && look < 3; ++look) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        auto again = scanWal(walPath);
        if (again && again->byte == first->byte && again->commits == first->commits) return again;
        first = std::move(again);
    }
    return std::nullopt;
}

}  // namespace warplab::session::detail
