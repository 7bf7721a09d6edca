// The baselines every upconversion method is judged beside: sample-and-hold at a lower
// rendering rate (what conventional 15/30/60 Hz looks like on a 120 Hz display) and a linear
// blend of the two neighbouring 15 Hz frames.
#include "upconvert/simple_methods.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gbuffer_gl.h"
#include "gl/check.h"
#include "upconvert/fullscreen.h"

namespace warplab::renderer {
namespace {

void bindTarget(DisplayFrame& out) {
    auto& g = out.buffer().impl();
    glBindFramebuffer(GL_FRAMEBUFFER, g.framebuffer.id());
    glViewport(0, 0, g.width, g.height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
}

void unbind() {
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, 0);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glEnable(GL_DEPTH_TEST);
}

void requireSource(const SourceFrame* source, const DisplayFrame& out, const MethodInfo& info, const char* which) {
    if (source == nullptr) throw std::invalid_argument(info.name + ": no " + which + " source frame");
    checkSourceSize(*source, out, info);
}

class HoldMethod final : public UpconversionMethod {
public:
    HoldMethod(const DataPaths& paths, double rateHz) {
        info_.name = "hold" + std::to_string(static_cast<int>(rateHz));
        info_.description = "conventional " + std::to_string(static_cast<int>(rateHz)) +
            " Hz, each frame held until the next (sample and hold)";
        info_.sourceRateHz = rateHz;
        info_.reportsCorrespondence = true;  // pixel (x, y) shows source pixel (x, y) (past any band)
        info_.acceptsGuardBand = true;  // shows the displayed part of a banded source
        program_ = gl::buildProgram(
            {paths.shaderDir, {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "hold.frag"}}, {}});
    }
    const MethodInfo& info() const override { return info_; }
    void produce(const UpconversionInput& input, DisplayFrame& out) override {
        requireSource(input.previous, out, info_, "previous");
        bindTarget(out);
        glUseProgram(program_.id());
        const auto& src = input.previous->gbuffer.impl();
        bindTexture(program_, "uColour", 0, src.colour);
        bindTexture(program_, "uIds", 1, src.ids);
        glUniform2i(gl::uniform(program_, "uBand"), input.previous->band.x, input.previous->band.y);
        glUniform1i(gl::uniform(program_, "uSourceHeight"), src.height);
        pass_.draw();
        unbind();
        gl::checkErrors("holding a frame");
    }

private:
    MethodInfo info_;
    gl::Program program_;
    FullscreenPass pass_;
};

class BlendMethod final : public UpconversionMethod {
public:
    explicit BlendMethod(const DataPaths& paths) {
        info_.name = "blend";
        info_.description = "linear blend of the two neighbouring 15 Hz frames (needs the next one)";
        info_.sourceRateHz = 15.0;
        info_.needsNext = true;
        program_ = gl::buildProgram(
            {paths.shaderDir, {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "blend.frag"}}, {}});
    }
    const MethodInfo& info() const override { return info_; }
    void produce(const UpconversionInput& input, DisplayFrame& out) override {
        requireSource(input.previous, out, info_, "previous");
        requireSource(input.next, out, info_, "next");
        const double t0 = input.previous->depicts.scene.time, t1 = input.next->depicts.scene.time;
        if (!(t1 > t0)) throw std::invalid_argument("blend: the next source frame is not later than the previous");
        const double alpha = std::clamp((input.displayTime - t0) / (t1 - t0), 0.0, 1.0);
        bindTarget(out);
        glUseProgram(program_.id());
        bindTexture(program_, "uColourA", 0, input.previous->gbuffer.impl().colour);
        bindTexture(program_, "uColourB", 1, input.next->gbuffer.impl().colour);
        bindTexture(program_, "uIdsA", 2, input.previous->gbuffer.impl().ids);
        bindTexture(program_, "uIdsB", 3, input.next->gbuffer.impl().ids);
        glUniform1f(gl::uniform(program_, "uAlpha"), static_cast<float>(alpha));
        pass_.draw();
        unbind();
        gl::checkErrors("blending two frames");
    }

private:
    MethodInfo info_;
    gl::Program program_;
    FullscreenPass pass_;
};

}  // namespace

std::unique_ptr<UpconversionMethod> makeHold(const DataPaths& paths, double rateHz) {
    return std::make_unique<HoldMethod>(paths, rateHz);
}
std::unique_ptr<UpconversionMethod> makeBlend(const DataPaths& paths) { return std::make_unique<BlendMethod>(paths); }

}  // namespace warplab::renderer
