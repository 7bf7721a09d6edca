// Extrapolation by iterative search: warp's motion model (seed 004 eq. 5-11) solved per
// displayed pixel with the fixed-point search of seed 000 eq. 4-7, in one full-screen
// fragment pass (shaders/warp_search.frag) -- no mesh, no geometry or tessellation stage.
#include "upconvert/warp_search.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "gbuffer_gl.h"
#include "gl/check.h"
#include "gl/program.h"
#include "upconvert/fullscreen.h"
#include "scene/camera.h"

namespace warplab::renderer {
namespace {

class WarpSearchMethod final : public UpconversionMethod {
public:
    WarpSearchMethod(const DataPaths& paths, const std::string& name, const WarpSearchSettings& settings)
        : settings_(settings) {
        if (settings.iterations < 1 || settings.iterations > 8)
            throw std::invalid_argument(name + ": iterations must be 1..8");
        if (settings.rings < 0 || settings.rings > 4) throw std::invalid_argument(name + ": rings must be 0..4");
        info_.name = name;
        info_.sourceRateHz = 15.0;
        info_.needsNext = false;
        info_.reportsCorrespondence = true;
        info_.description =
            "extrapolation from the latest 15 Hz frame by iterative search along the warp's flow "
            "(one full-screen pass, no mesh), m = " +
            std::to_string(settings.iterations) +
            (settings.rings > 0 ? ", " + std::to_string(settings.rings) + " rings of neighbourhood starts" : "");
        program_ = gl::buildProgram(
            {paths.shaderDir,
             {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "warp_search.frag", {"warp_common.glsl"}}},
             {"ITERATIONS " + std::to_string(settings.iterations), "RINGS " + std::to_string(settings.rings)}});
    }

    const MethodInfo& info() const override { return info_; }

    void produce(const UpconversionInput& input, DisplayFrame& out) override {
        if (input.previous == nullptr) throw std::invalid_argument(info_.name + ": no source frame");
        const SourceFrame& source = *input.previous;
        const auto& src = source.gbuffer.impl();
        const int w = out.width(), h = out.height();
        checkSourceSize(source, out, info_);
        const float aspect = static_cast<float>(w) / static_cast<float>(h);
        const scene::CameraState& sourceCamera = source.depicts.camera;
        const glm::mat4 sourceViewProjection =
            scene::projectionMatrix(sourceCamera, aspect) * scene::viewMatrix(sourceCamera);
        const glm::mat4 targetViewProjection =
            scene::projectionMatrix(input.camera, aspect) * scene::viewMatrix(input.camera);
        // Inverted in double, as warp does: float inversion of a perspective matrix with near
        // 0.05 and far 200 costs several bits where depth is most compressed.
        const glm::mat4 sourceInverse = glm::mat4(glm::inverse(glm::dmat4(sourceViewProjection)));
        const float dt = static_cast<float>(input.displayTime - source.depicts.scene.time);

        auto& target = out.buffer().impl();
        glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer.id());
        glViewport(0, 0, w, h);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);

        glUseProgram(program_.id());
        auto u = [&](const char* name) { return gl::uniform(program_, name); };
        bindTexture(program_, "uSourceDepth", 0, src.depth);
        bindTexture(program_, "uSourceVelocity", 1, src.velocity);
        bindTexture(program_, "uSourceColour", 2, src.colour);
        bindTexture(program_, "uSourceIds", 3, src.ids);
        glUniformMatrix4fv(u("uSourceInverseViewProjection"), 1, GL_FALSE, glm::value_ptr(sourceInverse));
        glUniformMatrix4fv(u("uTargetViewProjection"), 1, GL_FALSE, glm::value_ptr(targetViewProjection));
        glUniform3fv(u("uSourceEye"), 1, glm::value_ptr(sourceCamera.eye));
        glUniform2f(u("uSize"), static_cast<float>(w), static_cast<float>(h));
        glUniform1f(u("uDt"), dt);
        glUniform1f(u("uSkyDistance"), 0.9f * std::min(sourceCamera.farPlane, input.camera.farPlane));
        glUniform1f(u("uEps"), settings_.errorThresholdPx);
        glUniform1f(u("uRingRadius"), settings_.ringRadius * static_cast<float>(h));
        pass_.draw();

        for (int unit = 3; unit >= 0; --unit) {
            glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
            glBindTexture(GL_TEXTURE_2D, 0);
        }
        glUseProgram(0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glEnable(GL_DEPTH_TEST);
        gl::checkErrors(("extrapolating a frame by search (" + info_.name + ")").c_str());
    }

private:
    MethodInfo info_;
    WarpSearchSettings settings_;
    gl::Program program_;
    FullscreenPass pass_;
};

}  // namespace

std::unique_ptr<UpconversionMethod> makeWarpSearch(const DataPaths& paths, const std::string& name,
                                                   const WarpSearchSettings& settings) {
    return std::make_unique<WarpSearchMethod>(paths, name, settings);
}

}  // namespace warplab::renderer
