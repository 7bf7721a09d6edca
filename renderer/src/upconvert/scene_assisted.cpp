// Scene-assisted reprojection: the scene's depth is rasterised again at every B-frame (no
// shading), and each fragment's surface point is projected exactly into the two I-frames.
// It is the exact-correspondence reference the bench measures the image-based search
// against, and the better answer where shading, not geometry, is what costs (fill-bound).
#include "upconvert/scene_assisted.h"

#include <algorithm>
#include <stdexcept>

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

// A point is visible in an I-frame when the view depth stored there is within this fraction
// of its own: 1 % covers a surface seen at up to ~80 degrees over the half pixel between the
// point and the texel centre (the bench's ground truth uses the same figure).
constexpr float kDepthTolerance = 0.01f;

class SceneAssistedMethod final : public UpconversionMethod {
public:
    explicit SceneAssistedMethod(const DataPaths& paths) : geometry_(paths) {
        info_.name = "scene-assisted";
        info_.description =
            "scene-assisted bidirectional reprojection between 15 Hz I-frames: the scene's depth rasterised at "
            "each B-frame, exact correspondences, closest-on-miss";
        info_.sourceRateHz = 15.0;
        info_.needsNext = true;
        info_.needsScene = true;
        info_.reportsCorrespondence = true;
        program_ =
            gl::buildProgram({paths.shaderDir,
                              {{GL_VERTEX_SHADER, "scene_assisted.vert"}, {GL_FRAGMENT_SHADER, "scene_assisted.frag"}},
                              {}});
    }

    const MethodInfo& info() const override { return info_; }

    void produce(const UpconversionInput& input, DisplayFrame& out) override {
        if (input.previous == nullptr || input.next == nullptr || input.scene == nullptr)
            throw std::invalid_argument("scene-assisted: needs the previous and next source frames and the scene");
        const SourceFrame& a = *input.previous;
        const SourceFrame& b = *input.next;
        const auto& p = a.gbuffer.impl();
        const auto& n = b.gbuffer.impl();
        auto& target = out.buffer().impl();
        checkSourceSize(a, out, info_);
        checkSourceSize(b, out, info_);
        const double t0 = a.depicts.scene.time, t1 = b.depicts.scene.time;
        if (!(t1 > t0))
            throw std::invalid_argument("scene-assisted: the next source frame is not later than the previous");
        const float alpha = static_cast<float>(std::clamp((input.displayTime - t0) / (t1 - t0), 0.0, 1.0));

        const float aspect = static_cast<float>(target.width) / static_cast<float>(target.height);
        auto viewProjection = [&](const scene::CameraState& c) {
            return scene::projectionMatrix(c, aspect) * scene::viewMatrix(c);
        };
        const glm::mat4 vp = viewProjection(input.camera), vp0 = viewProjection(a.depicts.camera),
                        vp1 = viewProjection(b.depicts.camera);
        const glm::mat4 inverse = glm::mat4(glm::inverse(glm::dmat4(vp)));

        glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer.id());
        glViewport(0, 0, target.width, target.height);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
        glUseProgram(program_.id());
        auto u = [&](const char* name) { return gl::uniform(program_, name); };
        bindTexture(program_, "uColour0", 0, p.colour);
        bindTexture(program_, "uColour1", 1, n.colour);
        bindTexture(program_, "uDepth0", 2, p.depth);
        bindTexture(program_, "uDepth1", 3, n.depth);
        glUniformMatrix4fv(u("uViewProjection"), 1, GL_FALSE, glm::value_ptr(vp));
        glUniformMatrix4fv(u("uViewProjection0"), 1, GL_FALSE, glm::value_ptr(vp0));
        glUniformMatrix4fv(u("uViewProjection1"), 1, GL_FALSE, glm::value_ptr(vp1));
        glUniformMatrix4fv(u("uInverseViewProjection"), 1, GL_FALSE, glm::value_ptr(inverse));
        glUniform2f(u("uSize"), static_cast<float>(target.width), static_cast<float>(target.height));
        glUniform1f(u("uAlpha"), alpha);
        glUniform1f(u("uNear"), input.camera.nearPlane);
        glUniform1f(u("uFar"), input.camera.farPlane);
        glUniform1f(u("uDepthTolerance"), kDepthTolerance);

        geometry_.drawSky(program_);  // the sky everywhere first; then the scene's surfaces over it
        const GLint model = u("uModel"), model0 = u("uModel0"), model1 = u("uModel1"), objectId = u("uObjectId");
        const double now = input.displayTime;
        geometry_.draw(*input.scene, input.camera, target.height, [&](const SceneGeometry::Item& item) {
            glm::mat4 m0 = item.model, m1 = item.model;
            if (item.object != nullptr) {
                m0 = scene::modelMatrix(scene::objectAt(*item.object, now, a.depicts.scene));
                m1 = scene::modelMatrix(scene::objectAt(*item.object, now, b.depicts.scene));
            }
            glUniformMatrix4fv(model, 1, GL_FALSE, glm::value_ptr(item.model));
            glUniformMatrix4fv(model0, 1, GL_FALSE, glm::value_ptr(m0));
            glUniformMatrix4fv(model1, 1, GL_FALSE, glm::value_ptr(m1));
            glUniform1ui(objectId, item.id);
        });
        for (int unit = 3; unit >= 0; --unit) {
            glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
            glBindTexture(GL_TEXTURE_2D, 0);
        }
        glUseProgram(0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        gl::checkErrors("scene-assisted reprojection");
    }

private:
    MethodInfo info_;
    SceneGeometry geometry_;
    gl::Program program_;
};

}  // namespace

std::unique_ptr<UpconversionMethod> makeSceneAssisted(const DataPaths& paths) {
    return std::make_unique<SceneAssistedMethod>(paths);
}

}  // namespace warplab::renderer
