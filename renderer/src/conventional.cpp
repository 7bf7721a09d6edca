#include "renderer/conventional.h"

#include <stdexcept>

#include <algorithm>
#include <cstddef>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gbuffer_gl.h"
#include "gl/check.h"
#include "gl/program.h"
#include "renderer/mesh.h"
#include "scene_geometry.h"
#include "upconvert/fullscreen.h"
#include "scene/camera.h"
#include "scene/hangar_layout.h"
#include "scene/limits.h"
#include "scene/motion.h"

namespace warplab::renderer {

// ---------------------------------------------------------------------------- GBuffer

gl::Texture makeTexture(GLint internalFormat, GLenum format, GLenum type, int width, int height) {
    gl::Texture texture = gl::Texture::create();
    glBindTexture(GL_TEXTURE_2D, texture.id());
    glTexImage2D(GL_TEXTURE_2D, 0, internalFormat, width, height, 0, format, type, nullptr);
    // Later passes fetch texels exactly (texelFetch) or sample colour bilinearly; never mipmaps.
    const GLint filter = (format == GL_RGBA_INTEGER || format == GL_RED_INTEGER) ? GL_NEAREST : GL_LINEAR;
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

GBuffer::GBuffer(int width, int height) : impl_(std::make_unique<Impl>()) {
    if (glGenTextures == nullptr) throw std::logic_error("GBuffer: no OpenGL context has been created yet");
    if (width < 1 || height < 1 || width > scene::kMaxImageSize || height > scene::kMaxImageSize)
        throw std::invalid_argument("GBuffer: size " + std::to_string(width) + "x" + std::to_string(height) +
                                    " is outside 1.." + std::to_string(scene::kMaxImageSize));
    impl_->width = width;
    impl_->height = height;
    impl_->colour = makeTexture(GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, width, height);
    impl_->depth = makeTexture(GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT, width, height);
    impl_->ids = makeTexture(GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, width, height);
    impl_->velocity = makeTexture(GL_RGBA32F, GL_RGBA, GL_FLOAT, width, height);
    impl_->framebuffer = gl::Framebuffer::create();
    glBindFramebuffer(GL_FRAMEBUFFER, impl_->framebuffer.id());
    glFramebufferTexture2D(GL_FRAMEBUFFER, Impl::kColourAttachment, GL_TEXTURE_2D, impl_->colour.id(), 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, Impl::kIdAttachment, GL_TEXTURE_2D, impl_->ids.id(), 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, Impl::kVelocityAttachment, GL_TEXTURE_2D, impl_->velocity.id(), 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, impl_->depth.id(), 0);
    const GLenum buffers[] = {Impl::kColourAttachment, Impl::kIdAttachment, Impl::kVelocityAttachment};
    glDrawBuffers(3, buffers);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    gl::checkErrors("creating the G-buffer");
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw gl::GlError("GBuffer: the driver rejects the colour/id/velocity/depth framebuffer (status 0x" +
                          std::to_string(status) + ")");
}

GBuffer::~GBuffer() = default;
GBuffer::GBuffer(GBuffer&&) noexcept = default;
GBuffer& GBuffer::operator=(GBuffer&&) noexcept = default;
int GBuffer::width() const { return impl_->width; }
int GBuffer::height() const { return impl_->height; }

namespace {

// Reads one attachment (GL_NONE for depth) into `pixels`; the caller flips the rows, since GL
// rows are bottom-up and every image outside the renderer is top-down.
void readAttachment(const GBuffer::Impl& g, GLenum attachment, GLenum format, GLenum type, void* pixels,
                    const char* what) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, g.framebuffer.id());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    if (attachment != GL_NONE) glReadBuffer(attachment);
    glReadPixels(0, 0, g.width, g.height, format, type, pixels);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    gl::checkErrors(what);
}

}  // namespace

image::ImageRGBA8 readColourAttachment(const GBuffer::Impl& g) {
    image::ImageRGBA8 image = image::ImageRGBA8::make(g.width, g.height);
    readAttachment(g, GBuffer::Impl::kColourAttachment, GL_RGBA, GL_UNSIGNED_BYTE, image.pixels.data(),
                   "reading back a colour attachment");
    image::flipVertically(image);
    return image;
}

image::ImageU32 readIdAttachment(const GBuffer::Impl& g) {
    image::ImageU32 image = image::ImageU32::make(g.width, g.height);
    readAttachment(g, GBuffer::Impl::kIdAttachment, GL_RED_INTEGER, GL_UNSIGNED_INT, image.data.data(),
                   "reading back an id attachment");
    image::flipVertically(image);
    return image;
}

image::ImageF readVectorAttachment(const GBuffer::Impl& g, int channels) {
    image::ImageF image = image::ImageF::make(g.width, g.height, channels);
    readAttachment(g, GBuffer::Impl::kVelocityAttachment, channels == 4 ? GL_RGBA : GL_RGB, GL_FLOAT, image.data.data(),
                   "reading back a vector attachment");
    image::flipVertically(image);
    return image;
}

image::ImageF readDepthAttachment(const GBuffer::Impl& g) {
    image::ImageF image = image::ImageF::make(g.width, g.height, 1);
    readAttachment(g, GL_NONE, GL_DEPTH_COMPONENT, GL_FLOAT, image.data.data(), "reading back a depth attachment");
    image::flipVertically(image);
    return image;
}

GBufferImages readBack(const GBuffer& gbuffer) {
    const auto& g = gbuffer.impl();
    return {readColourAttachment(g), readDepthAttachment(g), readIdAttachment(g), readVectorAttachment(g, 3)};
}

void blitToDefaultFramebuffer(const GBuffer& gbuffer, int drawableWidth, int drawableHeight) {
    const auto& g = gbuffer.impl();
    glBindFramebuffer(GL_READ_FRAMEBUFFER, g.framebuffer.id());
    glReadBuffer(GBuffer::Impl::kColourAttachment);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glDrawBuffer(GL_BACK);
    const GLenum filter = (drawableWidth == g.width && drawableHeight == g.height) ? GL_NEAREST : GL_LINEAR;
    glBlitFramebuffer(0, 0, g.width, g.height, 0, 0, drawableWidth, drawableHeight, GL_COLOR_BUFFER_BIT, filter);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    gl::checkErrors("copying the frame to the window");
}

image::ImageRGBA8 readDefaultFramebuffer(int width, int height) {
    image::ImageRGBA8 image;
    image.width = width;
    image.height = height;
    image.pixels.resize(4 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, image.pixels.data());
    gl::checkErrors("reading the window's framebuffer");
    image::flipVertically(image);
    return image;
}

// ----------------------------------------------------------------- ConventionalRenderer

namespace {

// Ceiling lamps between the ribs, plus one near the far door; positions shared with the
// shader through uniforms. Few enough that llvmpipe stays fast at full HD.
struct Lamp {
    glm::vec3 position;
    glm::vec3 colour;
};

std::vector<Lamp> hangarLamps() {
    using L = scene::HangarLayout;
    std::vector<Lamp> lamps;
    for (int i = 0; i < L::kRibCount; ++i) {
        const float z = L::kFirstRibZ + L::kRibSpacing * 0.5f - L::kRibSpacing * static_cast<float>(i);
        lamps.push_back({{0.0f, L::kClearMaxY - 0.3f, z}, {0.9f, 0.92f, 1.0f}});
    }
    lamps.push_back({{0.0f, L::kClearMaxY - 0.3f, L::kBackZ - 1.0f}, {0.9f, 0.92f, 1.0f}});
    return lamps;
}

constexpr int kMaxLamps = 16;  // matches MAX_LAMPS in conventional.frag

const ShadingOptions& checked(const ShadingOptions& shading) {
    if (shading.supersampling < 1 || shading.supersampling > scene::kMaxSupersampling)
        throw std::invalid_argument("ConventionalRenderer: supersampling " + std::to_string(shading.supersampling) +
                                    " is outside 1.." + std::to_string(scene::kMaxSupersampling) +
                                    " (samples per pixel side; 1 = off)");
    const glm::ivec2 step = shading.latticeStep, phase = shading.latticePhase;
    if (step.x < 1 || step.y < 1 || phase.x < 0 || phase.y < 0 || phase.x >= step.x || phase.y >= step.y)
        throw std::invalid_argument("ConventionalRenderer: lattice phase (" + std::to_string(phase.x) + ", " +
                                    std::to_string(phase.y) + ") does not lie in a step of (" + std::to_string(step.x) +
                                    ", " + std::to_string(step.y) + ")");
    if (shading.supersampling > 1 && (step != glm::ivec2(1) || shading.sampleMask != 0))
        throw std::invalid_argument("ConventionalRenderer: a lattice or a sample mask is shaded without supersampling");
    return shading;
}

// Supersampling's N x N samples per pixel: colour and depth only, since ids, velocity and flow
// come from the 1x pass; a whole G-buffer at 4x4 of full HD would be about 1 GB.
struct SampleBuffer {
    int width = 0, height = 0;
    gl::Texture colour;  // GL_RGBA8, read by texelFetch in ssaa_resolve.frag
    // GL_DEPTH_COMPONENT32F like the G-buffer's, so surfaces that nearly touch hide each other
    // as they would in a direct render at this size.
    gl::Renderbuffer depth;
    gl::Framebuffer framebuffer;
};

SampleBuffer makeSampleBuffer(int width, int height, int factor) {
    GLint maxTexture = 0, maxRenderbuffer = 0, maxViewport[2] = {0, 0};
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxRenderbuffer);
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, maxViewport);
    const int limit = std::min({maxTexture, maxRenderbuffer, maxViewport[0], maxViewport[1]});
    if (width > limit || height > limit)
        throw std::invalid_argument("ConventionalRenderer: supersampling " + std::to_string(factor) + " needs a " +
                                    std::to_string(width) + "x" + std::to_string(height) +
                                    " sample buffer, over this driver's limit of " + std::to_string(limit));
    SampleBuffer b;
    b.width = width;
    b.height = height;
    b.colour = makeTexture(GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, width, height);
    glBindTexture(GL_TEXTURE_2D, 0);
    b.depth = gl::Renderbuffer::create();
    glBindRenderbuffer(GL_RENDERBUFFER, b.depth.id());
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, width, height);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    b.framebuffer = gl::Framebuffer::create();
    glBindFramebuffer(GL_FRAMEBUFFER, b.framebuffer.id());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, b.colour.id(), 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, b.depth.id());
    // conventional.frag's id, velocity and flow outputs (locations 1..3) go nowhere.
    const GLenum colourOnly[] = {GL_COLOR_ATTACHMENT0};
    glDrawBuffers(1, colourOnly);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    gl::checkErrors("creating the supersampling buffer");
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw gl::GlError(
            "ConventionalRenderer: the driver rejects the supersampling colour/depth framebuffer "
            "(status 0x" +
            std::to_string(status) + ")");
    return b;
}

}  // namespace

// Space beyond the far door: a dark blue-black, no id, no motion, depth at the far plane.
constexpr GLfloat kSky[4] = {0.02f, 0.025f, 0.05f, 1.0f};

struct ConventionalRenderer::Impl {
    ShadingOptions shading;
    gl::Program program;
    SceneGeometry geometry;
    std::vector<Lamp> lamps;
    gl::Program resolve;  // ssaa_resolve.frag
    FullscreenPass fullscreen;
    SampleBuffer samples;  // kept while the target size and supersampling stay the same
    Impl(const DataPaths& paths, const ShadingOptions& options) : shading(options), geometry(paths) {}
    void render(const scene::FrameDescription& frame, GBuffer& target, const scene::FrameDescription* flowTo);
    void resolveSamples(GBuffer::Impl& g);

    // The camera at this instant and at the flow's other one, over the target's lattice.
    struct Matrices {
        glm::mat4 view{1.0f}, viewProjection{1.0f}, otherView{1.0f}, otherViewProjection{1.0f};
    };
    // render's steps, in the order it takes them.
    void beginFrame(GBuffer::Impl& g);
    Matrices matrices(const scene::FrameDescription& frame, const scene::FrameDescription& other,
                      const GBuffer::Impl& g) const;
    void setCameraUniforms(const scene::FrameDescription& frame, const Matrices& mats, const GBuffer::Impl& g);
    void setShadingUniforms(const scene::FrameDescription& frame, const Matrices& mats);
    void drawScene(const scene::FrameDescription& frame, const scene::FrameDescription* flowTo, GLint otherModel,
                   int passHeight);
    struct Uniforms {
        GLint model, normalMatrix, viewProjection, objectId, linearVelocity, angularVelocity, centre, eye, tint,
            panelPattern, lampCount, lampPosition, lampColour, shadingCost, geometryOnly, masked, sampleMask;
    } u{};
};

ConventionalRenderer::ConventionalRenderer(const DataPaths& paths, ShadingOptions shading)
    : impl_(std::make_unique<Impl>(paths, checked(shading))) {
    auto& m = *impl_;
    m.program = gl::buildProgram(
        {paths.shaderDir,
         {{GL_VERTEX_SHADER, "conventional.vert"}, {GL_FRAGMENT_SHADER, "conventional.frag", {"flow_common.glsl"}}},
         {"MAX_LAMPS " + std::to_string(kMaxLamps),
          "SKY_COLOUR vec3(" + std::to_string(kSky[0]) + ", " + std::to_string(kSky[1]) + ", " +
              std::to_string(kSky[2]) + ")"}});
    const auto& p = m.program;
    m.u = {gl::uniform(p, "uModel"),          gl::uniform(p, "uNormalMatrix"),
           gl::uniform(p, "uViewProjection"), gl::uniform(p, "uObjectId"),
           gl::uniform(p, "uLinearVelocity"), gl::uniform(p, "uAngularVelocity"),
           gl::uniform(p, "uCentre"),         gl::uniform(p, "uEye"),
           gl::uniform(p, "uTint"),           gl::uniform(p, "uPanelPattern"),
           gl::uniform(p, "uLampCount"),      gl::uniform(p, "uLampPosition"),
           gl::uniform(p, "uLampColour"),     gl::uniform(p, "uShadingCost"),
           gl::uniform(p, "uGeometryOnly"),   gl::uniform(p, "uMasked"),
           gl::uniform(p, "uSampleMask")};
    m.lamps = hangarLamps();
    m.resolve = gl::buildProgram(
        {paths.shaderDir, {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "ssaa_resolve.frag"}}, {}});
}

ConventionalRenderer::~ConventionalRenderer() = default;

void ConventionalRenderer::setShading(const ShadingOptions& shading) {
    impl_->shading = checked(shading);
    if (shading.supersampling == 1) impl_->samples = {};  // up to 16x the frame's size: give it back
}

void ConventionalRenderer::render(const scene::FrameDescription& frame, GBuffer& target) {
    impl_->render(frame, target, nullptr);
}

void ConventionalRenderer::render(const scene::FrameDescription& frame, GBuffer& target,
                                  const scene::FrameDescription& flowTo) {
    impl_->render(frame, target, &flowTo);
}

namespace {

// The G-buffer's fourth target, scene flow, made the first time a render asks for it; the
// target's framebuffer must be bound.
void attachFlowTarget(GBuffer::Impl& g) {
    if (g.flow.id() != 0) return;
    g.flow = gl::Texture::create();
    glBindTexture(GL_TEXTURE_2D, g.flow.id());
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, g.width, g.height, 0, GL_RGBA, GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GBuffer::Impl::kFlowAttachment, GL_TEXTURE_2D, g.flow.id(), 0);
}

}  // namespace

void ConventionalRenderer::Impl::render(const scene::FrameDescription& frame, GBuffer& target,
                                        const scene::FrameDescription* flowTo) {
    auto& m = *this;
    auto& g = target.impl();
    const int n = m.shading.supersampling;
    beginFrame(g);
    // Without a flow target the "other" instant is this one: the flow output, not stored, is 0.
    const scene::FrameDescription& other = flowTo != nullptr ? *flowTo : frame;
    const Matrices mats = matrices(frame, other, g);
    setCameraUniforms(frame, mats, g);
    const GLint otherModel = gl::uniform(m.program, "uOtherModel");
    setShadingUniforms(frame, mats);

    if (flowTo != nullptr) {
        // The flow goes into a fourth target; the sky's flow first, under everything, as a
        // far-plane triangle that leaves depth alone.
        attachFlowTarget(g);
        const GLenum four[] = {GBuffer::Impl::kColourAttachment, GBuffer::Impl::kIdAttachment,
                               GBuffer::Impl::kVelocityAttachment, GBuffer::Impl::kFlowAttachment};
        glDrawBuffers(4, four);
        m.geometry.drawSky(m.program);
    }
    drawScene(frame, flowTo, otherModel, g.height * m.shading.latticeStep.y);
    if (flowTo != nullptr) {
        const GLenum three[] = {GBuffer::Impl::kColourAttachment, GBuffer::Impl::kIdAttachment,
                                GBuffer::Impl::kVelocityAttachment};
        glDrawBuffers(3, three);
        g.flowTo = GBuffer::Impl::FlowTarget{flowTo->scene.time, flowTo->camera.yaw, flowTo->camera.pitch};
    } else {
        g.flowTo.reset();  // whatever flow the target held belongs to its previous frame
    }

    // Supersampling: the pass above made depth, ids, velocity and flow at the pixel centres,
    // which scoring and the warp need exactly; now the same scene with the same uniforms at N x N
    // times the size, into a colour-and-depth buffer only, whose N x N blocks are then averaged
    // into the target's colour. The camera and aspect are unchanged, so sample (N x + i, N y + j)
    // lies at the centre of sub-pixel (i, j) of pixel (x, y).
    if (n > 1) {
        glBindFramebuffer(GL_FRAMEBUFFER, m.samples.framebuffer.id());
        glViewport(0, 0, m.samples.width, m.samples.height);
        glClearBufferfv(GL_COLOR, 0, kSky);
        glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
        drawScene(frame, flowTo, otherModel, m.samples.height);
        resolveSamples(g);
    }
    if (m.shading.sampleMask != 0) {
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, 0);
    }
    glBindVertexArray(0);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    gl::checkErrors("rendering a conventional frame");
}

// The supersampling buffer when the size changed, the target bound and cleared to the sky.
void ConventionalRenderer::Impl::beginFrame(GBuffer::Impl& g) {
    auto& m = *this;
    // Made before anything is drawn, so a size the driver refuses throws with the state untouched.
    const int n = m.shading.supersampling;
    if (n > 1 && (m.samples.width != n * g.width || m.samples.height != n * g.height))
        m.samples = makeSampleBuffer(n * g.width, n * g.height, n);
    glBindFramebuffer(GL_FRAMEBUFFER, g.framebuffer.id());
    glViewport(0, 0, g.width, g.height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);

    const GLuint noId[4] = {scene::kIdNone, 0, 0, 0};
    const GLfloat still[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearBufferfv(GL_COLOR, 0, kSky);
    glClearBufferuiv(GL_COLOR, 1, noId);
    glClearBufferfv(GL_COLOR, 2, still);
    glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
}

ConventionalRenderer::Impl::Matrices ConventionalRenderer::Impl::matrices(const scene::FrameDescription& frame,
                                                                          const scene::FrameDescription& other,
                                                                          const GBuffer::Impl& g) const {
    // The frame the target shades a lattice of (the target itself without one). A frame pixel
    // centre at NDC 2 (s X + p + 0.5) / W - 1 must land on the target's pixel centre
    // 2 s (X + 0.5) / W - 1: a shift by (s - 1 - 2 p) / W, the same for every pixel.
    const glm::ivec2 step = shading.latticeStep, phase = shading.latticePhase;
    const glm::vec2 frameSize(static_cast<float>(g.width * step.x), static_cast<float>(g.height * step.y));
    const float aspect = frameSize.x / frameSize.y;
    const glm::vec3 latticeShift(static_cast<float>(step.x - 1 - 2 * phase.x) / frameSize.x,
                                 static_cast<float>(step.y - 1 - 2 * phase.y) / frameSize.y, 0.0f);
    const glm::mat4 shift = glm::translate(glm::mat4(1.0f), latticeShift);
    Matrices mats;
    mats.view = scene::viewMatrix(frame.camera);
    mats.viewProjection = shift * scene::projectionMatrix(frame.camera, aspect) * mats.view;
    mats.otherView = scene::viewMatrix(other.camera);
    mats.otherViewProjection = shift * scene::projectionMatrix(other.camera, aspect) * mats.otherView;
    return mats;
}

// The program in use, with the camera of this instant and the flow's other one.
void ConventionalRenderer::Impl::setCameraUniforms(const scene::FrameDescription& frame, const Matrices& mats,
                                                   const GBuffer::Impl& g) {
    auto& m = *this;
    glUseProgram(m.program.id());
    auto u = [&](const char* name) { return gl::uniform(m.program, name); };
    glUniformMatrix4fv(u("uView"), 1, GL_FALSE, glm::value_ptr(mats.view));
    glUniformMatrix4fv(u("uOtherView"), 1, GL_FALSE, glm::value_ptr(mats.otherView));
    glUniformMatrix4fv(u("uOtherViewProjection"), 1, GL_FALSE, glm::value_ptr(mats.otherViewProjection));
    glUniformMatrix4fv(u("uFlowOtherViewProjection"), 1, GL_FALSE, glm::value_ptr(mats.otherViewProjection));
    const glm::mat4 inverse = glm::mat4(glm::inverse(glm::dmat4(mats.viewProjection)));
    glUniformMatrix4fv(u("uFlowInverseViewProjection"), 1, GL_FALSE, glm::value_ptr(inverse));
    glUniform2f(u("uFlowSize"), static_cast<float>(g.width), static_cast<float>(g.height));
    glUniform1f(u("uFlowFar"), frame.camera.farPlane);
    glUniform1i(u("uSky"), 0);
}

// The projection, the eye, the lamps and the shading options.
void ConventionalRenderer::Impl::setShadingUniforms(const scene::FrameDescription& frame, const Matrices& mats) {
    auto& m = *this;
    glUniformMatrix4fv(m.u.viewProjection, 1, GL_FALSE, glm::value_ptr(mats.viewProjection));
    glUniform3fv(m.u.eye, 1, glm::value_ptr(frame.camera.eye));
    const int lampCount = std::min<int>(static_cast<int>(m.lamps.size()), kMaxLamps);
    glUniform1i(m.u.lampCount, lampCount);
    glUniform1i(m.u.shadingCost, m.shading.shadingCost);
    glUniform1i(m.u.geometryOnly, m.shading.geometryOnly ? 1 : 0);
    glUniform1i(m.u.masked, m.shading.sampleMask != 0 ? 1 : 0);
    if (m.shading.sampleMask != 0) {
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, m.shading.sampleMask);
        glUniform1i(m.u.sampleMask, 0);
    }
    std::vector<glm::vec3> positions, colours;
    for (int i = 0; i < lampCount; ++i) {
        positions.push_back(m.lamps[static_cast<std::size_t>(i)].position);
        colours.push_back(m.lamps[static_cast<std::size_t>(i)].colour);
    }
    glUniform3fv(m.u.lampPosition, lampCount, glm::value_ptr(positions.front()));
    glUniform3fv(m.u.lampColour, lampCount, glm::value_ptr(colours.front()));
}

// Each pass draws its spheres as finely as its own pixels need: the 1x pass as any render
// of this size does (so a flow pass of the same frame draws the same triangles), the
// samples as a render N times the size.
void ConventionalRenderer::Impl::drawScene(const scene::FrameDescription& frame, const scene::FrameDescription* flowTo,
                                           GLint otherModel, int passHeight) {
    auto& m = *this;
    m.geometry.draw(frame.scene, frame.camera, passHeight, [&](const SceneGeometry::Item& item) {
        const scene::ObjectState* o = item.object;
        const glm::mat4 there = o == nullptr || flowTo == nullptr
            ? item.model
            : scene::modelMatrix(scene::objectAt(*o, frame.scene.time, flowTo->scene));
        glUniformMatrix4fv(otherModel, 1, GL_FALSE, glm::value_ptr(there));
        const glm::vec3 zero(0.0f);
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(item.model)));
        glUniformMatrix4fv(m.u.model, 1, GL_FALSE, glm::value_ptr(item.model));
        glUniformMatrix3fv(m.u.normalMatrix, 1, GL_FALSE, glm::value_ptr(normalMatrix));
        glUniform1ui(m.u.objectId, item.id);
        glUniform3fv(m.u.centre, 1, glm::value_ptr(o ? o->position : zero));
        glUniform3fv(m.u.linearVelocity, 1, glm::value_ptr(o ? o->velocity : zero));
        glUniform3fv(m.u.angularVelocity, 1, glm::value_ptr(o ? o->angularVelocity : zero));
        glUniform3fv(m.u.tint, 1, glm::value_ptr(o ? o->colour : glm::vec3(1.0f)));
        glUniform1i(m.u.panelPattern, o == nullptr && m.shading.panelPattern ? 1 : 0);
    });
}

// Writes the mean of each N x N block of samples into the target's colour attachment only.
void ConventionalRenderer::Impl::resolveSamples(GBuffer::Impl& g) {
    glBindFramebuffer(GL_FRAMEBUFFER, g.framebuffer.id());
    const GLenum colourOnly[] = {GBuffer::Impl::kColourAttachment};
    glDrawBuffers(1, colourOnly);
    glViewport(0, 0, g.width, g.height);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glUseProgram(resolve.id());
    bindTexture(resolve, "uSamples", 0, samples.colour);
    glUniform1i(gl::uniform(resolve, "uFactor"), shading.supersampling);
    fullscreen.draw();
    glBindTexture(GL_TEXTURE_2D, 0);
    // Back to what every other pass assumes of a G-buffer and of the context.
    const GLenum three[] = {GBuffer::Impl::kColourAttachment, GBuffer::Impl::kIdAttachment,
                            GBuffer::Impl::kVelocityAttachment};
    glDrawBuffers(3, three);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
}

}  // namespace warplab::renderer
