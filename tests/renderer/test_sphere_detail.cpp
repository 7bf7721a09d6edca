// Tests for how finely a sphere is drawn: its size on screen (scene/camera.h) and the
// tessellation that size asks for (renderer/mesh.h). No GL context needed.
#include <gtest/gtest.h>

#include <cmath>
#include <iterator>
#include <limits>

#include <glm/glm.hpp>

#include "renderer/mesh.h"
#include "scene/camera.h"

namespace warplab {
namespace {

constexpr int kHeight = 540;
constexpr float kAspect = 16.0f / 9.0f;

// An oracle independent of the formula: project a dense set of points on the sphere with the
// renderer's own matrices and take half the image's widest extent along the line from the
// image centre through the sphere's (the ellipse's long axis lies on it).
double sampledRadiusPixels(const scene::CameraState& camera, glm::vec3 centre, float radius) {
    const glm::dmat4 m = glm::dmat4(scene::projectionMatrix(camera, kAspect) * scene::viewMatrix(camera));
    auto pixel = [&](glm::dvec3 p) {
        const glm::dvec4 clip = m * glm::dvec4(p, 1.0);
        return glm::dvec2(clip.x / clip.w * kHeight * kAspect / 2.0, clip.y / clip.w * kHeight / 2.0);
    };
    glm::dvec2 axis = pixel(glm::dvec3(centre));
    axis = glm::length(axis) > 1e-9 ? glm::normalize(axis) : glm::dvec2(1.0, 0.0);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    const int n = 400;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j < 2 * n; ++j) {
            const double theta = M_PI * i / n, phi = M_PI * j / n;
            const glm::dvec3 p = glm::dvec3(centre) +
                double(radius) *
                    glm::dvec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
            const double along = glm::dot(pixel(p), axis);
            lo = std::min(lo, along);
            hi = std::max(hi, along);
        }
    return (hi - lo) / 2.0;
}

TEST(SphereDetail, ProjectedRadiusIsTheEllipsesLongSemiAxisOnAndOffTheViewAxis) {
    scene::CameraState camera;
    camera.eye = {0.0f, 4.5f, 0.0f};
    camera.yaw = 0.3f;
    camera.pitch = -0.1f;
    int offAxisLarger = 0;
    for (const glm::vec2 ndc :
         {glm::vec2(0.0f), glm::vec2(0.5f, 0.2f), glm::vec2(-0.9f, 0.8f), glm::vec2(0.95f, -0.9f)}) {
        for (const float distance : {2.0f, 6.0f, 25.0f}) {
            const glm::vec3 centre = camera.eye + distance * scene::rayDirection(camera, kAspect, ndc);
            const float got = scene::projectedSphereRadiusPixels(camera, kHeight, centre, 0.45f);
            const double sampled = sampledRadiusPixels(camera, centre, 0.45f);
            // The samples fall on or inside the silhouette: at most a hair short of it.
            EXPECT_NEAR(got, sampled, 1e-3 * sampled + 1e-3) << "ndc " << ndc.x << "," << ndc.y << " at " << distance;
            if (ndc != glm::vec2(0.0f)) {
                const glm::vec3 onAxis = camera.eye + distance * scene::forwardDirection(camera.yaw, camera.pitch);
                offAxisLarger += got > scene::projectedSphereRadiusPixels(camera, kHeight, onAxis, 0.45f);
            }
        }
    }
    EXPECT_EQ(offAxisLarger, 9);  // perspective stretches every sphere off the axis
}

TEST(SphereDetail, ProjectedRadiusIsZeroBehindTheEyeAndInfiniteAroundIt) {
    scene::CameraState camera;
    const glm::vec3 forward = scene::forwardDirection(camera.yaw, camera.pitch);
    EXPECT_EQ(scene::projectedSphereRadiusPixels(camera, kHeight, camera.eye - 3.0f * forward, 1.0f), 0.0f);
    EXPECT_TRUE(std::isinf(scene::projectedSphereRadiusPixels(camera, kHeight, camera.eye + 0.5f * forward, 1.0f)));
    // Beside the eye, reaching past its side plane: unbounded on the image plane.
    const glm::vec3 side = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
    EXPECT_TRUE(std::isinf(scene::projectedSphereRadiusPixels(camera, kHeight, camera.eye + 2.0f * side, 1.0f)));
}

TEST(SphereDetail, EachTessellationIsTheCoarsestWithinAnEighthOfAPixel) {
    const int coarsest = renderer::kSphereSlices[0];
    const int finest = renderer::kSphereSlices[std::size(renderer::kSphereSlices) - 1];
    auto shortfall = [](double radiusPx, int slices) { return radiusPx * (1.0 - std::cos(M_PI / slices)); };
    int previous = coarsest, changes = 0;
    for (double r = 0.0; r < 400.0; r += 0.05) {
        const int slices = renderer::sphereSlicesFor(static_cast<float>(r));
        EXPECT_GE(slices, previous) << r;  // never coarser for a larger sphere
        changes += slices != previous;
        previous = slices;
        if (slices != finest) {
            EXPECT_LE(shortfall(r, slices), 0.125) << r;
        }
        if (slices != coarsest) {
            EXPECT_GT(shortfall(r, slices / 2), 0.125) << r;
        }
    }
    EXPECT_EQ(changes, 3);
    EXPECT_EQ(renderer::sphereSlicesFor(1.0f), 8);
    EXPECT_EQ(renderer::sphereSlicesFor(4.0f), 16);  // a click-game sphere in a 160 x 90 percept
    EXPECT_EQ(renderer::sphereSlicesFor(std::numeric_limits<float>::infinity()), finest);
}

}  // namespace
}  // namespace warplab
