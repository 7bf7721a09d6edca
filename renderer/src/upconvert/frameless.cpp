// Adaptive frameless sampling (seed 002, Dayal et al. 2005), emulated by a rasteriser at a
// fixed budget per displayed frame: an eighth of the pixels shaded at the displayed instant,
// placed by a controller that follows the colour variation of a deep buffer of samples, and
// reconstructed by an adaptive space-time filter. What the emulation changes from the paper's
// ray tracer, which streams samples one at a time: samples are shaded in one masked pass per
// displayed frame (all at the frame's instant, not each at its own); the controller's tiles
// are fixed 8 x 8 cells whose sample counts follow their error, where the paper splits and
// merges a K-D tiling until tiles hold equal variation (either way, sample density follows
// variation); the deep buffer keeps one sample per pixel, not four; samples are reprojected
// through the geometry pass (a depth and id test) instead of being splatted from their stored
// 3D points; and the crosshairs' spatial gradients are taken between neighbouring samples.
#include "upconvert/frameless.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "gbuffer_gl.h"
#include "gl/check.h"
#include "gl/program.h"
#include "upconvert/accumulation_history.h"
#include "upconvert/fullscreen.h"
#include "upconvert/stage_clock.h"
#include "scene/camera.h"

namespace warplab::renderer {
namespace {

constexpr int kCell = 8;  // controller cell side, pixels
// The controller's tile error (section 6.1), the variation and undersampling terms' shares; the
// occlusion term's share goes to undersampling, which is where occlusions and disocclusions
// leave pixels without a sample here.
constexpr double kVariationShare = 0.6;
// Every cell keeps this share of an even spread, so that new motion anywhere is found (the
// paper picks tiles at random for the same reason).
constexpr double kEvenShare = 0.25;

struct CellStats {
    float variation, spatial, temporal, empty;
};

// Integer sample counts per cell summing exactly to `budget`, each at most the cell's pixels,
// in proportion to `weight` (largest remainders).
std::vector<int> allocate(const std::vector<double>& weight, const std::vector<int>& room, int budget) {
    const std::size_t n = weight.size();
    std::vector<int> count(n, 0);
    std::vector<double> w = weight;
    int left = budget;
    // A few rounds: cells that fill up give their share to the rest.
    for (int round = 0; round < 8 && left > 0; ++round) {
        double total = 0.0;
        for (std::size_t i = 0; i < n; ++i)
            if (count[i] < room[i]) total += w[i];
        if (total <= 0.0) break;
        std::vector<std::pair<double, std::size_t>> remainders;
        int given = 0;
        for (std::size_t i = 0; i < n; ++i) {
            if (count[i] >= room[i]) continue;
            const double share = left * w[i] / total;
            const int whole = std::min(static_cast<int>(share), room[i] - count[i]);
            count[i] += whole;
            given += whole;
            if (count[i] < room[i]) remainders.push_back({share - whole, i});
        }
        left -= given;
        std::sort(remainders.begin(), remainders.end(), [](const auto& a, const auto& b) {
            return a.first > b.first || (a.first == b.first && a.second < b.second);
        });
        for (const auto& [r, i] : remainders) {
            if (left == 0) break;
            ++count[i];
            --left;
        }
    }
    for (std::size_t i = 0; i < n && left > 0; ++i) {  // whatever rounding left, anywhere with room
        const int add = std::min(left, room[i] - count[i]);
        count[i] += add;
        left -= add;
    }
    return count;
}

class FramelessMethod final : public UpconversionMethod {
public:
    FramelessMethod(const DataPaths& paths, const std::string& name, int share) : paths_(paths), share_(share) {
        info_.name = name;
        info_.description = "adaptive frameless sampling (Dayal et al. 2005), rasterised: 1/" + std::to_string(share) +
            " of the pixels shaded every frame where colour varies, an adaptive space-time filter over a "
            "reprojected deep buffer";
        info_.sourceRateHz = 15.0;  // its sources are not used; the bench renders them anyway
        info_.needsScene = true;
        info_.shadedShare = 1.0 / share;
        info_.historyFrames = 16;
        info_.adaptivePlacement = true;
        const auto build = [&](const char* fragment) {
            return gl::buildProgram(
                {paths.shaderDir, {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, fragment}}, {}});
        };
        update_ = build("frameless_update.frag");
        stats_ = build("frameless_stats.frag");
        reconstruct_ = build("frameless.frag");
    }

    const MethodInfo& info() const override { return info_; }
    double lastShadedSamples() override { return shadedSamples_; }
    SamplePlacement placement() const { return {kCell, cellsX_, cellsY_, placed_}; }
    void timeStages(bool on) override { clock_.enable(on); }
    std::vector<StageTime> lastStageTimes() const override { return clock_.times(); }
    // The age of the sample each pixel holds in the deep buffer (the one its filter weighs most).
    // A pixel holding none (a disocclusion not sampled yet) counts as 0, so the ages are a lower
    // bound there.
    std::vector<float> lastSampleAges() override {
        std::vector<float> deep(4 * static_cast<std::size_t>(width_) * height_);
        glBindFramebuffer(GL_FRAMEBUFFER, slots_[static_cast<std::size_t>(history_.written())].framebuffer.id());
        glReadBuffer(GL_COLOR_ATTACHMENT0);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, deep.data());
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        gl::checkErrors("reading the deep buffer's sample times");
        const float now = static_cast<float>(history_.time() - history_.origin());
        std::vector<float> ages(static_cast<std::size_t>(width_) * height_);
        for (int y = 0; y < height_; ++y)
            for (int x = 0; x < width_; ++x) {
                const float made = deep[4 * (static_cast<std::size_t>(y) * width_ + x) + 3];
                ages[static_cast<std::size_t>(height_ - 1 - y) * width_ + x] = made < 0.0f ? 0.0f : now - made;
            }
        return ages;
    }

    void produce(const UpconversionInput& input, DisplayFrame& out) override {
        if (input.scene == nullptr)
            throw std::invalid_argument(info_.name + ": needs the scene at the displayed instant");
        allocateBuffers(out.width(), out.height());
        advance(input);
        clock_.start();
        Slot& now = slots_[static_cast<std::size_t>(history_.written())];
        const Slot& before = slots_[static_cast<std::size_t>(history_.previous())];
        const scene::FrameDescription frame{input.camera, *input.scene};

        // 1. Geometry: depth, ids and velocity of every pixel.
        ShadingOptions geometry;
        geometry.geometryOnly = true;
        conventional().setShading(geometry);
        conventional().render(frame, now.geometry);
        clock_.done("geometry");
        // 2. The controller places this frame's samples from the last frame's statistics.
        placeSamples();
        clock_.done("control");
        // 3. Shading at those pixels only, at the sources' shading cost.
        ShadingOptions masked;
        masked.shadingCost = input.shading.shadingCost;
        masked.panelPattern = input.shading.panelPattern;
        masked.sampleMask = mask_.id();
        conventional().setShading(masked);
        conventional().render(frame, *shaded_);
        clock_.done("shading");
        // 4. The deep buffer, its statistics (read back for the controller), and the displayed frame.
        updateDeepBuffer(input, now, before);
        measureCells(input, now);
        reconstruct(input, now, out);
        clock_.done("filter");
    }

private:
    struct Slot {
        GBuffer geometry;
        gl::Texture deep;  // GL_RGBA32F: colour, time made (< 0: none)
        gl::Texture change;  // GL_RGBA32F: r = the temporal gradient at the pixel
        gl::Framebuffer framebuffer;
    };

    ConventionalRenderer& conventional() {
        if (!conventional_) conventional_ = std::make_unique<ConventionalRenderer>(paths_);
        return *conventional_;
    }

    void allocateBuffers(int width, int height) {
        if (width_ == width && height_ == height) return;
        width_ = width;
        height_ = height;
        cellsX_ = (width + kCell - 1) / kCell;
        cellsY_ = (height + kCell - 1) / kCell;
        slots_.clear();
        for (int i = 0; i < 2; ++i) {
            Slot s{GBuffer(width, height), makeTexture(GL_RGBA32F, GL_RGBA, GL_FLOAT, width, height),
                   makeTexture(GL_RGBA32F, GL_RGBA, GL_FLOAT, width, height), gl::Framebuffer::create()};
            glBindFramebuffer(GL_FRAMEBUFFER, s.framebuffer.id());
            glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, s.deep.id(), 0);
            glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, s.change.id(), 0);
            slots_.push_back(std::move(s));
        }
        shaded_ = std::make_unique<GBuffer>(width, height);
        mask_ = makeTexture(GL_R8UI, GL_RED_INTEGER, GL_UNSIGNED_BYTE, width, height);
        counts_ = makeTexture(GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, cellsX_, cellsY_);
        cellStats_ = makeTexture(GL_RGBA32F, GL_RGBA, GL_FLOAT, cellsX_, cellsY_);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        statsFramebuffer_ = gl::Framebuffer::create();
        glBindFramebuffer(GL_FRAMEBUFFER, statsFramebuffer_.id());
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, cellStats_.id(), 0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glBindTexture(GL_TEXTURE_2D, 0);
        maskPixels_.assign(static_cast<std::size_t>(width) * height, 0);
        history_.reset();
    }

    // The frame's place in the history; the statistics the last frame measured steer this one.
    void advance(const UpconversionInput& input) {
        history_.advance(input.displayTime, viewProjectionOf(input.camera));
        if (history_.repeat()) return;
        if (!history_.follows()) statsKnown_ = false;
        if (statsKnown_) statsForPlacing_ = statsLastMeasured_;
    }

    glm::mat4 viewProjectionOf(const scene::CameraState& camera) const {
        const float aspect = static_cast<float>(width_) / static_cast<float>(height_);
        return scene::projectionMatrix(camera, aspect) * scene::viewMatrix(camera);
    }

    int budget() const { return width_ * height_ / share_; }

    void placeSamples() {
        const std::size_t cells = static_cast<std::size_t>(cellsX_) * cellsY_;
        std::vector<int> room(cells);
        for (int cy = 0; cy < cellsY_; ++cy)
            for (int cx = 0; cx < cellsX_; ++cx)
                room[static_cast<std::size_t>(cy) * cellsX_ + cx] = (std::min(width_, (cx + 1) * kCell) - cx * kCell) *
                    (std::min(height_, (cy + 1) * kCell) - cy * kCell);
        const double pixels = static_cast<double>(width_) * height_;
        std::vector<double> weight(cells);
        double variation = 0.0, empty = 0.0;
        if (statsKnown_)
            for (const CellStats& s : statsForPlacing_) {
                variation += s.variation;
                empty += s.empty;
            }
        for (std::size_t i = 0; i < cells; ++i) {
            const double even = room[i] / pixels;
            double error = even;
            if (statsKnown_) {
                const CellStats& s = statsForPlacing_[i];
                const double v = variation > 0.0 ? s.variation / variation : even;
                const double u = empty > 0.0 ? s.empty / empty : even;
                error = kVariationShare * v + (1.0 - kVariationShare) * u;
            }
            weight[i] = kEvenShare * even + (1.0 - kEvenShare) * error;
        }
        placed_ = allocate(weight, room, budget());
        // Which pixels: chosen at random within each cell, from a stream seeded by the frame's
        // place in the sequence (the same frames give the same samples).
        std::fill(maskPixels_.begin(), maskPixels_.end(), std::uint8_t{0});
        std::mt19937_64 random(0x5eed0000u + static_cast<std::uint64_t>(history_.frameIndex()));
        std::vector<int> order;
        long placed = 0;
        for (int cy = 0; cy < cellsY_; ++cy)
            for (int cx = 0; cx < cellsX_; ++cx) {
                const int n = placed_[static_cast<std::size_t>(cy) * cellsX_ + cx];
                const int w = std::min(width_, (cx + 1) * kCell) - cx * kCell;
                const int h = std::min(height_, (cy + 1) * kCell) - cy * kCell;
                order.resize(static_cast<std::size_t>(w) * h);
                std::iota(order.begin(), order.end(), 0);
                for (int k = 0; k < n; ++k) {  // a partial Fisher-Yates shuffle
                    std::uniform_int_distribution<int> pick(k, w * h - 1);
                    std::swap(order[static_cast<std::size_t>(k)], order[static_cast<std::size_t>(pick(random))]);
                    const int x = cx * kCell + order[static_cast<std::size_t>(k)] % w;
                    const int y = cy * kCell + order[static_cast<std::size_t>(k)] / w;
                    maskPixels_[static_cast<std::size_t>(y) * width_ + x] = 1;
                    ++placed;
                }
            }
        shadedSamples_ = static_cast<double>(placed);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glBindTexture(GL_TEXTURE_2D, mask_.id());
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width_, height_, GL_RED_INTEGER, GL_UNSIGNED_BYTE, maskPixels_.data());
        std::vector<std::uint32_t> counts(placed_.begin(), placed_.end());
        glBindTexture(GL_TEXTURE_2D, counts_.id());
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, cellsX_, cellsY_, GL_RED_INTEGER, GL_UNSIGNED_INT, counts.data());
        glBindTexture(GL_TEXTURE_2D, 0);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    }

    void updateDeepBuffer(const UpconversionInput& input, const Slot& now, const Slot& before) {
        glBindFramebuffer(GL_FRAMEBUFFER, now.framebuffer.id());
        const GLenum two[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        glDrawBuffers(2, two);
        glViewport(0, 0, width_, height_);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        glUseProgram(update_.id());
        const auto& g = now.geometry.impl();
        const auto& previous = before.geometry.impl();
        bindTexture(update_, "uDepth", 0, g.depth);
        bindTexture(update_, "uIds", 1, g.ids);
        bindTexture(update_, "uVelocity", 2, g.velocity);
        bindTexture(update_, "uShaded", 3, shaded_->impl().colour);
        bindTexture(update_, "uMask", 4, mask_);
        bindTexture(update_, "uPreviousDeep", 5, before.deep);
        bindTexture(update_, "uPreviousChange", 6, before.change);
        bindTexture(update_, "uPreviousDepth", 7, previous.depth);
        bindTexture(update_, "uPreviousIds", 8, previous.ids);
        auto u = [&](const char* name) { return gl::uniform(update_, name); };
        const glm::mat4 inverse = glm::mat4(glm::inverse(glm::dmat4(history_.viewProjection())));
        glUniformMatrix4fv(u("uInverseViewProjection"), 1, GL_FALSE, glm::value_ptr(inverse));
        glUniformMatrix4fv(u("uPreviousViewProjection"), 1, GL_FALSE,
                           glm::value_ptr(history_.previousViewProjection()));
        glUniform1f(u("uTime"), static_cast<float>(input.displayTime - timeOrigin()));
        glUniform1f(u("uDt"), static_cast<float>(history_.dt()));
        glUniform1f(u("uNear"), input.camera.nearPlane);
        glUniform1f(u("uFar"), input.camera.farPlane);
        glUniform1i(u("uHaveHistory"), history_.follows() ? 1 : 0);
        glUniform1f(u("uDepthTolerance"), AccumulationHistory::kSameSurfaceDepth);
        pass_.draw();
        endImagePass(9);
    }

    void measureCells(const UpconversionInput& input, const Slot& now) {
        glBindFramebuffer(GL_FRAMEBUFFER, statsFramebuffer_.id());
        const GLenum one[] = {GL_COLOR_ATTACHMENT0};
        glDrawBuffers(1, one);
        glViewport(0, 0, cellsX_, cellsY_);
        glDisable(GL_DEPTH_TEST);
        glUseProgram(stats_.id());
        bindTexture(stats_, "uDeep", 0, now.deep);
        bindTexture(stats_, "uChange", 1, now.change);
        glUniform1i(gl::uniform(stats_, "uCell"), kCell);
        glUniform1f(gl::uniform(stats_, "uTime"), static_cast<float>(input.displayTime - timeOrigin()));
        pass_.draw();
        // The controller reads them for the next frame (a small image: cellsX x cellsY).
        if (!history_.repeat()) {
            statsLastMeasured_.resize(static_cast<std::size_t>(cellsX_) * cellsY_);
            glReadBuffer(GL_COLOR_ATTACHMENT0);
            glReadPixels(0, 0, cellsX_, cellsY_, GL_RGBA, GL_FLOAT, statsLastMeasured_.data());
            statsKnown_ = true;
        }
        endImagePass(2);
    }

    void reconstruct(const UpconversionInput& input, const Slot& now, DisplayFrame& out) {
        auto& target = out.buffer().impl();
        glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer.id());
        const GLenum three[] = {GBuffer::Impl::kColourAttachment, GBuffer::Impl::kIdAttachment,
                                GBuffer::Impl::kVelocityAttachment};
        glDrawBuffers(3, three);
        glViewport(0, 0, width_, height_);
        glDisable(GL_DEPTH_TEST);
        glUseProgram(reconstruct_.id());
        bindTexture(reconstruct_, "uDeep", 0, now.deep);
        bindTexture(reconstruct_, "uStats", 1, cellStats_);
        bindTexture(reconstruct_, "uIds", 2, now.geometry.impl().ids);
        bindTexture(reconstruct_, "uCounts", 3, counts_);
        auto u = [&](const char* name) { return gl::uniform(reconstruct_, name); };
        glUniform1i(u("uCell"), kCell);
        glUniform1f(u("uTime"), static_cast<float>(input.displayTime - timeOrigin()));
        glUniform1f(u("uRefreshHz"), static_cast<float>(history_.dt() > 0.0 ? 1.0 / history_.dt() : 120.0));
        glUniform1f(u("uFreshPerPixel"), 1.0f / static_cast<float>(share_));
        pass_.draw();
        endImagePass(4);
        gl::checkErrors(info_.name.c_str());
    }

    // Sample times are stored from the start of the run of frames, so that a float keeps them to
    // the microsecond however long the session.
    double timeOrigin() const { return history_.origin(); }

    MethodInfo info_;
    DataPaths paths_;
    int share_;
    std::unique_ptr<ConventionalRenderer> conventional_;
    gl::Program update_, stats_, reconstruct_;
    FullscreenPass pass_;
    int width_ = 0, height_ = 0, cellsX_ = 0, cellsY_ = 0;
    std::vector<Slot> slots_;
    std::unique_ptr<GBuffer> shaded_;
    gl::Texture mask_, counts_, cellStats_;
    gl::Framebuffer statsFramebuffer_;
    std::vector<std::uint8_t> maskPixels_;
    std::vector<CellStats> statsLastMeasured_, statsForPlacing_;
    std::vector<int> placed_;
    bool statsKnown_ = false;
    AccumulationHistory history_;
    double shadedSamples_ = std::nan("");
    StageClock clock_;
};

}  // namespace

std::unique_ptr<UpconversionMethod> makeFrameless(const DataPaths& paths, const std::string& name, int share) {
    return std::make_unique<FramelessMethod>(paths, name, share);
}

SamplePlacement lastPlacement(const UpconversionMethod& method) {
    const auto* frameless = dynamic_cast<const FramelessMethod*>(&method);
    if (frameless == nullptr) throw std::invalid_argument(method.info().name + " is not a frameless method");
    return frameless->placement();
}

}  // namespace warplab::renderer
