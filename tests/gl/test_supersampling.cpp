// Supersampling as a setting of the conventional renderer: depth, ids, velocity and
// flow stay the pixel centre's bit for bit, and colour is the box mean of N x N sub-pixel
// samples, checked against an independent oracle -- the same frame rendered directly at N times
// the size, averaged on the CPU.
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "gl/gl_test_support.h"
// Renderer-private, for the flow attachment alone: nothing outside renderer/ reads flow back,
// so there is no public read-back to use.
#include "gbuffer_gl.h"
#include "gl/check.h"

namespace warplab {
namespace {

using testing::aimedAt;
using testing::shooterScene;

constexpr int kW = 96;
constexpr int kH = 54;

renderer::ConventionalRenderer& ssaaRenderer() {
    testing::glContext();
    static renderer::ConventionalRenderer renderer(testing::sourceDataPaths());
    return renderer;
}

std::vector<float> readFlow(const renderer::GBuffer& gbuffer) {
    const auto& g = gbuffer.impl();
    std::vector<float> flow(4 * static_cast<std::size_t>(g.width) * static_cast<std::size_t>(g.height));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, g.framebuffer.id());
    glReadBuffer(renderer::GBuffer::Impl::kFlowAttachment);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, g.width, g.height, GL_RGBA, GL_FLOAT, flow.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    gl::checkErrors("reading back the flow attachment");
    return flow;  // rows bottom-up: only ever compared with another read the same way
}

struct Rendered {
    renderer::GBufferImages images;
    std::vector<float> flow;  // empty unless rendered with flowTo
};

Rendered render(const scene::FrameDescription& frame, int width, int height, int supersampling,
                const scene::FrameDescription* flowTo = nullptr) {
    auto& r = ssaaRenderer();
    renderer::ShadingOptions shading;
    shading.supersampling = supersampling;
    r.setShading(shading);
    renderer::GBuffer gbuffer(width, height);
    Rendered out;
    if (flowTo != nullptr) {
        r.render(frame, gbuffer, *flowTo);
        out.flow = readFlow(gbuffer);
    } else {
        r.render(frame, gbuffer);
    }
    out.images = renderer::readBack(gbuffer);
    return out;
}

// Frames with silhouettes against walls and sky, panel seams and specular highlights.
std::vector<scene::FrameDescription> frames(int width, int height) {
    const auto shooter = shooterScene(width, height, 7, 5.0);
    std::vector<scene::FrameDescription> out;
    scene::FrameDescription aimed{shooter.restingCamera(), shooter.snapshot(0.37)};
    aimed.camera = aimedAt(aimed.camera, aimed.scene.objects.front().position);
    out.push_back(aimed);
    scene::FrameDescription wall{shooter.restingCamera(), shooter.snapshot(1.25)};
    wall.camera.yaw = glm::radians(60.0f);  // the right-hand wall and its ribs, at a slant
    out.push_back(wall);
    scene::FrameDescription hallway{shooter.restingCamera(), shooter.snapshot(2.5)};  // the far door's sky
    out.push_back(hallway);
    return out;
}

// Values whose bits differ: "bit-identical" has to hold for NaN and -0 as well.
template <typename T>
std::size_t bitDifferences(const std::vector<T>& a, const std::vector<T>& b) {
    if (a.size() != b.size()) return std::max(a.size(), b.size());
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.size(); ++i) n += std::memcmp(&a[i], &b[i], sizeof(T)) != 0 ? 1 : 0;
    return n;
}

int maxChannelDiff(const std::uint8_t* a, const std::uint8_t* b) {
    int d = 0;
    for (int c = 0; c < 4; ++c) d = std::max(d, std::abs(int(a[c]) - int(b[c])));
    return d;
}

// The oracle: each n x n block of a render at n times the size, averaged and rounded.
image::ImageRGBA8 boxMean(const image::ImageRGBA8& big, int n) {
    auto small = image::ImageRGBA8::make(big.width / n, big.height / n);
    for (int y = 0; y < small.height; ++y)
        for (int x = 0; x < small.width; ++x)
            for (int c = 0; c < 4; ++c) {
                int sum = 0;
                for (int j = 0; j < n; ++j)
                    for (int i = 0; i < n; ++i) sum += big.at(n * x + i, n * y + j)[c];
                small.at(x, y)[c] = static_cast<std::uint8_t>((sum + n * n / 2) / (n * n));
            }
    return small;
}

TEST(Supersampling, KeepsDepthIdsVelocityAndFlowOfThePixelCentreBitForBit) {
    for (const auto& frame : frames(kW, kH)) {
        scene::FrameDescription before = frame;
        before.scene = shooterScene(kW, kH, 7, 5.0).snapshot(frame.scene.time - 1.0 / 15.0);
        before.camera.yaw += 0.02f;
        const Rendered plain = render(frame, kW, kH, 1);
        const Rendered plainFlow = render(frame, kW, kH, 1, &before);
        ASSERT_FALSE(plainFlow.flow.empty());
        for (int n : {2, 3}) {
            SCOPED_TRACE("supersampling " + std::to_string(n) + ", t = " + std::to_string(frame.scene.time));
            for (const Rendered* reference : {&plain, &plainFlow}) {
                const bool withFlow = reference == &plainFlow;
                const Rendered ssaa = render(frame, kW, kH, n, withFlow ? &before : nullptr);
                EXPECT_EQ(bitDifferences(ssaa.images.depth.data, reference->images.depth.data), 0u);
                EXPECT_EQ(bitDifferences(ssaa.images.ids.data, reference->images.ids.data), 0u);
                EXPECT_EQ(bitDifferences(ssaa.images.velocity.data, reference->images.velocity.data), 0u);
                if (withFlow) {
                    EXPECT_EQ(bitDifferences(ssaa.flow, reference->flow), 0u);
                }
            }
        }
    }
}

TEST(Supersampling, ColourIsTheBoxMeanOfARenderAtNTimesTheSize) {
    for (int n : {2, 3}) {
        // Two sizes in turn at the same factor, so the sample buffer is reused and also made anew
        // for a new size; the oracle comes from the test support's own renderer, leaving this
        // one's factor alone between frames.
        for (const auto& [w, h] : {std::pair{kW, kH}, std::pair{160, 90}, std::pair{kW, kH}}) {
            for (const auto& frame : frames(w, h)) {
                SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + ", supersampling " + std::to_string(n) +
                             ", t = " + std::to_string(frame.scene.time));
                const auto expected = boxMean(testing::renderFrame(frame, n * w, n * h).colour, n);
                const auto actual = render(frame, w, h, n).images.colour;
                ASSERT_EQ(actual.width, expected.width);
                ASSERT_EQ(actual.height, expected.height);
                int over = 0, worst = 0;
                for (int y = 0; y < h; ++y)
                    for (int x = 0; x < w; ++x) {
                        const int d = maxChannelDiff(actual.at(x, y), expected.at(x, y));
                        worst = std::max(worst, d);
                        // 1 of 255: the GPU sums the samples as floats and rounds its own way
                        // (a mean of exactly k + 0.5 may go either way), the oracle in integers.
                        over += d > 1 ? 1 : 0;
                    }
                // The samples and the oracle's pixels are the same draws at the same size, but
                // into framebuffers of different formats, for which GL's invariance rules promise
                // nothing; 0.1 % leaves room for a rasteriser that differs there on a rare edge.
                EXPECT_LE(over, w * h / 1000) << "worst channel difference " << worst;
            }
        }
    }
}

TEST(Supersampling, SmoothsEdgesAndLeavesFlatAreasAlone) {
    const int n = 2;
    int pixels = 0, changed = 0, flat = 0, flatChanged = 0;
    for (const auto& frame : frames(kW, kH)) {
        const auto plain = render(frame, kW, kH, 1).images.colour;
        const auto ssaa = render(frame, kW, kH, n).images.colour;
        // Flatness is judged on the samples too, not only on the 1x pixels: a seam thinner than
        // a pixel can fall between two pixel centres and still cover some of their samples.
        const auto samples = render(frame, n * kW, n * kH, 1).images.colour;
        for (int y = 1; y < kH - 1; ++y)
            for (int x = 1; x < kW - 1; ++x) {
                ++pixels;
                const int d = maxChannelDiff(plain.at(x, y), ssaa.at(x, y));
                changed += d > 2 ? 1 : 0;
                // Flat: the pixel centre, its samples and the ring of samples around them all
                // within 4 of each other -- one smoothly shaded surface, no edge or seam nearby.
                bool isFlat = true;
                for (int j = -1; j <= n && isFlat; ++j)
                    for (int i = -1; i <= n && isFlat; ++i)
                        isFlat = maxChannelDiff(samples.at(n * x + i, n * y + j), plain.at(x, y)) <= 4;
                if (!isFlat) continue;
                ++flat;
                flatChanged += d > 2 ? 1 : 0;
            }
    }
    // Seams, ribs, crates and the target's silhouette cover much of a 96 x 54 frame (44 % of
    // pixels change by more than 2 here); a supersampling that does nothing changes none.
    EXPECT_GE(changed, pixels * 15 / 100) << "of " << pixels;
    // Enough flat pixels (25 % here) for the next check to mean something.
    ASSERT_GE(flat, pixels / 10) << "of " << pixels;
    // Smooth shading changes by a fraction of a unit over half a pixel, so the mean of a flat
    // pixel's samples is its centre's colour within rounding (none change by more than 1 here);
    // 1 % allows for a specular highlight's steeper gradient.
    EXPECT_LE(flatChanged, flat / 100) << "of " << flat << " flat pixels changed by more than 2";
}

TEST(Supersampling, RejectsFactorsOutsideOneToFour) {
    testing::glContext();
    for (int bad : {0, 5, -1}) {
        renderer::ShadingOptions shading;
        shading.supersampling = bad;
        const std::string named = "supersampling " + std::to_string(bad) + " ";
        try {
            renderer::ConventionalRenderer r(testing::sourceDataPaths(), shading);
            ADD_FAILURE() << "the constructor accepted supersampling " << bad;
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(named), std::string::npos) << e.what();
        }
        try {
            ssaaRenderer().setShading(shading);
            ADD_FAILURE() << "setShading accepted supersampling " << bad;
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(named), std::string::npos) << e.what();
        }
    }
}

}  // namespace
}  // namespace warplab
