#include "upconvert/warp.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "gbuffer_gl.h"
#include "gl/check.h"
#include "gl/program.h"
#include "upconvert/fullscreen.h"
#include "scene/camera.h"

namespace warplab::renderer {
namespace {

constexpr GLuint kRestart = 0xFFFFFFFFu;

class WarpMethod final : public UpconversionMethod {
public:
    WarpMethod(const DataPaths& paths, const std::string& name, const WarpSettings& settings) : settings_(settings) {
        info_.name = name;
        info_.sourceRateHz = 15.0;
        info_.reportsCorrespondence = true;
        info_.takesGuardBand = true;
        info_.acceptsGuardBand = true;
        info_.description = settings.patchSize == 0
            ? std::string("warp extrapolation from the latest 15 Hz frame, full-density mesh") +
                (settings.disocclusionFix ? " with the disocclusion fix" : " without the disocclusion fix")
            : "warp extrapolation, " + std::to_string(settings.patchSize) + "x" + std::to_string(settings.patchSize) +
                " sparse mesh re-densified by tessellation";
        const std::vector<std::string> common{"warp_common.glsl"};
        std::vector<gl::ShaderStage> stages;
        if (settings.patchSize == 0) {
            stages.push_back({GL_VERTEX_SHADER, "warp_full.vert", common});
        } else {
            stages.push_back({GL_VERTEX_SHADER, "warp_sparse.vert"});
            stages.push_back({GL_TESS_CONTROL_SHADER, "warp_sparse.tesc"});
            stages.push_back({GL_TESS_EVALUATION_SHADER, "warp_sparse.tese", common});
            flagsProgram_ = gl::buildProgram(
                {paths.shaderDir,
                 {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "warp_patch_flags.frag", common}},
                 {}});
        }
        std::vector<std::string> defines;
        if (settings.disocclusionFix || settings.patchSize != 0) {
            // Sparse meshes always take the fix: the thesis' final renderer used both.
            stages.push_back({GL_GEOMETRY_SHADER, "warp_fix.geom"});
            defines.push_back("WARP_GEOMETRY_STAGE 1");
        }
        stages.push_back({GL_FRAGMENT_SHADER, "warp.frag"});
        program_ = gl::buildProgram({paths.shaderDir, stages, defines});
        fillProgram_ = gl::buildProgram({paths.shaderDir,
                                         {{GL_VERTEX_SHADER, "fullscreen.vert"},
                                          {GL_FRAGMENT_SHADER, "warp_border_fill.frag", {"warp_border.glsl"}}},
                                         {}});
        primitives_ = gl::Query::create();
    }

    const MethodInfo& info() const override { return info_; }

    void produce(const UpconversionInput& input, DisplayFrame& out) override {
        if (input.previous == nullptr) throw std::invalid_argument(info_.name + ": no source frame");
        const SourceFrame& source = *input.previous;
        const auto& src = source.gbuffer.impl();
        const int w = out.width(), h = out.height();
        checkSourceSize(source, out, info_);
        // A source with a guard band is larger, its camera widened to the same pixel pitch: the
        // mesh spans all its pixels (warpMatrices).
        const int sw = src.width, sh = src.height;
        const WarpMatrices m = warpMatrices(source, input, w, h);
        // The warp's uniforms for the mesh and for the patch flags alike, and the display's size
        // (the fix's sheet test and the flags measure in display pixels).
        const auto setMeshUniforms = [&](const gl::Program& program) {
            setWarpUniforms(program, source, input, m);
            glUniform2f(gl::uniform(program, "uTargetSize"), static_cast<float>(w), static_cast<float>(h));
        };

        if (settings_.patchSize != 0) classifyPatches(source, sw, sh, setMeshUniforms);

        auto& target = out.buffer().impl();
        glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer.id());
        glViewport(0, 0, w, h);
        const GLuint noId[4] = {0, 0, 0, 0};
        const GLfloat none[4] = {std::nanf(""), std::nanf(""), std::nanf(""), std::nanf("")};
        glClearBufferuiv(GL_COLOR, 1, noId);
        glClearBufferfv(GL_COLOR, 2, none);
        glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        fillBorder(source, input.camera, m.sourceViewProjection, m.targetInverse, w, h);

        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glUseProgram(program_.id());
        auto u = [&](const char* name) { return gl::uniform(program_, name); };
        setMeshUniforms(program_);
        bindTexture(program_, "uSourceColour", 2, src.colour);
        bindTexture(program_, "uSourceIds", 3, src.ids);
        glUniform1f(u("uGrazingCosine"), std::cos(glm::radians(settings_.sheetAngleDeg)));
        glUniform1f(u("uSheetDepthRatio"), settings_.sheetDepthRatio);

        glBeginQuery(GL_PRIMITIVES_GENERATED, primitives_.id());
        if (settings_.patchSize == 0) {
            const GLsizei count = fullMeshIndices(sw, sh);
            glEnable(GL_PRIMITIVE_RESTART);
            glPrimitiveRestartIndex(kRestart);
            glBindVertexArray(fullMesh_.vao.id());
            glDrawElements(GL_TRIANGLE_STRIP, count, GL_UNSIGNED_INT, nullptr);
            glDisable(GL_PRIMITIVE_RESTART);
        } else {
            glUniform1i(u("uPatchSize"), settings_.patchSize);
            glUniform2i(u("uPatchCount"), patchCountX_, patchCountY_);
            bindTexture(program_, "uPatchFlags", 4, flags_);
            glPatchParameteri(GL_PATCH_VERTICES, 4);
            glBindVertexArray(emptyVao_.id());
            // Mesa's llvmpipe (draw_tess.c, 22.3) numbers the tessellated vertices of the patches
            // of one run with 16 bits; past 65535 of them -- 227 fully subdivided 16 x 16 patches,
            // 809 of 8 x 8 -- they wrap and the run's triangles join the wrong vertices. So at
            // most that many patches per draw. The control stage finds each patch from its origin
            // (gl_VertexID counts on across draws), so the batches draw what one call would.
            const GLint perDraw = 65535 / ((settings_.patchSize + 1) * (settings_.patchSize + 1));
            const GLint patches = patchCountX_ * patchCountY_;
            for (GLint first = 0; first < patches; first += perDraw)
                glDrawArrays(GL_PATCHES, 4 * first, 4 * std::min(perDraw, patches - first));
        }
        glEndQuery(GL_PRIMITIVES_GENERATED);
        glBindVertexArray(0);
        glActiveTexture(GL_TEXTURE0);
        glUseProgram(0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        gl::checkErrors(("warping a frame (" + info_.name + ")").c_str());
    }

    // Triangles the last draw made (after tessellation), for the bench's counts.
    double lastTriangleCount() override {
        GLuint64 n = 0;
        glGetQueryObjectui64v(primitives_.id(), GL_QUERY_RESULT, &n);
        return static_cast<double>(n);
    }

private:
    // What no warped source pixel covers (content that was off-screen in the source) takes
    // the nearest source edge instead of black. A fill drawn first, writing no depth, rather
    // than a mesh ring stretched outwards: the mesh then overwrites it wherever it lands
    // whatever its depth, so no depth value is reserved for the fill and no exact far-plane
    // comparison is needed; and the sparse meshes' border patches keep their own geometry (a
    // far-flung ring vertex would drag an unsubdivided patch's interior with it). It covers
    // every pixel, so colour and id are never left at a clear value; its correspondence
    // stays NaN, so coverage by the mesh is still told apart.
    void fillBorder(const SourceFrame& source, const scene::CameraState& target, const glm::mat4& sourceViewProjection,
                    const glm::mat4& targetInverse, int w, int h) {
        const auto& src = source.gbuffer.impl();
        glDisable(GL_DEPTH_TEST);
        glDepthMask(GL_FALSE);
        glUseProgram(fillProgram_.id());
        auto u = [&](const char* name) { return gl::uniform(fillProgram_, name); };
        bindTexture(fillProgram_, "uSourceColour", 0, src.colour);
        bindTexture(fillProgram_, "uSourceIds", 1, src.ids);
        glUniformMatrix4fv(u("uTargetInverseViewProjection"), 1, GL_FALSE, glm::value_ptr(targetInverse));
        glUniformMatrix4fv(u("uSourceViewProjection"), 1, GL_FALSE, glm::value_ptr(sourceViewProjection));
        glUniform3fv(u("uTargetEye"), 1, glm::value_ptr(target.eye));
        glUniform2f(u("uSourceSize"), static_cast<float>(src.width), static_cast<float>(src.height));
        glUniform2f(u("uTargetSize"), static_cast<float>(w), static_cast<float>(h));
        fillPass_.draw();
        glDepthMask(GL_TRUE);
        gl::checkErrors(("filling the warp's border (" + info_.name + ")").c_str());
    }

    struct FullMesh {
        gl::VertexArray vao;
        gl::Buffer indices;
        int width = 0, height = 0;
        GLsizei count = 0;
    };

    // Row strips over the (w + 2) x (h + 2) vertex grid (the image plus an outer ring), one
    // restart between rows; built once per size.
    GLsizei fullMeshIndices(int w, int h) {
        if (fullMesh_.width == w && fullMesh_.height == h) return fullMesh_.count;
        const int columns = w + 2, rows = h + 2;
        std::vector<GLuint> indices;
        indices.reserve(static_cast<std::size_t>(rows - 1) * (2 * columns + 1));
        for (int y = 0; y + 1 < rows; ++y) {
            for (int x = 0; x < columns; ++x) {
                indices.push_back(static_cast<GLuint>((y + 1) * columns + x));
                indices.push_back(static_cast<GLuint>(y * columns + x));
            }
            indices.push_back(kRestart);
        }
        fullMesh_.vao = gl::VertexArray::create();
        fullMesh_.indices = gl::Buffer::create();
        glBindVertexArray(fullMesh_.vao.id());
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, fullMesh_.indices.id());
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size() * sizeof(GLuint)), indices.data(),
                     GL_STATIC_DRAW);
        glBindVertexArray(0);
        fullMesh_.width = w;
        fullMesh_.height = h;
        fullMesh_.count = static_cast<GLsizei>(indices.size());
        gl::checkErrors("building the full warp mesh");
        return fullMesh_.count;
    }

    // One texel per patch saying where the depth (or velocity) jumps and this warp moves the
    // patch's pixels apart; the tessellation control stage reads it for the patch and its four
    // neighbours. `setMeshUniforms` gives the pass the warp's own (warp_common.glsl).
    template <typename SetMeshUniforms>
    void classifyPatches(const SourceFrame& source, int w, int h, const SetMeshUniforms& setMeshUniforms) {
        const int n = settings_.patchSize;
        const int px = (w + 1 + n - 1) / n, py = (h + 1 + n - 1) / n;  // cover pixels -1 .. w
        if (px != patchCountX_ || py != patchCountY_) {
            patchCountX_ = px;
            patchCountY_ = py;
            flags_ = gl::Texture::create();
            glBindTexture(GL_TEXTURE_2D, flags_.id());
            glTexImage2D(GL_TEXTURE_2D, 0, GL_RG8, px, py, 0, GL_RG, GL_UNSIGNED_BYTE, nullptr);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            flagsFramebuffer_ = gl::Framebuffer::create();
            glBindFramebuffer(GL_FRAMEBUFFER, flagsFramebuffer_.id());
            glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, flags_.id(), 0);
            if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
                throw gl::GlError(info_.name + ": the patch-flag framebuffer is incomplete");
        }
        glBindFramebuffer(GL_FRAMEBUFFER, flagsFramebuffer_.id());
        glViewport(0, 0, px, py);
        glDisable(GL_DEPTH_TEST);
        glUseProgram(flagsProgram_.id());
        setMeshUniforms(flagsProgram_);
        glUniform1i(gl::uniform(flagsProgram_, "uPatchSize"), n);
        glUniform1f(gl::uniform(flagsProgram_, "uNear"), source.depicts.camera.nearPlane);
        glUniform1f(gl::uniform(flagsProgram_, "uFar"), source.depicts.camera.farPlane);
        glUniform1f(gl::uniform(flagsProgram_, "uDepthThreshold"), settings_.depthJump);
        glUniform1f(gl::uniform(flagsProgram_, "uVelocityThreshold"), settings_.velocityJump);
        flagsPass_.draw();
        gl::checkErrors("classifying warp patches");
    }

    MethodInfo info_;
    WarpSettings settings_;
    gl::Program program_;
    gl::Program flagsProgram_;
    gl::Program fillProgram_;
    FullscreenPass fillPass_;
    gl::Query primitives_;
    FullMesh fullMesh_;
    gl::VertexArray emptyVao_ = gl::VertexArray::create();
    FullscreenPass flagsPass_;
    gl::Texture flags_;
    gl::Framebuffer flagsFramebuffer_;
    int patchCountX_ = 0, patchCountY_ = 0;
};

}  // namespace

WarpMatrices warpMatrices(const SourceFrame& source, const UpconversionInput& input, int width, int height) {
    const auto& src = source.gbuffer.impl();
    const scene::CameraState& sourceCamera = source.depicts.camera;
    WarpMatrices m;
    m.sourceViewProjection =
        scene::projectionMatrix(sourceCamera, static_cast<float>(src.width) / static_cast<float>(src.height)) *
        scene::viewMatrix(sourceCamera);
    m.targetViewProjection =
        scene::projectionMatrix(input.camera, static_cast<float>(width) / static_cast<float>(height)) *
        scene::viewMatrix(input.camera);
    m.sourceInverse = glm::mat4(glm::inverse(glm::dmat4(m.sourceViewProjection)));
    m.targetInverse = glm::mat4(glm::inverse(glm::dmat4(m.targetViewProjection)));
    m.dt = static_cast<float>(input.displayTime - source.depicts.scene.time);
    return m;
}

void setWarpUniforms(const gl::Program& program, const SourceFrame& source, const UpconversionInput& input,
                     const WarpMatrices& m) {
    const auto& src = source.gbuffer.impl();
    const scene::CameraState& sourceCamera = source.depicts.camera;
    auto u = [&](const char* name) { return gl::uniform(program, name); };
    bindTexture(program, "uSourceDepth", 0, src.depth);
    bindTexture(program, "uSourceVelocity", 1, src.velocity);
    glUniformMatrix4fv(u("uSourceInverseViewProjection"), 1, GL_FALSE, glm::value_ptr(m.sourceInverse));
    glUniformMatrix4fv(u("uSourceViewProjection"), 1, GL_FALSE, glm::value_ptr(m.sourceViewProjection));
    glUniformMatrix4fv(u("uTargetViewProjection"), 1, GL_FALSE, glm::value_ptr(m.targetViewProjection));
    glUniform3fv(u("uSourceEye"), 1, glm::value_ptr(sourceCamera.eye));
    glUniform2f(u("uSize"), static_cast<float>(src.width), static_cast<float>(src.height));
    glUniform1f(u("uDt"), m.dt);
    glUniform1f(u("uSkyDistance"), 0.9f * std::min(sourceCamera.farPlane, input.camera.farPlane));
}

std::unique_ptr<UpconversionMethod> makeWarp(const DataPaths& paths, const std::string& name,
                                             const WarpSettings& settings) {
    return std::make_unique<WarpMethod>(paths, name, settings);
}

}  // namespace warplab::renderer
