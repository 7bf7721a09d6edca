// Plain-C++ images for read-back, `warplab render` outputs and reference-image tests.
// No GL here on purpose: tests, the benchmark and offline tools use these without a context.
//
// Every image is stored TOP-DOWN (row 0 is the top), as image files and viewers expect.
// glReadPixels returns rows bottom-up: call flipVertically() (or flipRows() on a raw buffer)
// once after reading back.
//
// Errors: std::invalid_argument for a caller's mistake (buffer size not matching width and
// height, mismatched sizes, bad parameters); std::runtime_error for file problems. Each
// message is one sentence naming the file (for I/O) or the function and what is wrong.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace warplab::image {

// 8-bit RGBA colour, 4 bytes per pixel, rows packed (no padding).
struct ImageRGBA8 {
    int width = 0, height = 0;
    std::vector<std::uint8_t> pixels;  // 4 * width * height

    static ImageRGBA8 make(int w, int h);  // all zero
    std::uint8_t* at(int x, int y) { return &pixels[4 * (std::size_t(y) * width + x)]; }
    const std::uint8_t* at(int x, int y) const { return &pixels[4 * (std::size_t(y) * width + x)]; }
};

// Float image with 1, 3 or 4 interleaved channels (linear depth, 3D velocity).
struct ImageF {
    int width = 0, height = 0, channels = 1;
    std::vector<float> data;  // channels * width * height

    static ImageF make(int w, int h, int channels);  // all zero
    float* at(int x, int y) { return &data[channels * (std::size_t(y) * width + x)]; }
    const float* at(int x, int y) const { return &data[channels * (std::size_t(y) * width + x)]; }
};

// One 32-bit value per pixel (object ids; 0 = no object).
struct ImageU32 {
    int width = 0, height = 0;
    std::vector<std::uint32_t> data;  // width * height

    static ImageU32 make(int w, int h);  // all zero
    std::uint32_t& at(int x, int y) { return data[std::size_t(y) * width + x]; }
    std::uint32_t at(int x, int y) const { return data[std::size_t(y) * width + x]; }
};

// Swap row r with row rows-1-r in a packed buffer of `rows` rows of `rowBytes` bytes.
void flipRows(void* data, std::size_t rowBytes, int rows);
void flipVertically(ImageRGBA8& image);
void flipVertically(ImageF& image);
void flipVertically(ImageU32& image);

// PNG (8-bit RGBA, via stb). Alpha is stored as given, not premultiplied.
void writePng(const std::string& path, const ImageRGBA8& image);
ImageRGBA8 readPng(const std::string& path);  // any PNG; grey/RGB are expanded to RGBA

// PFM, little-endian. 1 channel -> "Pf"; 2 channels -> "PF" with blue = 0; 3 -> "PF";
// 4 -> "PF" of the first three. readPfm accepts either byte order and ignores the
// magnitude of the scale (it is metadata; the floats are returned as stored).
void writePfm(const std::string& path, const ImageF& image);
ImageF readPfm(const std::string& path);

// False colour for figures and debugging. Alpha is always 255.
// Depth: linear eye-space distance; viridis ramp, near = yellow, far = dark purple;
// at or beyond the far plane (or +inf) = black; NaN = magenta; below near clamps to near.
// Needs a 1-channel image and 0 <= nearPlane < farPlane, both finite.
ImageRGBA8 depthFalseColour(const ImageF& linearDepth, float nearPlane, float farPlane);
// 0 = black; each other id a fixed saturated colour (same id -> same colour, on every run).
ImageRGBA8 idFalseColour(const ImageU32& ids);
// |v.xyz| / maxSpeed -> rgb, clamped: static = black, as in the thesis figures (the sign is
// not shown). Needs 2 to 4 channels (missing z = 0) and finite maxSpeed > 0; NaN = magenta.
ImageRGBA8 velocityFalseColour(const ImageF& velocity, float maxSpeed);

inline constexpr std::uint8_t kNanColour[4] = {255, 0, 255, 255};
inline constexpr std::uint8_t kFarColour[4] = {0, 0, 0, 255};

// Reference-image comparison over all four channels (alpha included).
struct ImageDiff {
    int maxChannelDiff = 0;  // largest |a - b| over all channels of all pixels
    double meanChannelDiff = 0.0;  // mean |a - b| over all channels of all pixels
    int pixelsOverThreshold = 0;  // pixels whose largest channel difference > threshold
    // A dimmed grey copy of `a`; pixels over the threshold red, smaller differences yellow.
    ImageRGBA8 diffImage;
};
ImageDiff compareImages(const ImageRGBA8& a, const ImageRGBA8& b, int perPixelThreshold);

// |a - b| as a grey image for looking at a method's error: each pixel's mean absolute RGB
// difference times `gain`, clamped to 255 (black = exact, white = 255 / gain or more off).
ImageRGBA8 absoluteErrorImage(const ImageRGBA8& a, const ImageRGBA8& b, int gain);

// PSNR in dB over R, G and B (alpha ignored), peak 255; +infinity for identical images.
double psnr(const ImageRGBA8& a, const ImageRGBA8& b);
// Mean SSIM (Wang et al. 2004) on Rec. 601 luma (0.299 R + 0.587 G + 0.114 B, not rounded),
// Gaussian 11x11 window with sigma 1.5, K1 = 0.01, K2 = 0.03, L = 255, over every window that
// fits inside the image (no padding). Exactly 1 for identical images. Needs at least 11x11.
double ssimLuminance(const ImageRGBA8& a, const ImageRGBA8& b);

}  // namespace warplab::image
