// Spatio-temporal upsampling (seed 001, Herzog et al. 2010): every displayed frame is a
// deferred renderer's -- a geometry pass over all pixels (depth, id, velocity), the expensive
// shading on a rotating lattice of them only (a low-resolution render shifted by a sub-pixel
// offset, section 3.2), and the joint spatio-temporal filter of shaders/stu.frag, which
// upsamples the lattice guided by the geometry and blends it into the exponential history
// buffer reprojected from the frame before (sections 3.3-3.5).
#include "upconvert/spatiotemporal.h"

#include <array>
#include <cmath>
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

// h_w's cap: the history never outweighs this many frames' spatial estimates, so that a change
// the gradient misses still fades in within a few frames.
constexpr float kMaxHistoryWeight = 16.0f;
// How near a texel centre (pixels) a pixel's reprojection must land for the pixel to count as
// still: its history texel read as it is and its own lattice samples kept exact
// (shaders/stu.frag). Above the rounding of a still camera's reprojection (every pixel of a
// still 1080p frame lands within it; 3.6 % miss 1e-4 px), far below any resampling's blur: a
// pixel drifting at the tolerance moves 0.008 px over a lattice cycle of 8 frames before its
// own sample is shaded again.
constexpr float kStillTolerance = 0.001f;

// The order the lattice's phases are shaded in: each next phase far from the last, so that a
// frame's samples and the previous frame's interleave (Herzog et al.'s Figure 2 for 2 x 2).
std::vector<glm::ivec2> phaseOrder(glm::ivec2 step) {
    std::vector<glm::ivec2> order;
    if (step == glm::ivec2(2, 2)) return {{0, 0}, {1, 1}, {1, 0}, {0, 1}};
    // Otherwise row by row with the columns in bit-reversed order and the rows alternating.
    for (int i = 0; i < step.x * step.y; ++i) {
        const int row = i % step.y;
        int column = i / step.y, reversed = 0;
        for (int bit = 1; bit < step.x; bit <<= 1, column >>= 1) reversed = (reversed << 1) | (column & 1);
        order.push_back({reversed % step.x, row});
    }
    return order;
}

class SpatioTemporalMethod final : public UpconversionMethod {
public:
    SpatioTemporalMethod(const DataPaths& paths, const std::string& name, glm::ivec2 step)
        : paths_(paths), step_(step), phases_(phaseOrder(step)) {
        info_.name = name;
        info_.description =
            "spatio-temporal upsampling (Herzog et al. 2010): a geometry pass every frame, shading on 1/" +
            std::to_string(step.x * step.y) +
            " of the pixels (a rotating lattice), a joint space-time filter with "
            "a reprojected history";
        info_.sourceRateHz = 15.0;  // its sources are not used; the bench renders them anyway
        info_.needsScene = true;
        info_.shadedShare = 1.0 / (step.x * step.y);
        info_.historyFrames = 2 * step.x * step.y;
        program_ = gl::buildProgram(
            {paths.shaderDir, {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "stu.frag"}}, {}});
    }

    const MethodInfo& info() const override { return info_; }
    double lastShadedSamples() override { return shadedSamples_; }
    void timeStages(bool on) override { clock_.enable(on); }
    std::vector<StageTime> lastStageTimes() const override { return clock_.times(); }

    void produce(const UpconversionInput& input, DisplayFrame& out) override {
        if (input.scene == nullptr)
            throw std::invalid_argument(info_.name + ": needs the scene at the displayed instant");
        const int width = out.width(), height = out.height();
        if (width % step_.x != 0 || height % step_.y != 0)
            throw std::invalid_argument(info_.name + ": the display's " + std::to_string(width) + "x" +
                                        std::to_string(height) + " pixels do not divide into its " +
                                        std::to_string(step_.x) + "x" + std::to_string(step_.y) + " lattice");
        allocate(width, height);
        const float aspect = static_cast<float>(width) / static_cast<float>(height);
        history_.advance(input.displayTime,
                         scene::projectionMatrix(input.camera, aspect) * scene::viewMatrix(input.camera));
        clock_.start();
        Slot& now = slots_[static_cast<std::size_t>(history_.written())];
        const Slot& before = slots_[static_cast<std::size_t>(history_.previous())];
        const scene::FrameDescription frame{input.camera, *input.scene};

        // 1. Geometry: every pixel's depth, id and velocity, no shading.
        ShadingOptions geometry;
        geometry.geometryOnly = true;
        conventional().setShading(geometry);
        conventional().render(frame, now.geometry);
        clock_.done("geometry");
        // 2. Shading: the lattice's phase for this frame, at the sources' shading cost.
        ShadingOptions lattice;
        lattice.shadingCost = input.shading.shadingCost;
        lattice.panelPattern = input.shading.panelPattern;
        lattice.latticeStep = step_;
        lattice.latticePhase = phases_[static_cast<std::size_t>(history_.frameIndex()) % phases_.size()];
        conventional().setShading(lattice);
        conventional().render(frame, *low_);
        shadedSamples_ = static_cast<double>(low_->width()) * low_->height();
        clock_.done("shading");
        // 3. The filter, into the displayed frame and the history.
        filter(input, now, before, out);
        clock_.done("filter");
    }

private:
    struct Slot {
        GBuffer geometry;
        gl::Texture history;  // GL_RGBA32F: rgb h_r, a h_w
        gl::Texture gradients;  // GL_RGBA32F: the last three relative temporal gradients, own flag
    };

    ConventionalRenderer& conventional() {
        if (!conventional_) conventional_ = std::make_unique<ConventionalRenderer>(paths_);
        return *conventional_;
    }

    void allocate(int width, int height) {
        if (!slots_.empty() && slots_[0].geometry.width() == width && slots_[0].geometry.height() == height) return;
        slots_.clear();
        for (int i = 0; i < 2; ++i)
            slots_.push_back({GBuffer(width, height), makeTexture(GL_RGBA32F, GL_RGBA, GL_FLOAT, width, height),
                              makeTexture(GL_RGBA32F, GL_RGBA, GL_FLOAT, width, height)});
        glBindTexture(GL_TEXTURE_2D, 0);
        low_ = std::make_unique<GBuffer>(width / step_.x, height / step_.y);
        framebuffer_ = gl::Framebuffer::create();
        history_.reset();
    }

    void filter(const UpconversionInput& input, const Slot& now, const Slot& before, DisplayFrame& out) {
        auto& target = out.buffer().impl();
        const auto& g = now.geometry.impl();
        const auto& previous = before.geometry.impl();
        const auto& low = low_->impl();
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target.colour.id(), 0);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, target.ids.id(), 0);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT2, GL_TEXTURE_2D, target.velocity.id(), 0);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT3, GL_TEXTURE_2D, now.history.id(), 0);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT4, GL_TEXTURE_2D, now.gradients.id(), 0);
        const GLenum five[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3,
                               GL_COLOR_ATTACHMENT4};
        glDrawBuffers(5, five);
        glViewport(0, 0, target.width, target.height);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        glUseProgram(program_.id());
        bindTexture(program_, "uDepth", 0, g.depth);
        bindTexture(program_, "uIds", 1, g.ids);
        bindTexture(program_, "uVelocity", 2, g.velocity);
        bindTexture(program_, "uLowColour", 3, low.colour);
        bindTexture(program_, "uLowDepth", 4, low.depth);
        bindTexture(program_, "uLowIds", 5, low.ids);
        bindTexture(program_, "uHistory", 6, before.history);
        bindTexture(program_, "uGradients", 7, before.gradients);
        bindTexture(program_, "uPreviousDepth", 8, previous.depth);
        bindTexture(program_, "uPreviousIds", 9, previous.ids);
        auto u = [&](const char* name) { return gl::uniform(program_, name); };
        const glm::dmat4 inverse = glm::inverse(glm::dmat4(history_.viewProjection()));
        const glm::mat4 reprojection = glm::mat4(glm::dmat4(history_.previousViewProjection()) * inverse);
        glUniformMatrix4fv(u("uInverseViewProjection"), 1, GL_FALSE, glm::value_ptr(glm::mat4(inverse)));
        glUniformMatrix4fv(u("uPreviousViewProjection"), 1, GL_FALSE,
                           glm::value_ptr(history_.previousViewProjection()));
        glUniformMatrix4fv(u("uReprojection"), 1, GL_FALSE, glm::value_ptr(reprojection));
        glUniform2i(u("uStep"), step_.x, step_.y);
        const glm::ivec2 phase = phases_[static_cast<std::size_t>(history_.frameIndex()) % phases_.size()];
        glUniform2i(u("uPhase"), phase.x, phase.y);
        glUniform1f(u("uDt"), static_cast<float>(history_.dt()));
        glUniform1f(u("uNear"), input.camera.nearPlane);
        glUniform1f(u("uFar"), input.camera.farPlane);
        glUniform1i(u("uHaveHistory"), history_.follows() ? 1 : 0);
        glUniform1f(u("uMaxHistoryWeight"), kMaxHistoryWeight);
        glUniform1f(u("uDepthTolerance"), AccumulationHistory::kSameSurfaceDepth);
        glUniform1f(u("uStillTolerance"), kStillTolerance);
        pass_.draw();
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
        for (GLenum a : five) glFramebufferTexture2D(GL_FRAMEBUFFER, a, GL_TEXTURE_2D, 0, 0);
        endImagePass(10);
        gl::checkErrors(info_.name.c_str());
    }

    MethodInfo info_;
    DataPaths paths_;
    glm::ivec2 step_;
    std::vector<glm::ivec2> phases_;
    std::unique_ptr<ConventionalRenderer> conventional_;  // made at the first frame: it loads the hangar
    gl::Program program_;
    FullscreenPass pass_;
    std::vector<Slot> slots_;
    std::unique_ptr<GBuffer> low_;
    gl::Framebuffer framebuffer_;
    AccumulationHistory history_;
    double shadedSamples_ = std::nan("");
    StageClock clock_;
};

}  // namespace

std::unique_ptr<UpconversionMethod> makeSpatioTemporal(const DataPaths& paths, const std::string& name,
                                                       glm::ivec2 step) {
    return std::make_unique<SpatioTemporalMethod>(paths, name, step);
}

}  // namespace warplab::renderer
