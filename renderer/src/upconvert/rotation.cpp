// Late warp by camera rotation: the source frame shown as the displayed camera sees it, for a
// camera that only turns about its eye (the shooter's never translates). Every static surface
// is then where a pure rotation puts it whatever its depth, so one homography per frame does
// what the warp's mesh does, at the cost of a full-screen copy; what moved since the source
// stays where the source had it (the warp's velocities are what would move it).
#include "upconvert/rotation.h"

#include <stdexcept>

#include <glm/gtc/type_ptr.hpp>

#include "gbuffer_gl.h"
#include "gl/check.h"
#include "gl/program.h"
#include "upconvert/fullscreen.h"
#include "scene/camera.h"

namespace warplab::renderer {
namespace {

// The rows of a view-projection that give clip x, y and w of a direction (w = 0: a point at
// infinity, so the eye's position drops out), as a 3x3 matrix of the direction.
glm::dmat3 directionToClip(const scene::CameraState& camera, int width, int height) {
    // The renderer's own matrices, so yaw, pitch, aspect and field of view follow its
    // conventions exactly; in double, since the display side is inverted.
    const glm::dmat4 m = glm::dmat4(scene::projectionMatrix(camera, static_cast<float>(width) / height)) *
        glm::dmat4(scene::viewMatrix(camera));
    glm::dmat3 a;
    for (int column = 0; column < 3; ++column) a[column] = glm::dvec3(m[column][0], m[column][1], m[column][3]);
    return a;
}

// Homogeneous clip (x, y, w) to window coordinates (x, y, w) of a width x height image.
glm::dmat3 clipToWindow(int width, int height) {
    glm::dmat3 s(0.0);
    s[0][0] = 0.5 * width;
    s[1][1] = 0.5 * height;
    s[2] = glm::dvec3(0.5 * width, 0.5 * height, 1.0);
    return s;
}

class RotationMethod final : public UpconversionMethod {
public:
    explicit RotationMethod(const DataPaths& paths) {
        info_.name = "rotation";
        info_.description =
            "late warp by camera rotation: the latest 60 Hz frame re-projected, depth ignored, to the displayed "
            "camera (exact for a turning eye and a static scene)";
        info_.sourceRateHz = 60.0;
        info_.reportsCorrespondence = true;
        info_.takesGuardBand = true;
        info_.acceptsGuardBand = true;
        program_ = gl::buildProgram(
            {paths.shaderDir, {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "rotation.frag"}}, {}});
    }

    const MethodInfo& info() const override { return info_; }

    void produce(const UpconversionInput& input, DisplayFrame& out) override {
        if (input.previous == nullptr) throw std::invalid_argument(info_.name + ": no source frame");
        const SourceFrame& source = *input.previous;
        checkSourceSize(source, out, info_);
        const auto& src = source.gbuffer.impl();
        // A banded source's camera is already widened to its larger image (renderSource), so the
        // homography lands in the band wherever the turn looks past the displayed view.
        const glm::mat3 toSource = glm::mat3(
            rotationHomography(input.camera, out.width(), out.height(), source.depicts.camera, src.width, src.height));

        auto& target = out.buffer().impl();
        glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer.id());
        glViewport(0, 0, target.width, target.height);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        glUseProgram(program_.id());
        bindTexture(program_, "uSourceColour", 0, src.colour);
        bindTexture(program_, "uSourceIds", 1, src.ids);
        glUniformMatrix3fv(gl::uniform(program_, "uDisplayToSource"), 1, GL_FALSE, glm::value_ptr(toSource));
        glUniform2f(gl::uniform(program_, "uSourceSize"), static_cast<float>(src.width),
                    static_cast<float>(src.height));
        pass_.draw();
        endImagePass(2);
        gl::checkErrors(("rotating a frame (" + info_.name + ")").c_str());
    }

private:
    MethodInfo info_;
    gl::Program program_;
    FullscreenPass pass_;
};

}  // namespace

glm::dmat3 rotationHomography(const scene::CameraState& display, int width, int height,
                              const scene::CameraState& source, int sourceWidth, int sourceHeight) {
    // Display window -> display NDC (x, y, 1), which is the display's clip (x, y, w) of the
    // pixel's ray up to a positive factor; its direction, then the source's clip and window.
    glm::dmat3 windowToNdc(0.0);
    windowToNdc[0][0] = 2.0 / width;
    windowToNdc[1][1] = 2.0 / height;
    windowToNdc[2] = glm::dvec3(-1.0, -1.0, 1.0);
    return clipToWindow(sourceWidth, sourceHeight) * directionToClip(source, sourceWidth, sourceHeight) *
        glm::inverse(directionToClip(display, width, height)) * windowToNdc;
}

std::unique_ptr<UpconversionMethod> makeRotation(const DataPaths& paths) {
    return std::make_unique<RotationMethod>(paths);
}

}  // namespace warplab::renderer
