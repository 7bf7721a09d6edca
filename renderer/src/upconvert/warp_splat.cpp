// Warp extrapolation by forward splatting ("warp-splat"): the warp equations of the mesh warps
// (seed 004 eq. 6-11, warp_common.glsl) per source pixel, the footprint of each warped source
// pixel splatted into the display with atomics instead of rasterised as a mesh, then one
// full-screen resolve. Passes, over shader storage buffers (warp_splat_common.glsl):
//  1a. warp_splat_vertices.comp: every grid vertex (source pixel, guard band and an outer ring)
//      warped to the displayed instant;
//  1b. warp_splat.comp: each cell's two triangles cover the display pixel centres inside them
//      with an imageAtomicMin of their depth;
//  1c. the same program again: where its depth is the kept one, the triangle's index, also a
//      minimum, so the result does not depend on the order invocations run in;
//  2.  warp_splat_resolve.frag: colour, id and correspondence from the winning triangle, true
//      holes from the background (the disocclusion fix's rule), the border as the mesh warps
//      fill it.
// No geometry or tessellation stage, which llvmpipe runs on the CPU one primitive at a time.
#include "upconvert/warp_splat.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "gbuffer_gl.h"
#include "gl/check.h"
#include "gl/program.h"
#include "upconvert/fullscreen.h"
#include "upconvert/stage_clock.h"
#include "upconvert/warp.h"
#include "scene/camera.h"

namespace warplab::renderer {
namespace {

constexpr GLuint kNoWinner = 0xFFFFFFFFu;
constexpr GLuint kGroupSize = 16;  // local_size_x and _y of both compute shaders

GLuint groups(int n) { return (static_cast<GLuint>(n) + kGroupSize - 1) / kGroupSize; }

gl::Buffer makeStorage(std::size_t bytes) {
    gl::Buffer buffer = gl::Buffer::create();
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer.id());
    glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(bytes), nullptr, GL_DYNAMIC_COPY);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    return buffer;
}

class WarpSplatMethod final : public UpconversionMethod {
public:
    WarpSplatMethod(const DataPaths& paths, const std::string& name, const WarpSplatSettings& settings)
        : settings_(settings) {
        std::string why;
        if (!gl::hasCompute(&why)) throw std::runtime_error(name + " needs OpenGL 4.3 compute shaders; " + why);
        info_.name = name;
        info_.sourceRateHz = 15.0;
        info_.reportsCorrespondence = true;
        info_.takesGuardBand = true;
        info_.acceptsGuardBand = true;
        info_.description =
            "warp extrapolation from the latest 15 Hz frame by forward splatting in compute (atomic depth test, "
            "no mesh), holes filled from the background";
        vertexProgram_ = gl::buildProgram(
            {paths.shaderDir,
             {{GL_COMPUTE_SHADER, "warp_splat_vertices.comp", {"warp_common.glsl", "warp_splat_common.glsl"}}},
             {}});
        splatProgram_ =
            gl::buildProgram({paths.shaderDir,
                              {{GL_COMPUTE_SHADER, "warp_splat.comp", {"warp_common.glsl", "warp_splat_common.glsl"}}},
                              {}});
        resolveProgram_ = gl::buildProgram(
            {paths.shaderDir,
             {{GL_VERTEX_SHADER, "fullscreen.vert"},
              {GL_FRAGMENT_SHADER, "warp_splat_resolve.frag", {"warp_splat_common.glsl", "warp_border.glsl"}}},
             {}});
    }

    const MethodInfo& info() const override { return info_; }
    void timeStages(bool on) override { clock_.enable(on); }
    std::vector<StageTime> lastStageTimes() const override { return clock_.times(); }

    void produce(const UpconversionInput& input, DisplayFrame& out) override {
        if (input.previous == nullptr) throw std::invalid_argument(info_.name + ": no source frame");
        const SourceFrame& source = *input.previous;
        checkSourceSize(source, out, info_);
        const auto& src = source.gbuffer.impl();
        const int w = out.width(), h = out.height();
        const int sw = src.width, sh = src.height;
        allocate(sw, sh, w, h);
        const WarpMatrices m = warpMatrices(source, input, w, h);  // as the mesh warps make them
        const WarpSettings fix;  // the disocclusion fix's sheet rule, shared with the mesh warps

        clock_.start();
        // Every display pixel starts with no surface and no winner.
        const GLuint none = kNoWinner;
        for (const gl::Buffer* b : {&depths_, &winners_}) {
            glBindBuffer(GL_SHADER_STORAGE_BUFFER, b->id());
            glClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &none);
        }
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, vertices_.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, depths_.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, winners_.id());
        // The warp's uniforms (the vertex pass warps every grid vertex with them, the splat
        // unprojects the corners of a triangle that may be a sheet) and the grid's size.
        const auto setGridUniforms = [&](const gl::Program& program) {
            setWarpUniforms(program, source, input, m);
            glUniform2i(gl::uniform(program, "uCells"), sw + 1, sh + 1);
        };

        // 1a: the warped grid.
        glUseProgram(vertexProgram_.id());
        setGridUniforms(vertexProgram_);
        glUniform2f(gl::uniform(vertexProgram_, "uTargetSize"), static_cast<float>(w), static_cast<float>(h));
        glDispatchCompute(groups(sw + 2), groups(sh + 2), 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

        // 1b and 1c: nearest depth, then the winner at that depth.
        glUseProgram(splatProgram_.id());
        setGridUniforms(splatProgram_);
        {
            auto u = [&](const char* n) { return gl::uniform(splatProgram_, n); };
            glUniform2i(u("uTargetPixels"), w, h);
            glUniform1f(u("uGrazingCosine"), std::cos(glm::radians(fix.sheetAngleDeg)));
            glUniform1f(u("uSheetDepthRatio"), fix.sheetDepthRatio);
            glUniform1i(u("uMaxSpan"), settings_.maxSpanPx);
        }
        const GLint winnerPass = gl::uniform(splatProgram_, "uWinnerPass");
        for (const GLint pass : {0, 1}) {
            glUniform1i(winnerPass, pass);
            glDispatchCompute(groups(sw + 1), groups(sh + 1), 1);
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        }
        clock_.done("splat");

        // 2: the resolve, into the display frame's attachments (depth through gl_FragDepth).
        auto& target = out.buffer().impl();
        glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer.id());
        glViewport(0, 0, w, h);
        glDisable(GL_BLEND);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_ALWAYS);
        glDepthMask(GL_TRUE);
        glUseProgram(resolveProgram_.id());
        {
            auto u = [&](const char* n) { return gl::uniform(resolveProgram_, n); };
            bindTexture(resolveProgram_, "uSourceColour", 0, src.colour);
            bindTexture(resolveProgram_, "uSourceIds", 1, src.ids);
            glUniform2i(u("uCells"), sw + 1, sh + 1);
            glUniform1i(u("uHoleReach"),
                        std::max(1, static_cast<int>(std::lround(settings_.holeReach * static_cast<float>(h)))));
            glUniform1f(u("uSheetDepthRatio"), fix.sheetDepthRatio);
            glUniform1f(u("uNear"), input.camera.nearPlane);
            glUniform1f(u("uFar"), input.camera.farPlane);
            glUniformMatrix4fv(u("uTargetInverseViewProjection"), 1, GL_FALSE, glm::value_ptr(m.targetInverse));
            glUniformMatrix4fv(u("uSourceViewProjection"), 1, GL_FALSE, glm::value_ptr(m.sourceViewProjection));
            glUniform3fv(u("uTargetEye"), 1, glm::value_ptr(input.camera.eye));
            glUniform2f(u("uSourceSize"), static_cast<float>(sw), static_cast<float>(sh));
            glUniform2f(u("uTargetSize"), static_cast<float>(w), static_cast<float>(h));
        }
        pass_.draw();
        glDepthFunc(GL_LESS);
        for (GLuint binding = 0; binding < 3; ++binding) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, 0);
        endImagePass(2);
        clock_.done("resolve");
        gl::checkErrors(("splatting a frame (" + info_.name + ")").c_str());
    }

private:
    // The grid's buffer for a source of sw x sh, the per-pixel ones for a display of w x h; made
    // again only when a size changes.
    void allocate(int sw, int sh, int w, int h) {
        if (sw != sourceWidth_ || sh != sourceHeight_) {
            vertices_ =
                makeStorage(sizeof(float) * 4 * static_cast<std::size_t>(sw + 2) * static_cast<std::size_t>(sh + 2));
            sourceWidth_ = sw;
            sourceHeight_ = sh;
        }
        if (w != width_ || h != height_) {
            depths_ = makeStorage(sizeof(GLuint) * static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
            winners_ = makeStorage(sizeof(GLuint) * static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
            width_ = w;
            height_ = h;
        }
        gl::checkErrors(("allocating the splat's buffers (" + info_.name + ")").c_str());
    }

    MethodInfo info_;
    WarpSplatSettings settings_;
    gl::Program vertexProgram_, splatProgram_, resolveProgram_;
    FullscreenPass pass_;
    gl::Buffer vertices_, depths_, winners_;
    int sourceWidth_ = 0, sourceHeight_ = 0, width_ = 0, height_ = 0;
    StageClock clock_;
};

}  // namespace

std::unique_ptr<UpconversionMethod> makeWarpSplat(const DataPaths& paths, const std::string& name,
                                                  const WarpSplatSettings& settings) {
    return std::make_unique<WarpSplatMethod>(paths, name, settings);
}

}  // namespace warplab::renderer
