#include "image/image.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>

#include <sys/stat.h>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <utility>

// The implementations live in libstb (Debian libstb-dev): link -lstb, define nothing here.
#if __has_include(<stb_image_write.h>)
#include <stb_image.h>
#include <stb_image_write.h>
#else
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#endif

namespace warplab::image {
namespace {

std::string sizeText(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

// Sizes come from files and callers; checked once here so indexing below cannot overflow.
std::size_t pixelCount(int w, int h, const char* what) {
    if (w < 0 || h < 0)
        throw std::invalid_argument(std::string(what) + ": negative image size " + sizeText(w, h) + ".");
    return std::size_t(w) * std::size_t(h);
}

void checkImage(const ImageRGBA8& im, const char* what) {
    if (im.pixels.size() != 4 * pixelCount(im.width, im.height, what))
        throw std::invalid_argument(std::string(what) + ": RGBA8 image " + sizeText(im.width, im.height) + " has " +
                                    std::to_string(im.pixels.size()) + " bytes, expected " +
                                    std::to_string(4 * pixelCount(im.width, im.height, what)) + ".");
}

void checkImage(const ImageF& im, const char* what) {
    if (im.channels < 1 || im.channels > 4)
        throw std::invalid_argument(std::string(what) + ": float image has " + std::to_string(im.channels) +
                                    " channels, expected 1 to 4.");
    const std::size_t expected = std::size_t(im.channels) * pixelCount(im.width, im.height, what);
    if (im.data.size() != expected)
        throw std::invalid_argument(std::string(what) + ": float image " + sizeText(im.width, im.height) + "x" +
                                    std::to_string(im.channels) + " has " + std::to_string(im.data.size()) +
                                    " floats, expected " + std::to_string(expected) + ".");
}

void checkImage(const ImageU32& im, const char* what) {
    if (im.data.size() != pixelCount(im.width, im.height, what))
        throw std::invalid_argument(std::string(what) + ": id image " + sizeText(im.width, im.height) + " has " +
                                    std::to_string(im.data.size()) + " values, expected " +
                                    std::to_string(pixelCount(im.width, im.height, what)) + ".");
}

[[noreturn]] void fileError(const char* verb, const char* format, const std::string& path, const std::string& reason) {
    throw std::runtime_error(std::string("cannot ") + verb + " " + format + " '" + path + "': " + reason + ".");
}

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};

// Whole-file I/O through stdio so that failures can report errno (stb only says "failed").
std::vector<unsigned char> readWholeFile(const std::string& path, const char* format) {
    std::FILE* raw = std::fopen(path.c_str(), "rb");
    if (!raw) fileError("read", format, path, std::strerror(errno));
    std::unique_ptr<std::FILE, FileCloser> f(raw);
    std::vector<unsigned char> bytes;
    unsigned char buf[1 << 16];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f.get())) > 0) bytes.insert(bytes.end(), buf, buf + n);
    if (std::ferror(f.get())) fileError("read", format, path, std::strerror(errno));
    return bytes;
}

void writeWholeFile(const std::string& path, const char* format, const void* data, std::size_t size) {
    // An output is a regular file: opening a pipe for writing would wait for a reader forever,
    // and a device is nobody's image.
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
        fileError("write", format, path, "it exists and is not a regular file (a pipe, socket, device or folder)");
    std::FILE* raw = std::fopen(path.c_str(), "wb");
    if (!raw) fileError("write", format, path, std::strerror(errno));
    std::unique_ptr<std::FILE, FileCloser> f(raw);
    if (std::fwrite(data, 1, size, f.get()) != size) fileError("write", format, path, std::strerror(errno));
    // A full disk often only shows up when the buffered tail is flushed.
    if (std::fclose(f.release()) != 0) fileError("write", format, path, std::strerror(errno));
}

bool hostIsLittleEndian() {
    const std::uint32_t one = 1;
    unsigned char first;
    std::memcpy(&first, &one, 1);
    return first == 1;
}

float byteSwapped(float v) {
    unsigned char b[4];
    std::memcpy(b, &v, 4);
    std::swap(b[0], b[3]);
    std::swap(b[1], b[2]);
    std::memcpy(&v, b, 4);
    return v;
}

std::uint8_t toByte(double unit) { return std::uint8_t(std::lround(std::clamp(unit, 0.0, 1.0) * 255.0)); }

void setPixel(std::uint8_t* p, const std::uint8_t c[4]) { std::memcpy(p, c, 4); }

}  // namespace

ImageRGBA8 ImageRGBA8::make(int w, int h) {
    return ImageRGBA8{w, h, std::vector<std::uint8_t>(4 * pixelCount(w, h, "ImageRGBA8::make"))};
}

ImageF ImageF::make(int w, int h, int channels) {
    if (channels < 1 || channels > 4)
        throw std::invalid_argument("ImageF::make: " + std::to_string(channels) + " channels, expected 1 to 4.");
    return ImageF{w, h, channels, std::vector<float>(std::size_t(channels) * pixelCount(w, h, "ImageF::make"))};
}

ImageU32 ImageU32::make(int w, int h) {
    return ImageU32{w, h, std::vector<std::uint32_t>(pixelCount(w, h, "ImageU32::make"))};
}

// ---------------------------------------------------------------------------------------
// Flipping

void flipRows(void* data, std::size_t rowBytes, int rows) {
    auto* bytes = static_cast<unsigned char*>(data);
    for (int top = 0, bottom = rows - 1; top < bottom; ++top, --bottom)
        std::swap_ranges(bytes + std::size_t(top) * rowBytes, bytes + std::size_t(top + 1) * rowBytes,
                         bytes + std::size_t(bottom) * rowBytes);
}

void flipVertically(ImageRGBA8& image) {
    checkImage(image, "flipVertically");
    flipRows(image.pixels.data(), 4 * std::size_t(image.width), image.height);
}

void flipVertically(ImageF& image) {
    checkImage(image, "flipVertically");
    flipRows(image.data.data(), sizeof(float) * image.channels * std::size_t(image.width), image.height);
}

void flipVertically(ImageU32& image) {
    checkImage(image, "flipVertically");
    flipRows(image.data.data(), sizeof(std::uint32_t) * std::size_t(image.width), image.height);
}

// ---------------------------------------------------------------------------------------
// PNG

void writePng(const std::string& path, const ImageRGBA8& image) {
    checkImage(image, "writePng");
    if (image.width == 0 || image.height == 0)
        fileError("write", "PNG", path, "the image is empty (" + sizeText(image.width, image.height) + ")");
    // Encode to memory, then write ourselves: stbi_write_png gives no reason on failure.
    std::vector<unsigned char> encoded;
    auto append = [](void* ctx, void* data, int size) {
        auto* out = static_cast<std::vector<unsigned char>*>(ctx);
        auto* bytes = static_cast<unsigned char*>(data);
        out->insert(out->end(), bytes, bytes + size);
    };
    if (!stbi_write_png_to_func(append, &encoded, image.width, image.height, 4, image.pixels.data(), 4 * image.width))
        fileError("write", "PNG", path, "the PNG encoder failed");
    writeWholeFile(path, "PNG", encoded.data(), encoded.size());
}

ImageRGBA8 readPng(const std::string& path) {
    const std::vector<unsigned char> bytes = readWholeFile(path, "PNG");
    static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    // Checked first because stb would happily decode a JPEG or BMP under a .png name.
    if (bytes.size() < 8 || std::memcmp(bytes.data(), kSignature, 8) != 0)
        fileError("read", "PNG", path, "file is not a PNG");
    if (bytes.size() > std::size_t(std::numeric_limits<int>::max()))
        fileError("read", "PNG", path, "file is too large");
    int w = 0, h = 0, channelsInFile = 0;
    unsigned char* decoded = stbi_load_from_memory(bytes.data(), int(bytes.size()), &w, &h, &channelsInFile, 4);
    if (!decoded) {
        const char* why = stbi_failure_reason();
        fileError("read", "PNG", path, std::string("the PNG is damaged (") + (why ? why : "unknown") + ")");
    }
    ImageRGBA8 image{w, h, std::vector<std::uint8_t>(decoded, decoded + 4 * std::size_t(w) * std::size_t(h))};
    stbi_image_free(decoded);
    return image;
}

// ---------------------------------------------------------------------------------------
// PFM

void writePfm(const std::string& path, const ImageF& image) {
    checkImage(image, "writePfm");
    const int outChannels = image.channels == 1 ? 1 : 3;
    const std::string header = std::string(outChannels == 1 ? "Pf" : "PF") + "\n" + std::to_string(image.width) + " " +
        std::to_string(image.height) + "\n-1.0\n";  // negative = little-endian
    std::vector<unsigned char> bytes(header.begin(), header.end());
    const std::size_t headerSize = bytes.size();
    bytes.resize(headerSize + sizeof(float) * outChannels * pixelCount(image.width, image.height, "writePfm"));
    const bool swap = !hostIsLittleEndian();
    unsigned char* out = bytes.data() + headerSize;
    // The format stores the bottom row first.
    for (int y = image.height - 1; y >= 0; --y)
        for (int x = 0; x < image.width; ++x) {
            const float* p = image.at(x, y);
            for (int c = 0; c < outChannels; ++c) {
                float v = c < image.channels ? p[c] : 0.0f;
                if (swap) v = byteSwapped(v);
                std::memcpy(out, &v, sizeof v);
                out += sizeof v;
            }
        }
    writeWholeFile(path, "PFM", bytes.data(), bytes.size());
}

ImageF readPfm(const std::string& path) {
    const std::vector<unsigned char> bytes = readWholeFile(path, "PFM");
    auto fail = [&](const std::string& why) { fileError("read", "PFM", path, why); };

    std::size_t pos = 0;
    auto isSpace = [](unsigned char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
    auto nextToken = [&](const char* what) {
        while (pos < bytes.size() && isSpace(bytes[pos])) ++pos;
        const std::size_t start = pos;
        while (pos < bytes.size() && !isSpace(bytes[pos]) && pos - start < 64) ++pos;
        if (start == pos) fail(std::string("the header ends before the ") + what);
        return std::string(bytes.begin() + std::ptrdiff_t(start), bytes.begin() + std::ptrdiff_t(pos));
    };

    if (bytes.size() < 2 || bytes[0] != 'P' || (bytes[1] != 'F' && bytes[1] != 'f'))
        fail("file is not a PFM (it does not start with 'PF' or 'Pf')");
    pos = 2;
    if (pos >= bytes.size() || !isSpace(bytes[pos])) fail("file is not a PFM (it does not start with 'PF' or 'Pf')");
    const int channels = bytes[1] == 'F' ? 3 : 1;

    auto parseDimension = [&](const char* what) {
        const std::string token = nextToken(what);
        char* end = nullptr;
        errno = 0;
        const long value = std::strtol(token.c_str(), &end, 10);
        if (*end != '\0' || errno == ERANGE || value <= 0 || value > std::numeric_limits<int>::max())
            fail(std::string("the ") + what + " '" + token + "' is not a positive integer");
        return int(value);
    };
    const int width = parseDimension("width");
    const int height = parseDimension("height");
    const std::string scaleToken = nextToken("scale");
    char* end = nullptr;
    const double scale = std::strtod(scaleToken.c_str(), &end);
    if (*end != '\0' || !std::isfinite(scale) || scale == 0.0)
        fail("the scale '" + scaleToken + "' is not a non-zero number");
    // Exactly one whitespace byte separates the header from the data, which may itself
    // begin with bytes that look like whitespace.
    if (pos >= bytes.size()) fail("file is truncated: it ends right after the header");
    ++pos;

    const std::size_t remaining = bytes.size() - pos;
    const std::size_t floatsPerRow = std::size_t(width) * channels;
    // Compare in rows rather than multiplying width * height first: the header is untrusted.
    const std::size_t rowBytes = floatsPerRow * sizeof(float);
    const std::string expected =
        sizeText(width, height) + " with " + std::to_string(channels) + (channels == 1 ? " channel" : " channels");
    if (remaining / rowBytes < std::size_t(height))
        fail("file is truncated: the header says " + expected + " but only " + std::to_string(remaining) +
             " bytes of pixel data follow");
    // Extra bytes mean the header's size is wrong, so the pixels would be misread.
    if (remaining / rowBytes > std::size_t(height) || remaining % rowBytes != 0)
        fail("file has " + std::to_string(remaining) + " bytes of pixel data, more than its header (" + expected +
             ") says");

    ImageF image = ImageF::make(width, height, channels);
    const bool swap = (scale < 0) != hostIsLittleEndian();
    const unsigned char* in = bytes.data() + pos;
    for (int y = height - 1; y >= 0; --y) {  // bottom row first in the file
        float* row = image.at(0, y);
        std::memcpy(row, in, rowBytes);
        in += rowBytes;
        if (swap)
            for (std::size_t i = 0; i < floatsPerRow; ++i) row[i] = byteSwapped(row[i]);
    }
    return image;
}

// ---------------------------------------------------------------------------------------
// False colour

namespace {

// Viridis at 10 evenly spaced stops (R's viridis(10)); perceptually uniform and readable in
// greyscale print, and none of its colours is black or magenta, which mark far and NaN.
constexpr std::uint8_t kViridis[10][3] = {
    {0x44, 0x01, 0x54}, {0x48, 0x28, 0x78}, {0x3E, 0x4A, 0x89}, {0x31, 0x68, 0x8E}, {0x26, 0x82, 0x8E},
    {0x1F, 0x9E, 0x89}, {0x35, 0xB7, 0x79}, {0x6D, 0xCD, 0x59}, {0xB4, 0xDE, 0x2C}, {0xFD, 0xE7, 0x25},
};

void viridis(double t, std::uint8_t* out) {
    const double s = std::clamp(t, 0.0, 1.0) * 9.0;
    const int i = std::min(int(s), 8);
    const double f = s - i;
    for (int c = 0; c < 3; ++c)
        out[c] = std::uint8_t(std::lround(kViridis[i][c] + f * (kViridis[i + 1][c] - kViridis[i][c])));
    out[3] = 255;
}

// splitmix64 finaliser: small consecutive ids get unrelated bits.
std::uint64_t mix(std::uint64_t z) {
    z += 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

void hsvToRgb(double h, double s, double v, std::uint8_t* out) {
    const double hh = (h - std::floor(h)) * 6.0;
    const int sector = std::min(int(hh), 5);
    const double f = hh - sector;
    const double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
    double r = v, g = t, b = p;
    switch (sector) {
        case 1:
            r = q;
            g = v;
            b = p;
            break;
        case 2:
            r = p;
            g = v;
            b = t;
            break;
        case 3:
            r = p;
            g = q;
            b = v;
            break;
        case 4:
            r = t;
            g = p;
            b = v;
            break;
        case 5:
            r = v;
            g = p;
            b = q;
            break;
        default: break;
    }
    out[0] = toByte(r);
    out[1] = toByte(g);
    out[2] = toByte(b);
    out[3] = 255;
}

}  // namespace

ImageRGBA8 depthFalseColour(const ImageF& linearDepth, float nearPlane, float farPlane) {
    checkImage(linearDepth, "depthFalseColour");
    if (linearDepth.channels != 1)
        throw std::invalid_argument("depthFalseColour: depth image has " + std::to_string(linearDepth.channels) +
                                    " channels, expected 1.");
    if (!std::isfinite(nearPlane) || !std::isfinite(farPlane) || nearPlane < 0 || !(nearPlane < farPlane))
        throw std::invalid_argument("depthFalseColour: need finite 0 <= near < far, got near " +
                                    std::to_string(nearPlane) + " and far " + std::to_string(farPlane) + ".");
    // Cleared pixels linearise to the far plane only up to float rounding.
    const double farThreshold = double(farPlane) * (1.0 - 1e-5);
    ImageRGBA8 out = ImageRGBA8::make(linearDepth.width, linearDepth.height);
    for (std::size_t i = 0; i < linearDepth.data.size(); ++i) {
        const double d = linearDepth.data[i];
        std::uint8_t* p = &out.pixels[4 * i];
        if (std::isnan(d))
            setPixel(p, kNanColour);
        else if (d >= farThreshold)
            setPixel(p, kFarColour);
        else
            viridis(1.0 - (d - nearPlane) / (double(farPlane) - nearPlane), p);  // near bright
    }
    return out;
}

ImageRGBA8 idFalseColour(const ImageU32& ids) {
    checkImage(ids, "idFalseColour");
    ImageRGBA8 out = ImageRGBA8::make(ids.width, ids.height);
    for (std::size_t i = 0; i < ids.data.size(); ++i) {
        const std::uint32_t id = ids.data[i];
        std::uint8_t* p = &out.pixels[4 * i];
        if (id == 0) {
            setPixel(p, kFarColour);
            continue;
        }
        // Golden-ratio hue steps keep the few low ids a scene uses far apart on the hue
        // circle; the hashed saturation/value separate ids whose hues happen to come close.
        const double hue = std::fmod(double(id) * 0.6180339887498949, 1.0);
        const std::uint64_t h = mix(id);
        const double sat = 0.65 + 0.35 * double(h & 0xFF) / 255.0;
        const double val = 0.75 + 0.25 * double((h >> 8) & 0xFF) / 255.0;
        hsvToRgb(hue, sat, val, p);
    }
    return out;
}

ImageRGBA8 velocityFalseColour(const ImageF& velocity, float maxSpeed) {
    checkImage(velocity, "velocityFalseColour");
    if (velocity.channels < 2)
        throw std::invalid_argument("velocityFalseColour: velocity image has " + std::to_string(velocity.channels) +
                                    " channel, expected 2 to 4.");
    if (!std::isfinite(maxSpeed) || !(maxSpeed > 0))
        throw std::invalid_argument("velocityFalseColour: maxSpeed must be finite and positive, got " +
                                    std::to_string(maxSpeed) + ".");
    ImageRGBA8 out = ImageRGBA8::make(velocity.width, velocity.height);
    const std::size_t n = pixelCount(velocity.width, velocity.height, "velocityFalseColour");
    for (std::size_t i = 0; i < n; ++i) {
        const float* v = &velocity.data[i * velocity.channels];
        std::uint8_t* p = &out.pixels[4 * i];
        const int used = std::min(velocity.channels, 3);
        bool nan = false;
        for (int c = 0; c < used; ++c) nan = nan || std::isnan(v[c]);
        if (nan) {
            setPixel(p, kNanColour);
            continue;
        }
        for (int c = 0; c < 3; ++c) p[c] = c < used ? toByte(std::fabs(double(v[c])) / maxSpeed) : 0;
        p[3] = 255;
    }
    return out;
}

// ---------------------------------------------------------------------------------------
// Comparison and metrics

namespace {
void checkSameSize(const ImageRGBA8& a, const ImageRGBA8& b, const char* what) {
    checkImage(a, what);
    checkImage(b, what);
    if (a.width != b.width || a.height != b.height)
        throw std::invalid_argument(std::string(what) + ": image sizes differ (" + sizeText(a.width, a.height) +
                                    " vs " + sizeText(b.width, b.height) + ").");
}
}  // namespace

ImageRGBA8 absoluteErrorImage(const ImageRGBA8& a, const ImageRGBA8& b, int gain) {
    checkSameSize(a, b, "absoluteErrorImage");
    ImageRGBA8 out = ImageRGBA8::make(a.width, a.height);
    const std::size_t n = pixelCount(a.width, a.height, "absoluteErrorImage");
    for (std::size_t i = 0; i < n; ++i) {
        int sum = 0;
        for (int c = 0; c < 3; ++c) sum += std::abs(int(a.pixels[4 * i + c]) - int(b.pixels[4 * i + c]));
        const auto grey = static_cast<std::uint8_t>(std::min(255, sum * gain / 3));
        const std::uint8_t g[4] = {grey, grey, grey, 255};
        setPixel(&out.pixels[4 * i], g);
    }
    return out;
}

ImageDiff compareImages(const ImageRGBA8& a, const ImageRGBA8& b, int perPixelThreshold) {
    checkSameSize(a, b, "compareImages");
    ImageDiff diff;
    diff.diffImage = ImageRGBA8::make(a.width, a.height);
    std::uint64_t sum = 0;  // integer so the mean is exact for any realistic size
    const std::size_t n = pixelCount(a.width, a.height, "compareImages");
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint8_t* pa = &a.pixels[4 * i];
        const std::uint8_t* pb = &b.pixels[4 * i];
        int pixelMax = 0;
        for (int c = 0; c < 4; ++c) {
            const int d = std::abs(int(pa[c]) - int(pb[c]));
            pixelMax = std::max(pixelMax, d);
            sum += unsigned(d);
        }
        diff.maxChannelDiff = std::max(diff.maxChannelDiff, pixelMax);
        std::uint8_t* out = &diff.diffImage.pixels[4 * i];
        if (pixelMax > perPixelThreshold) {
            ++diff.pixelsOverThreshold;
            const std::uint8_t red[4] = {255, 0, 0, 255};
            setPixel(out, red);
        } else if (pixelMax > 0) {
            const std::uint8_t yellow[4] = {255, 220, 0, 255};
            setPixel(out, yellow);
        } else {
            // Dimmed so that the marks stand out whatever the scene's colours are.
            const auto grey = std::uint8_t((299 * pa[0] + 587 * pa[1] + 114 * pa[2]) / 3000);
            const std::uint8_t g[4] = {grey, grey, grey, 255};
            setPixel(out, g);
        }
    }
    diff.meanChannelDiff = n ? double(sum) / double(4 * n) : 0.0;
    return diff;
}

double psnr(const ImageRGBA8& a, const ImageRGBA8& b) {
    checkSameSize(a, b, "psnr");
    const std::size_t n = pixelCount(a.width, a.height, "psnr");
    if (n == 0) throw std::invalid_argument("psnr: images are empty (" + sizeText(a.width, a.height) + ").");
    std::uint64_t sumSq = 0;  // exact: at most 3 * 255^2 per pixel
    for (std::size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
            const int d = int(a.pixels[4 * i + c]) - int(b.pixels[4 * i + c]);
            sumSq += std::uint64_t(d * d);
        }
    if (sumSq == 0) return std::numeric_limits<double>::infinity();
    const double mse = double(sumSq) / double(3 * n);
    // 20 log10(peak / rmse) rather than 10 log10(peak^2 / mse): for a uniform integer error e
    // the root is exactly e, so the result is exactly 20 log10(255 / e).
    return 20.0 * std::log10(255.0 / std::sqrt(mse));
}

double ssimLuminance(const ImageRGBA8& a, const ImageRGBA8& b) {
    checkSameSize(a, b, "ssimLuminance");
    constexpr int kWindow = 11;
    constexpr double kSigma = 1.5;
    const int w = a.width, h = a.height;
    if (w < kWindow || h < kWindow)
        throw std::invalid_argument("ssimLuminance: images are " + sizeText(w, h) + ", need at least 11x11.");

    std::array<double, kWindow> weights{};
    double total = 0;
    for (int i = 0; i < kWindow; ++i) {
        const double x = i - kWindow / 2;
        weights[i] = std::exp(-x * x / (2 * kSigma * kSigma));
        total += weights[i];
    }
    for (double& wt : weights) wt /= total;

    const std::size_t n = pixelCount(w, h, "ssimLuminance");
    std::vector<double> x(n), y(n);
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint8_t* pa = &a.pixels[4 * i];
        const std::uint8_t* pb = &b.pixels[4 * i];
        x[i] = 0.299 * pa[0] + 0.587 * pa[1] + 0.114 * pa[2];
        y[i] = 0.299 * pb[0] + 0.587 * pb[1] + 0.114 * pb[2];
    }

    // Separable 'valid' Gaussian filter: horizontal pass then vertical pass.
    const int ow = w - kWindow + 1, oh = h - kWindow + 1;
    auto filter = [&](auto&& value) {
        std::vector<double> horizontal(std::size_t(ow) * h), result(std::size_t(ow) * oh);
        for (int r = 0; r < h; ++r)
            for (int c = 0; c < ow; ++c) {
                double s = 0;
                for (int k = 0; k < kWindow; ++k) s += weights[k] * value(std::size_t(r) * w + c + k);
                horizontal[std::size_t(r) * ow + c] = s;
            }
        for (int r = 0; r < oh; ++r)
            for (int c = 0; c < ow; ++c) {
                double s = 0;
                for (int k = 0; k < kWindow; ++k) s += weights[k] * horizontal[std::size_t(r + k) * ow + c];
                result[std::size_t(r) * ow + c] = s;
            }
        return result;
    };
    // Identical inputs are 1 by definition; said outright because compilers may contract
    // a*b + c into fused multiply-adds differently in the numerator and the denominator.
    if (x == y) return 1.0;
    const auto muX = filter([&](std::size_t i) { return x[i]; });
    const auto muY = filter([&](std::size_t i) { return y[i]; });
    const auto xx = filter([&](std::size_t i) { return x[i] * x[i]; });
    const auto yy = filter([&](std::size_t i) { return y[i] * y[i]; });
    const auto xy = filter([&](std::size_t i) { return x[i] * y[i]; });

    constexpr double kL = 255.0, kC1 = (0.01 * kL) * (0.01 * kL), kC2 = (0.03 * kL) * (0.03 * kL);
    double sum = 0;
    for (std::size_t i = 0; i < muX.size(); ++i) {
        const double mx = muX[i], my = muY[i];
        const double varX = xx[i] - mx * mx, varY = yy[i] - my * my, cov = xy[i] - mx * my;
        sum += ((2 * mx * my + kC1) * (2 * cov + kC2)) / ((mx * mx + my * my + kC1) * (varX + varY + kC2));
    }
    return sum / double(muX.size());
}

}  // namespace warplab::image
