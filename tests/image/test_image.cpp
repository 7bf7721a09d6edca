// Tests for image/image.h: file round-trips and orientation, error messages, false colour,
// comparison and metrics. No GL context needed.
#include "image/image.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#if __has_include(<stb_image.h>)
#include <stb_image.h>
#include <stb_image_write.h>
#else
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#endif

namespace fs = std::filesystem;
using namespace warplab::image;

namespace {

fs::path tempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    fs::path dir = fs::path(::testing::TempDir()) / "warplab_image_tests" /
        (std::string(info->test_suite_name()) + "." + info->name());
    fs::create_directories(dir);
    return dir;
}

// Every pixel different, so a flip, transpose or channel swap shows up.
ImageRGBA8 pattern(int w, int h) {
    ImageRGBA8 im = ImageRGBA8::make(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            std::uint8_t* p = im.at(x, y);
            p[0] = std::uint8_t(10 + 20 * x);
            p[1] = std::uint8_t(5 + 40 * y);
            p[2] = std::uint8_t(7 * x + 11 * y);
            p[3] = std::uint8_t(255 - 9 * (x + w * y));
        }
    return im;
}

// Smooth but structured 64x64 image, away from 0 and 255 so added noise never clips.
ImageRGBA8 texture() {
    ImageRGBA8 im = ImageRGBA8::make(64, 64);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            std::uint8_t* p = im.at(x, y);
            const double v = 128 + 60 * std::sin(x * 0.45) * std::cos(y * 0.3) + 30 * std::sin((x + y) * 0.2);
            p[0] = std::uint8_t(std::lround(v));
            p[1] = std::uint8_t(std::lround(255 - v));
            p[2] = std::uint8_t(std::lround(0.5 * v + 40));
            p[3] = 255;
        }
    return im;
}

std::vector<unsigned char> fileBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const fs::path& p, const std::string& bytes) {
    std::ofstream out(p, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

std::string floatBytes(const std::vector<float>& values, bool bigEndian) {
    std::string s;
    for (float v : values) {
        unsigned char b[4];
        std::memcpy(b, &v, 4);  // tests run on little-endian hosts
        if (bigEndian) {
            std::swap(b[0], b[3]);
            std::swap(b[1], b[2]);
        }
        s.append(reinterpret_cast<const char*>(b), 4);
    }
    return s;
}

// Runs f, expects E, and returns its message.
template <class E, class F>
std::string errorOf(F&& f) {
    try {
        f();
    } catch (const E& e) {
        return e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << "wrong exception type: " << e.what();
        return {};
    }
    ADD_FAILURE() << "no exception thrown";
    return {};
}

::testing::AssertionResult pixelIs(const ImageRGBA8& im, int x, int y, std::array<int, 4> want) {
    const std::uint8_t* p = im.at(x, y);
    for (int c = 0; c < 4; ++c)
        if (p[c] != want[std::size_t(c)])
            return ::testing::AssertionFailure()
                << "pixel (" << x << "," << y << ") is " << int(p[0]) << "," << int(p[1]) << "," << int(p[2]) << ","
                << int(p[3]) << "; want " << want[0] << "," << want[1] << "," << want[2] << "," << want[3];
    return ::testing::AssertionSuccess();
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Flipping

TEST(Flip, SwapsRowsOfEveryImageKind) {
    ImageRGBA8 c = pattern(3, 5);
    const ImageRGBA8 original = c;
    flipVertically(c);
    EXPECT_EQ(0, std::memcmp(c.at(0, 0), original.at(0, 4), 12));
    EXPECT_EQ(0, std::memcmp(c.at(0, 2), original.at(0, 2), 12));  // middle row stays
    flipVertically(c);
    EXPECT_EQ(c.pixels, original.pixels);

    ImageF f = ImageF::make(2, 3, 3);
    for (std::size_t i = 0; i < f.data.size(); ++i) f.data[i] = float(i);
    flipVertically(f);
    EXPECT_EQ(f.at(1, 0)[2], float((2 * 2 + 1) * 3 + 2));

    ImageU32 u = ImageU32::make(2, 2);
    u.data = {1, 2, 3, 4};
    flipVertically(u);
    EXPECT_EQ(u.data, (std::vector<std::uint32_t>{3, 4, 1, 2}));
}

TEST(Flip, RejectsBufferOfWrongSize) {
    ImageRGBA8 bad{4, 4, std::vector<std::uint8_t>(10)};
    const std::string msg = errorOf<std::invalid_argument>([&] { flipVertically(bad); });
    EXPECT_NE(msg.find("4x4"), std::string::npos) << msg;
}

// ---------------------------------------------------------------------------------------
// PNG

TEST(Png, RoundTripOddSizeKeepsEveryPixel) {
    const fs::path path = tempDir() / "odd.png";
    const ImageRGBA8 im = pattern(3, 5);
    writePng(path.string(), im);
    const ImageRGBA8 back = readPng(path.string());
    ASSERT_EQ(back.width, 3);
    ASSERT_EQ(back.height, 5);
    EXPECT_EQ(back.pixels, im.pixels);
    EXPECT_TRUE(pixelIs(back, 2, 0, {50, 5, 14, 237}));
}

// Our writer and reader could agree on the wrong orientation; check against stb directly,
// whose buffers are top-down.
TEST(Png, FileIsTopDown) {
    const fs::path dir = tempDir();
    const ImageRGBA8 im = pattern(3, 5);
    writePng((dir / "ours.png").string(), im);
    int w = 0, h = 0, n = 0;
    unsigned char* decoded = stbi_load((dir / "ours.png").string().c_str(), &w, &h, &n, 4);
    ASSERT_NE(decoded, nullptr);
    ASSERT_EQ(w, 3);
    ASSERT_EQ(h, 5);
    EXPECT_EQ(0, std::memcmp(decoded, im.at(0, 0), 12)) << "first row in the file must be row 0 (top)";
    stbi_image_free(decoded);

    // And a file from another writer: a 1x2 image, red on top of blue.
    const unsigned char redOverBlue[8] = {255, 0, 0, 255, 0, 0, 255, 255};
    ASSERT_NE(0, stbi_write_png((dir / "theirs.png").string().c_str(), 1, 2, 4, redOverBlue, 4));
    const ImageRGBA8 back = readPng((dir / "theirs.png").string());
    EXPECT_TRUE(pixelIs(back, 0, 0, {255, 0, 0, 255}));
    EXPECT_TRUE(pixelIs(back, 0, 1, {0, 0, 255, 255}));
}

TEST(Png, GreyFileIsExpandedToRgba) {
    const fs::path path = tempDir() / "grey.png";
    const unsigned char grey[2] = {17, 200};
    ASSERT_NE(0, stbi_write_png(path.string().c_str(), 2, 1, 1, grey, 2));
    const ImageRGBA8 back = readPng(path.string());
    EXPECT_TRUE(pixelIs(back, 1, 0, {200, 200, 200, 255}));
}

TEST(Png, NonPngInputNamesPathAndReason) {
    const fs::path path = tempDir() / "text.png";
    writeBytes(path, "hello, I am not an image\n");
    const std::string msg = errorOf<std::runtime_error>([&] { readPng(path.string()); });
    EXPECT_NE(msg.find("'" + path.string() + "'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("not a PNG"), std::string::npos) << msg;
}

TEST(Png, DamagedPngNamesPath) {
    const fs::path path = tempDir() / "cut.png";
    writePng(path.string(), texture());
    const auto bytes = fileBytes(path);
    writeBytes(path, std::string(bytes.begin(), bytes.begin() + 60));  // signature intact, data cut
    const std::string msg = errorOf<std::runtime_error>([&] { readPng(path.string()); });
    EXPECT_NE(msg.find(path.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("damaged"), std::string::npos) << msg;
}

TEST(Png, MissingFileAndUnwritablePathNamePath) {
    const fs::path dir = tempDir();
    const std::string missing = (dir / "nope.png").string();
    std::string msg = errorOf<std::runtime_error>([&] { readPng(missing); });
    EXPECT_NE(msg.find("cannot read PNG '" + missing + "'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("No such file"), std::string::npos) << msg;

    const std::string unwritable = (dir / "no_such_dir" / "x.png").string();
    msg = errorOf<std::runtime_error>([&] { writePng(unwritable, pattern(2, 2)); });
    EXPECT_NE(msg.find("cannot write PNG '" + unwritable + "'"), std::string::npos) << msg;
}

TEST(Png, EmptyImageIsRefused) {
    const std::string path = (tempDir() / "empty.png").string();
    const std::string msg = errorOf<std::runtime_error>([&] { writePng(path, ImageRGBA8{}); });
    EXPECT_NE(msg.find("empty"), std::string::npos) << msg;
    EXPECT_FALSE(fs::exists(path));
}

// ---------------------------------------------------------------------------------------
// PFM

TEST(Pfm, RoundTripOneAndThreeChannelsOddSize) {
    const fs::path dir = tempDir();
    for (int channels : {1, 3}) {
        ImageF im = ImageF::make(3, 5, channels);
        for (std::size_t i = 0; i < im.data.size(); ++i) im.data[i] = 0.25f * float(i) - 3.0f;
        im.data[4] = std::numeric_limits<float>::infinity();
        im.data[5] = std::nanf("");
        const std::string path = (dir / ("c" + std::to_string(channels) + ".pfm")).string();
        writePfm(path, im);
        const ImageF back = readPfm(path);
        ASSERT_EQ(back.width, 3);
        ASSERT_EQ(back.height, 5);
        ASSERT_EQ(back.channels, channels);
        ASSERT_EQ(back.data.size(), im.data.size());
        // Bitwise, so NaN compares too.
        EXPECT_EQ(0, std::memcmp(back.data.data(), im.data.data(), im.data.size() * sizeof(float)));
        EXPECT_EQ(back.at(2, 0)[channels - 1], im.at(2, 0)[channels - 1]);
    }
}

// The format stores the bottom row first; check the file itself, not just a round trip.
TEST(Pfm, FileStoresBottomRowFirst) {
    const fs::path path = tempDir() / "depth.pfm";
    ImageF im = ImageF::make(3, 5, 1);
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 3; ++x) *im.at(x, y) = float(10 * y + x);
    writePfm(path.string(), im);
    const auto bytes = fileBytes(path);
    const std::string header = "Pf\n3 5\n-1.0\n";
    ASSERT_EQ(bytes.size(), header.size() + 15 * 4);
    EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + std::ptrdiff_t(header.size())), header);
    float first = 0;
    std::memcpy(&first, bytes.data() + header.size(), 4);
    EXPECT_EQ(first, 40.0f) << "first stored pixel must be the bottom-left one";
}

TEST(Pfm, ReadsHandWrittenLittleAndBigEndianFiles) {
    const fs::path dir = tempDir();
    // 2x2 RGB: bottom row stored first.
    const std::vector<float> stored = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
    writeBytes(dir / "le.pfm", "PF\n2 2\n-1.000000\n" + floatBytes(stored, false));
    writeBytes(dir / "be.pfm", "PF 2 2 4.0\n" + floatBytes(stored, true));
    for (const char* name : {"le.pfm", "be.pfm"}) {
        const ImageF im = readPfm((dir / name).string());
        ASSERT_EQ(im.channels, 3) << name;
        EXPECT_EQ(im.at(0, 1)[0], 1.0f) << name;  // bottom-left
        EXPECT_EQ(im.at(1, 0)[2], 12.0f) << name;  // top-right
    }
}

TEST(Pfm, FourChannelsWritesFirstThree) {
    const std::string path = (tempDir() / "v.pfm").string();
    ImageF im = ImageF::make(2, 1, 4);
    im.data = {1, 2, 3, 99, 4, 5, 6, 99};
    writePfm(path, im);
    const ImageF back = readPfm(path);
    ASSERT_EQ(back.channels, 3);
    EXPECT_EQ(back.data, (std::vector<float>{1, 2, 3, 4, 5, 6}));
}

TEST(Pfm, TruncatedFileNamesPathAndProblem) {
    const fs::path path = tempDir() / "cut.pfm";
    writePfm(path.string(), ImageF::make(3, 5, 3));
    fs::resize_file(path, fs::file_size(path) - 7);
    const std::string msg = errorOf<std::runtime_error>([&] { readPfm(path.string()); });
    EXPECT_NE(msg.find("cannot read PFM '" + path.string() + "'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("truncated"), std::string::npos) << msg;
    EXPECT_NE(msg.find("3x5"), std::string::npos) << msg;
}

TEST(Pfm, MalformedHeadersNameWhatIsWrong) {
    const fs::path dir = tempDir();
    struct Case {
        const char* name;
        std::string content;
        const char* expected;
    };
    const Case cases[] = {
        {"magic.pfm", "P6\n2 2\n255\n", "not a PFM"},
        {"empty.pfm", "", "not a PFM"},
        {"width.pfm", "Pf\n-3 5\n-1\n", "width '-3'"},
        {"height.pfm", "Pf\n3 x\n-1\n", "height 'x'"},
        {"scale.pfm", "Pf\n1 1\n0\n" + floatBytes({1}, false), "scale '0'"},
        {"short.pfm", "Pf\n1 1\n", "before the scale"},
        {"long.pfm", "Pf\n1 1\n-1\n" + floatBytes({1, 2}, false), "more than its header"},
    };
    for (const Case& c : cases) {
        writeBytes(dir / c.name, c.content);
        const std::string path = (dir / c.name).string();
        const std::string msg = errorOf<std::runtime_error>([&] { readPfm(path); });
        EXPECT_NE(msg.find("'" + path + "'"), std::string::npos) << msg;
        EXPECT_NE(msg.find(c.expected), std::string::npos) << c.name << ": " << msg;
    }
}

// ---------------------------------------------------------------------------------------
// False colour

TEST(FalseColour, DepthMarksNanAndFarAndRampsInBetween) {
    ImageF depth = ImageF::make(6, 1, 1);
    depth.data = {std::nanf(""), 100.0f, std::numeric_limits<float>::infinity(), 0.5f, 50.0f, 99.0f};
    const ImageRGBA8 c = depthFalseColour(depth, 0.5f, 100.0f);
    EXPECT_TRUE(pixelIs(c, 0, 0, {255, 0, 255, 255}));  // NaN = magenta
    EXPECT_TRUE(pixelIs(c, 1, 0, {0, 0, 0, 255}));  // far plane = black
    EXPECT_TRUE(pixelIs(c, 2, 0, {0, 0, 0, 255}));  // infinity = black
    EXPECT_TRUE(pixelIs(c, 3, 0, {0xFD, 0xE7, 0x25, 255}));  // near = viridis yellow
    for (int x : {4, 5}) {  // finite depths are neither mark
        EXPECT_FALSE(pixelIs(c, x, 0, {0, 0, 0, 255}));
        EXPECT_FALSE(pixelIs(c, x, 0, {255, 0, 255, 255}));
    }
    // Nearer is brighter.
    auto sum = [&](int x) { return c.at(x, 0)[0] + c.at(x, 0)[1] + c.at(x, 0)[2]; };
    EXPECT_GT(sum(3), sum(4));
    EXPECT_GT(sum(4), sum(5));
    EXPECT_THROW(depthFalseColour(depth, 10.0f, 1.0f), std::invalid_argument);
}

TEST(FalseColour, IdsAreDeterministicDistinctAndZeroIsBlack) {
    ImageU32 ids = ImageU32::make(12, 1);
    ids.data = {0, 1, 2, 3, 4, 5, 6, 7, 8, 1000, 65535, 0xFFFFFFFFu};
    const ImageRGBA8 c = idFalseColour(ids);
    EXPECT_TRUE(pixelIs(c, 0, 0, {0, 0, 0, 255}));
    // Pinned so that figures and reference images keep their colours between builds and
    // platforms (a std::hash-based mapping would not).
    EXPECT_TRUE(pixelIs(c, 1, 0, {18, 75, 214, 255}));
    for (int i = 1; i < 12; ++i) {
        const std::uint8_t* p = c.at(i, 0);
        const int maxC = std::max({p[0], p[1], p[2]}), minC = std::min({p[0], p[1], p[2]});
        EXPECT_GE(maxC, 180) << "id " << ids.data[std::size_t(i)] << " too dark";
        EXPECT_GE(maxC - minC, 100) << "id " << ids.data[std::size_t(i)] << " not saturated";
    }
    // The low ids a scene actually uses must be told apart at a glance; arbitrary large ids
    // are hashed, so two of them may by chance come out similar.
    for (int i = 2; i <= 8; ++i)
        for (int j = 1; j < i; ++j) {
            const std::uint8_t *p = c.at(i, 0), *q = c.at(j, 0);
            const int dist = std::abs(p[0] - q[0]) + std::abs(p[1] - q[1]) + std::abs(p[2] - q[2]);
            EXPECT_GE(dist, 100) << "ids " << i << " and " << j;
        }
}

TEST(FalseColour, VelocityStaticIsBlackAndComponentsMapToChannels) {
    ImageF v = ImageF::make(4, 1, 3);
    v.data = {0, 0, 0, 2, -1, 0, -8, 0, 0.5f, 0, std::nanf(""), 0};
    const ImageRGBA8 c = velocityFalseColour(v, 2.0f);
    EXPECT_TRUE(pixelIs(c, 0, 0, {0, 0, 0, 255}));
    EXPECT_TRUE(pixelIs(c, 1, 0, {255, 128, 0, 255}));  // |-1|/2 * 255 = 127.5 -> 128
    EXPECT_TRUE(pixelIs(c, 2, 0, {255, 0, 64, 255}));  // clamped; 0.25 * 255 = 63.75 -> 64
    EXPECT_TRUE(pixelIs(c, 3, 0, {255, 0, 255, 255}));
    EXPECT_THROW(velocityFalseColour(v, 0.0f), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------
// Comparison

TEST(Compare, IdenticalImagesGiveZeros) {
    const ImageRGBA8 a = pattern(3, 5);
    const ImageDiff d = compareImages(a, a, 0);
    EXPECT_EQ(d.maxChannelDiff, 0);
    EXPECT_EQ(d.meanChannelDiff, 0.0);
    EXPECT_EQ(d.pixelsOverThreshold, 0);
    ASSERT_EQ(d.diffImage.width, 3);
    ASSERT_EQ(d.diffImage.height, 5);
}

TEST(Compare, KnownChangeGivesExactNumbersAndMarksThePixels) {
    const ImageRGBA8 a = pattern(4, 4);
    ImageRGBA8 b = a;
    b.at(1, 2)[0] = std::uint8_t(b.at(1, 2)[0] + 10);
    b.at(3, 0)[1] = std::uint8_t(b.at(3, 0)[1] - 3);
    const ImageDiff d = compareImages(a, b, 5);
    EXPECT_EQ(d.maxChannelDiff, 10);
    EXPECT_DOUBLE_EQ(d.meanChannelDiff, 13.0 / 64.0);
    EXPECT_EQ(d.pixelsOverThreshold, 1);
    EXPECT_TRUE(pixelIs(d.diffImage, 1, 2, {255, 0, 0, 255}));
    EXPECT_TRUE(pixelIs(d.diffImage, 3, 0, {255, 220, 0, 255}));
    const std::uint8_t* unchanged = d.diffImage.at(0, 0);
    EXPECT_TRUE(unchanged[0] == unchanged[1] && unchanged[1] == unchanged[2]) << "unchanged pixels are grey";
    EXPECT_EQ(compareImages(a, b, 2).pixelsOverThreshold, 2);
}

TEST(Compare, MismatchedSizesNameBothSizes) {
    const std::string msg = errorOf<std::invalid_argument>([&] { compareImages(pattern(3, 5), pattern(4, 5), 0); });
    EXPECT_NE(msg.find("3x5"), std::string::npos) << msg;
    EXPECT_NE(msg.find("4x5"), std::string::npos) << msg;
    EXPECT_THROW(psnr(pattern(3, 5), pattern(4, 5)), std::invalid_argument);
    EXPECT_THROW(ssimLuminance(texture(), pattern(4, 5)), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------
// PSNR and SSIM

TEST(Psnr, IdenticalIsInfinite) {
    const ImageRGBA8 a = texture();
    EXPECT_EQ(psnr(a, a), std::numeric_limits<double>::infinity());
}

TEST(Psnr, UniformErrorIsExact) {
    const ImageRGBA8 a = texture();
    for (int e : {1, 3, 17}) {
        ImageRGBA8 b = a;
        for (std::size_t i = 0; i < b.pixels.size(); ++i)
            if (i % 4 != 3) b.pixels[i] = std::uint8_t(b.pixels[i] + ((i / 4) % 2 ? e : -e));  // sign irrelevant
        EXPECT_EQ(psnr(a, b), 20.0 * std::log10(255.0 / e)) << "e = " << e;
    }
    // Alpha is not part of PSNR.
    ImageRGBA8 b = a;
    b.pixels[3] = 0;
    EXPECT_EQ(psnr(a, b), std::numeric_limits<double>::infinity());
}

TEST(Psnr, KnownNoiseLevel) {
    // Uniform integer noise on [-8, 8] has variance (17^2 - 1) / 12 = 24.
    ImageRGBA8 a = ImageRGBA8::make(256, 256);
    for (std::size_t i = 0; i < a.pixels.size(); ++i) a.pixels[i] = std::uint8_t(i % 4 == 3 ? 255 : 128);
    ImageRGBA8 b = a;
    std::mt19937 rng(12345);
    for (std::size_t i = 0; i < b.pixels.size(); ++i)
        if (i % 4 != 3) b.pixels[i] = std::uint8_t(128 + int(rng() % 17) - 8);
    EXPECT_NEAR(psnr(a, b), 10.0 * std::log10(255.0 * 255.0 / 24.0), 0.1);
}

TEST(Ssim, IdenticalIsExactlyOne) {
    const ImageRGBA8 a = texture();
    EXPECT_EQ(ssimLuminance(a, a), 1.0);
    ImageRGBA8 flat = ImageRGBA8::make(11, 11);
    EXPECT_EQ(ssimLuminance(flat, flat), 1.0);
}

TEST(Ssim, DropsForNoiseAndShiftAndStaysInRange) {
    const ImageRGBA8 a = texture();
    ImageRGBA8 noisy = a, noisier = a, shifted = a;
    std::mt19937 rng(7);
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        if (i % 4 == 3) continue;
        const int n = int(rng() % 41) - 20;
        noisy.pixels[i] = std::uint8_t(a.pixels[i] + n / 4);
        noisier.pixels[i] = std::uint8_t(a.pixels[i] + n);
    }
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) std::memcpy(shifted.at(x, y), a.at(std::max(0, x - 2), y), 4);
    const double sNoisy = ssimLuminance(a, noisy), sNoisier = ssimLuminance(a, noisier);
    const double sShift = ssimLuminance(a, shifted);
    EXPECT_LT(sNoisy, 0.999);
    EXPECT_LT(sNoisier, sNoisy);
    EXPECT_LT(sNoisier, 0.95);
    EXPECT_GT(sNoisier, 0.0);
    EXPECT_LT(sShift, 0.95);
    // Symmetric up to rounding (fused multiply-adds may round the two orders differently).
    EXPECT_NEAR(ssimLuminance(a, noisy), ssimLuminance(noisy, a), 1e-12);
}

TEST(Ssim, ConstantImagesFollowTheLuminanceTerm) {
    // Flat windows: sigma = 0, so SSIM = (2 mx my + C1) / (mx^2 + my^2 + C1).
    ImageRGBA8 a = ImageRGBA8::make(12, 12), b = ImageRGBA8::make(12, 12);
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        a.pixels[i] = 100;
        b.pixels[i] = 150;
    }
    const double c1 = (0.01 * 255) * (0.01 * 255);
    EXPECT_NEAR(ssimLuminance(a, b), (2 * 100.0 * 150 + c1) / (100.0 * 100 + 150.0 * 150 + c1), 1e-9);
}

// Expected value from an independent, direct (non-separable) 2D implementation of
// Wang et al.'s ssim_index.m (Gaussian 11x11, sigma 1.5, 'valid' windows) in plain Python,
// on the same inputs; it pins the constants, the window and the luma weights.
TEST(Ssim, MatchesDirectReferenceImplementation) {
    ImageRGBA8 a = ImageRGBA8::make(23, 17), b = a;
    std::mt19937 rng(3);  // raw mt19937 output is the same on every platform
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        a.pixels[i] = std::uint8_t(rng() % 256);
        b.pixels[i] = i % 7 == 0 ? std::uint8_t(rng() % 256) : a.pixels[i];
    }
    EXPECT_NEAR(ssimLuminance(a, b), 0.8519859803331623, 1e-12);
    EXPECT_NEAR(psnr(a, b), 16.05811339828054, 1e-12);
}

TEST(Ssim, TooSmallIsRefused) {
    const std::string msg = errorOf<std::invalid_argument>([&] { ssimLuminance(pattern(3, 5), pattern(3, 5)); });
    EXPECT_NE(msg.find("11x11"), std::string::npos) << msg;
}
