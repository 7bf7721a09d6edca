#include "upconvert/bireproj.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "gbuffer_gl.h"
#include "gl/check.h"
#include "gl/program.h"
#include "scene_geometry.h"
#include "upconvert/fullscreen.h"
#include "scene/camera.h"
#include "scene/motion.h"

namespace warplab::renderer {
namespace {

// What the flow fields of a pair of I-frames were drawn for: reused while the pair is the same.
struct PairKey {
    const SourceFrame* previous = nullptr;
    const SourceFrame* next = nullptr;
    std::uint64_t previousSerial = 0, nextSerial = 0;  // which renders they hold (renderSource)
    double previousTime = 0, nextTime = 0;
    float previousYaw = 0, previousPitch = 0, nextYaw = 0, nextPitch = 0;
    bool operator==(const PairKey& o) const {
        return previous == o.previous && next == o.next && previousSerial == o.previousSerial &&
            nextSerial == o.nextSerial && previousTime == o.previousTime && nextTime == o.nextTime &&
            previousYaw == o.previousYaw && previousPitch == o.previousPitch && nextYaw == o.nextYaw &&
            nextPitch == o.nextPitch;
    }
};

PairKey keyOf(const UpconversionInput& in) {
    return {in.previous,
            in.next,
            in.previous->serial,
            in.next->serial,
            in.previous->depicts.scene.time,
            in.next->depicts.scene.time,
            in.previous->depicts.camera.yaw,
            in.previous->depicts.camera.pitch,
            in.next->depicts.camera.yaw,
            in.next->depicts.camera.pitch};
}

gl::Texture makeFloatTexture(int width, int height) {
    gl::Texture t = gl::Texture::create();
    glBindTexture(GL_TEXTURE_2D, t.id());
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
    return t;
}

class BireprojMethod final : public UpconversionMethod {
public:
    BireprojMethod(const DataPaths& paths, const std::string& name, const BireprojSettings& settings)
        : settings_(settings), geometry_(paths) {
        if (settings.iterations < 1 || settings.iterations > 8)
            throw std::invalid_argument(name + ": iterations must be 1..8");
        info_.name = name;
        info_.sourceRateHz = 15.0;
        info_.needsNext = true;
        info_.reportsCorrespondence = true;
        info_.usesEarlierFrames = settings.latestInit;
        info_.usesSourceFlow = true;
        info_.description = "image-based bidirectional reprojection between 15 Hz I-frames, m = " +
            std::to_string(settings.iterations) + (settings.dualInit ? ", dual" : "") +
            (settings.latestInit ? ", latest-frame" : "") + " initialisation";
        if (!settings.dualInit && !settings.latestInit) info_.description += " (default start only)";
        flowProgram_ = gl::buildProgram(
            {paths.shaderDir,
             {{GL_VERTEX_SHADER, "flow.vert"}, {GL_FRAGMENT_SHADER, "flow.frag", {"flow_common.glsl"}}},
             {}});
        program_ = gl::buildProgram({paths.shaderDir,
                                     {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "bireproj.frag"}},
                                     {"ITERATIONS " + std::to_string(settings.iterations),
                                      "DUAL_INIT " + std::to_string(settings.dualInit ? 1 : 0),
                                      "LATEST_INIT " + std::to_string(settings.latestInit ? 1 : 0),
                                      "NEIGHBOURHOOD " + std::to_string(settings.neighbourhood)}});
    }

    const MethodInfo& info() const override { return info_; }

    // The I-frame work: the forward flow of the previous I-frame and the backward flow of the
    // next, drawn once per pair and reused by every B-frame between them.
    void prepare(const UpconversionInput& input) override {
        check(input);
        const PairKey key = keyOf(input);
        const int w = input.previous->gbuffer.width(), h = input.previous->gbuffer.height();
        if (!forward_ || forward_->width() != w || forward_->height() != h) {
            forward_ = std::make_unique<GBuffer>(w, h);
            backward_ = std::make_unique<GBuffer>(w, h);
            for (auto& o : offsets_) o = makeFloatTexture(w, h);
            flowsFor_.reset();
        }
        if (flowsFor_ && *flowsFor_ == key) return;
        // The forward flow of the earlier I-frame needs the later one's instant, so it is drawn
        // now, as seed 000 section 5 draws it; the later I-frame's backward flow came with its
        // own render where the renderer was asked for it (the condition's sessions, the bench).
        drawFlow(input.previous->depicts, input.next->depicts, *forward_);
        const auto& next = input.next->gbuffer.impl();
        const auto& before = input.previous->depicts;
        backwardFromSource_ = next.flowTo && next.flowTo->time == before.scene.time &&
            next.flowTo->yaw == before.camera.yaw && next.flowTo->pitch == before.camera.pitch;
        if (!backwardFromSource_) drawFlow(input.next->depicts, input.previous->depicts, *backward_);
        flowsFor_ = key;
        latest_ = {};  // a new interval: no earlier B-frame in it
        initFrom_ = {};
    }

    void produce(const UpconversionInput& input, DisplayFrame& out) override {
        prepare(input);
        const auto& p = input.previous->gbuffer.impl();
        const auto& n = input.next->gbuffer.impl();
        checkSourceSize(*input.previous, out, info_);
        checkSourceSize(*input.next, out, info_);
        const double t0 = input.previous->depicts.scene.time, t1 = input.next->depicts.scene.time;
        const float alpha = static_cast<float>(std::clamp((input.displayTime - t0) / (t1 - t0), 0.0, 1.0));

        // Latest-frame initialisation reads the offsets of the latest earlier B-frame of this
        // interval. Repeating a frame (the bench's timed repeats) reads the same ones again,
        // so a repeat gives the same pixels.
        if (latest_.alpha > 0.0f && latest_.alpha < alpha)
            initFrom_ = latest_;
        else if (latest_.alpha != alpha)
            initFrom_ = {};
        const int write = initFrom_.slot == 0 ? 1 : 0;

        auto& target = out.buffer().impl();
        glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer.id());
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT3, GL_TEXTURE_2D, offsets_[write].id(), 0);
        const GLenum buffers[] = {GBuffer::Impl::kColourAttachment, GBuffer::Impl::kIdAttachment,
                                  GBuffer::Impl::kVelocityAttachment, GL_COLOR_ATTACHMENT3};
        glDrawBuffers(4, buffers);
        glViewport(0, 0, target.width, target.height);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);

        glUseProgram(program_.id());
        bindTexture(program_, "uColour0", 0, p.colour);
        bindTexture(program_, "uColour1", 1, n.colour);
        bindTexture(program_, "uIds0", 2, p.ids);
        bindTexture(program_, "uIds1", 3, n.ids);
        bindTexture(program_, "uFlowF", 4, forward_->impl().velocity);
        bindTexture(program_, "uFlowB", 5, backwardFromSource_ ? n.flow : backward_->impl().velocity);
        // Never the texture being written: with no earlier frame the shader ignores it anyway.
        bindTexture(program_, "uPreviousOffsets", 6, offsets_[1 - write]);
        glUniform2f(gl::uniform(program_, "uSize"), static_cast<float>(target.width),
                    static_cast<float>(target.height));
        glUniform1f(gl::uniform(program_, "uAlpha"), alpha);
        glUniform1f(gl::uniform(program_, "uPreviousAlpha"), initFrom_.slot < 0 ? 0.0f : initFrom_.alpha);
        glUniform1f(gl::uniform(program_, "uEps1"), settings_.errorThresholdPx);
        glUniform1f(gl::uniform(program_, "uEps2"), settings_.depthThreshold);
        pass_.draw();

        // Leave the display frame's framebuffer as it was made: three attachments.
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT3, GL_TEXTURE_2D, 0, 0);
        glDrawBuffers(3, buffers);
        for (int unit = 6; unit >= 0; --unit) {
            glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
            glBindTexture(GL_TEXTURE_2D, 0);
        }
        glUseProgram(0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glEnable(GL_DEPTH_TEST);
        gl::checkErrors("bidirectional reprojection");
        latest_ = {write, alpha};
    }

private:
    struct Offsets {
        int slot = -1;  // which of offsets_ holds them; -1 = none
        float alpha = 0.0f;  // the B-frame they were computed for
    };

    void check(const UpconversionInput& in) const {
        if (in.previous == nullptr || in.next == nullptr)
            throw std::invalid_argument(info_.name + ": needs the previous and the next source frame");
        if (in.previous->gbuffer.width() != in.next->gbuffer.width() ||
            in.previous->gbuffer.height() != in.next->gbuffer.height())
            throw std::invalid_argument(info_.name + ": the two source frames differ in size");
        if (!(in.next->depicts.scene.time > in.previous->depicts.scene.time))
            throw std::invalid_argument(info_.name + ": the next source frame is not later than the previous");
    }

    // The flow of `from`'s visible surface towards `to`'s instant, into flow.velocity (see
    // flow.frag), with from's ids.
    void drawFlow(const scene::FrameDescription& from, const scene::FrameDescription& to, GBuffer& flow) {
        auto& g = flow.impl();
        glBindFramebuffer(GL_FRAMEBUFFER, g.framebuffer.id());
        glViewport(0, 0, g.width, g.height);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        const GLuint noId[4] = {scene::kIdNone, 0, 0, 0};
        glClearBufferuiv(GL_COLOR, 1, noId);
        glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);

        const float aspect = static_cast<float>(g.width) / static_cast<float>(g.height);
        const glm::mat4 view = scene::viewMatrix(from.camera), otherView = scene::viewMatrix(to.camera);
        const glm::mat4 viewProjection = scene::projectionMatrix(from.camera, aspect) * view;
        const glm::mat4 otherViewProjection = scene::projectionMatrix(to.camera, aspect) * otherView;
        const glm::mat4 inverse = glm::mat4(glm::inverse(glm::dmat4(viewProjection)));
        glUseProgram(flowProgram_.id());
        auto u = [&](const char* name) { return gl::uniform(flowProgram_, name); };
        glUniformMatrix4fv(u("uView"), 1, GL_FALSE, glm::value_ptr(view));
        glUniformMatrix4fv(u("uOtherView"), 1, GL_FALSE, glm::value_ptr(otherView));
        glUniformMatrix4fv(u("uViewProjection"), 1, GL_FALSE, glm::value_ptr(viewProjection));
        glUniformMatrix4fv(u("uOtherViewProjection"), 1, GL_FALSE, glm::value_ptr(otherViewProjection));
        glUniformMatrix4fv(u("uFlowInverseViewProjection"), 1, GL_FALSE, glm::value_ptr(inverse));
        glUniformMatrix4fv(u("uFlowOtherViewProjection"), 1, GL_FALSE, glm::value_ptr(otherViewProjection));
        glUniform2f(u("uFlowSize"), static_cast<float>(g.width), static_cast<float>(g.height));
        glUniform1f(u("uFlowFar"), from.camera.farPlane);

        geometry_.drawSky(flowProgram_);  // the sky first, everywhere; then the scene over it
        const GLint model = u("uModel"), otherModel = u("uOtherModel"), objectId = u("uObjectId");
        geometry_.draw(from.scene, from.camera, g.height, [&](const SceneGeometry::Item& item) {
            const glm::mat4 there = item.object == nullptr
                ? item.model
                : scene::modelMatrix(scene::objectAt(*item.object, from.scene.time, to.scene));
            glUniformMatrix4fv(model, 1, GL_FALSE, glm::value_ptr(item.model));
            glUniformMatrix4fv(otherModel, 1, GL_FALSE, glm::value_ptr(there));
            glUniform1ui(objectId, item.id);
        });
        glUseProgram(0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        gl::checkErrors("drawing flow fields");
    }

    BireprojSettings settings_;
    MethodInfo info_;
    SceneGeometry geometry_;
    gl::Program flowProgram_, program_;
    FullscreenPass pass_;
    std::unique_ptr<GBuffer> forward_, backward_;  // flows in their velocity attachments
    gl::Texture offsets_[2];
    std::optional<PairKey> flowsFor_;
    bool backwardFromSource_ = false;  // the next source's own flow target holds the backward flow
    Offsets latest_, initFrom_;
};

// The mean of several B-frames over the interval: each made by the image-based method into a
// scratch frame and added into a float accumulator, then resolved into the displayed frame.
class BireprojBlurMethod final : public UpconversionMethod {
public:
    BireprojBlurMethod(const DataPaths& paths, const std::string& name, const BireprojSettings& settings, int samples)
        : bframes_(paths, name, settings), samples_(samples) {
        if (samples < 1 || samples > 64) throw std::invalid_argument(name + ": samples must be 1..64");
        info_ = bframes_.info();  // usesSourceFlow included: it hands the sources on
        info_.name = name;
        info_.description = "motion blur: the mean of " + std::to_string(samples) +
            " bidirectionally reprojected B-frames spread over the 15 Hz interval";
        info_.reportsCorrespondence = false;
        info_.usesEarlierFrames = false;  // it makes the interval's frames itself, in order
        info_.exposureSamples = samples;
        accumulate_ = gl::buildProgram(
            {paths.shaderDir, {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "accumulate.frag"}}, {}});
        resolve_ =
            gl::buildProgram({paths.shaderDir,
                              {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "accumulate_resolve.frag"}},
                              {}});
    }

    const MethodInfo& info() const override { return info_; }
    void prepare(const UpconversionInput& input) override { bframes_.prepare(input); }

    void produce(const UpconversionInput& input, DisplayFrame& out) override {
        prepare(input);
        const int w = out.width(), h = out.height();
        if (!scratch_ || scratch_->width() != w || scratch_->height() != h) {
            scratch_ = std::make_unique<DisplayFrame>(w, h);
            middle_ = std::make_unique<DisplayFrame>(w, h);
            sum_ = makeFloatTexture(w, h);
            sumTarget_ = gl::Framebuffer::create();
            glBindFramebuffer(GL_FRAMEBUFFER, sumTarget_.id());
            glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, sum_.id(), 0);
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
        }
        const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        glBindFramebuffer(GL_FRAMEBUFFER, sumTarget_.id());
        glClearBufferfv(GL_COLOR, 0, zero);
        const double t0 = input.previous->depicts.scene.time, t1 = input.next->depicts.scene.time;
        const int middle = samples_ / 2;
        for (int k = 0; k < samples_; ++k) {
            UpconversionInput instant = input;
            instant.displayTime = t0 + (t1 - t0) * (k + 0.5) / samples_;
            DisplayFrame& frame = k == middle ? *middle_ : *scratch_;
            bframes_.produce(instant, frame);
            glBindFramebuffer(GL_FRAMEBUFFER, sumTarget_.id());
            glViewport(0, 0, w, h);
            glDisable(GL_DEPTH_TEST);
            glEnable(GL_BLEND);
            glBlendFunc(GL_ONE, GL_ONE);
            glUseProgram(accumulate_.id());
            bindTexture(accumulate_, "uColour", 0, frame.buffer().impl().colour);
            pass_.draw();
            glDisable(GL_BLEND);
        }
        auto& target = out.buffer().impl();
        glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer.id());
        glViewport(0, 0, w, h);
        glUseProgram(resolve_.id());
        bindTexture(resolve_, "uSum", 0, sum_);
        bindTexture(resolve_, "uMiddleIds", 1, middle_->buffer().impl().ids);
        glUniform1f(gl::uniform(resolve_, "uCount"), static_cast<float>(samples_));
        pass_.draw();
        endImagePass(2);
        gl::checkErrors("accumulating B-frames");
    }

private:
    BireprojMethod bframes_;
    int samples_;
    MethodInfo info_;
    gl::Program accumulate_, resolve_;
    FullscreenPass pass_;
    std::unique_ptr<DisplayFrame> scratch_, middle_;
    gl::Texture sum_;
    gl::Framebuffer sumTarget_;
};

}  // namespace

std::unique_ptr<UpconversionMethod> makeBireprojBlur(const DataPaths& paths, const std::string& name,
                                                     const BireprojSettings& settings, int samples) {
    return std::make_unique<BireprojBlurMethod>(paths, name, settings, samples);
}

std::unique_ptr<UpconversionMethod> makeBireproj(const DataPaths& paths, const std::string& name,
                                                 const BireprojSettings& settings) {
    return std::make_unique<BireprojMethod>(paths, name, settings);
}

}  // namespace warplab::renderer
