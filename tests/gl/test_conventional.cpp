// The conventional renderer's G-buffer against the scene it was given: ids, velocities,
// depth that unprojects onto the right surface, no NaN/Inf anywhere, reference images.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "gl/gl_test_support.h"
#include "renderer/mesh.h"
#include "scene/camera.h"

namespace warplab {
namespace {

using testing::aimedAt;
using testing::renderFrame;
using testing::shooterScene;

constexpr int kW = 96;
constexpr int kH = 54;

std::uint32_t centreId(const renderer::GBufferImages& g) { return g.ids.at(g.ids.width / 2, g.ids.height / 2); }

TEST(ConventionalRenderer, IdBufferNamesTheTargetWhenAimedAtIt) {
    const auto shooter = shooterScene(kW, kH, 7);
    for (double t : {0.0, 0.37, 2.5}) {
        scene::FrameDescription frame{shooter.restingCamera(), shooter.snapshot(t)};
        frame.camera = aimedAt(frame.camera, frame.scene.objects.front().position);
        EXPECT_EQ(centreId(renderFrame(frame, kW, kH)), scene::kIdTarget) << "t = " << t;
    }
}

TEST(ConventionalRenderer, IdBufferNamesTheWallWhenNotAimedAtTheTarget) {
    const auto shooter = shooterScene(kW, kH, 7);
    scene::FrameDescription frame{shooter.restingCamera(), shooter.snapshot(0.0)};
    frame.camera.yaw = glm::radians(85.0f);  // facing the right-hand wall
    EXPECT_EQ(centreId(renderFrame(frame, kW, kH)), scene::kIdHangar);
    frame.camera.yaw = 0.0f;  // straight down the hallway: the open far door, nothing there
    EXPECT_EQ(centreId(renderFrame(frame, kW, kH)), scene::kIdNone);
}

TEST(ConventionalRenderer, VelocityIsTheTargetsOnItsPixelsAndZeroElsewhere) {
    const auto shooter = shooterScene(kW, kH, 3, 5.0);
    scene::FrameDescription frame{shooter.restingCamera(), shooter.snapshot(1.25)};
    frame.camera = aimedAt(frame.camera, frame.scene.objects.front().position);
    const glm::vec3 v = frame.scene.objects.front().velocity;
    ASSERT_GT(glm::length(v), 4.9f);
    const auto g = renderFrame(frame, kW, kH);
    int targetPixels = 0;
    for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
            const float* p = g.velocity.at(x, y);
            if (g.ids.at(x, y) == scene::kIdTarget) {
                ++targetPixels;
                // A constant uniform written per fragment: exact, no interpolation involved.
                EXPECT_EQ(p[0], v.x);
                EXPECT_EQ(p[1], v.y);
                EXPECT_EQ(p[2], v.z);
            } else {
                EXPECT_EQ(p[0], 0.0f);
                EXPECT_EQ(p[1], 0.0f);
                EXPECT_EQ(p[2], 0.0f);
            }
        }
    }
    EXPECT_GT(targetPixels, 8);  // the sphere is about 4 px across at this size
}

// Window coordinates + stored depth -> world, with the inverse matrices (seed 004 eq. 5-7).
glm::dvec3 unproject(const scene::CameraState& camera, int x, int y, float depth, int w, int h) {
    const glm::dmat4 viewProjection =
        glm::dmat4(scene::projectionMatrix(camera, float(w) / float(h))) * glm::dmat4(scene::viewMatrix(camera));
    const glm::dmat4 inverse = glm::inverse(viewProjection);
    // Images are top-down; GL window y is bottom-up. Pixel centres are at +0.5.
    const glm::dvec4 ndc(2.0 * (x + 0.5) / w - 1.0, 1.0 - 2.0 * (y + 0.5) / h, 2.0 * depth - 1.0, 1.0);
    const glm::dvec4 world = inverse * ndc;
    return glm::dvec3(world) / world.w;
}

double pointTriangleDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    // Ericson, Real-Time Collision Detection 5.1.5: closest point on a triangle.
    const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return glm::length(p - a);
    const glm::dvec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return glm::length(p - b);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return glm::length(p - (a + ab * (d1 / (d1 - d3))));
    const glm::dvec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return glm::length(p - c);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return glm::length(p - (a + ac * (d2 / (d2 - d6))));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return glm::length(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
    const double denom = 1.0 / (va + vb + vc);
    return glm::length(p - (a + ab * (vb * denom) + ac * (vc * denom)));
}

// Every depth pixel, unprojected, lies on the surface named by its id: on the hangar model's
// triangles, or on the target sphere. Tolerance: one step of 32-bit depth near 1 is 2^-24,
// worth d^2 * 2^-24 / near = 1.2e-6 d^2 metres at distance d (near = 0.05 m); the rasteriser's
// interpolated depth may be off by a couple of steps, so allow two (5 mm at 45 m), plus 1 mm
// for the rest of the arithmetic. The sphere is drawn as a polygon of N slices and N / 2 stacks
// (N as its size on screen asks, renderer::sphereSlicesFor) whose vertices lie on the true
// sphere; its triangles' legs span 2 pi / N, so no point of one lies deeper inside than its
// circumcircle's centre, r (1 - cos(pi sqrt(2) / N)): 0.8 mm at N = 64, 13 mm at N = 16.
TEST(ConventionalRenderer, DepthUnprojectsOntoTheSurfaceItCameFrom) {
    const renderer::MeshData hangar = renderer::loadObj(std::string(WARPLAB_SOURCE_DIR) + "/assets/hangar.obj");
    const auto shooter = shooterScene(kW, kH, 11);
    std::vector<scene::CameraState> cameras;
    scene::FrameDescription frame{shooter.restingCamera(), shooter.snapshot(0.8)};
    cameras.push_back(frame.camera);
    cameras.push_back(aimedAt(frame.camera, frame.scene.objects.front().position));
    scene::CameraState turned = frame.camera;
    turned.yaw = glm::radians(-90.0f);
    turned.pitch = glm::radians(-20.0f);
    cameras.push_back(turned);
    const auto& target = frame.scene.objects.front();
    // Close enough that the target is drawn with more than the coarsest polygon.
    scene::CameraState close = frame.camera;
    close.eye = target.position + 3.0f * glm::normalize(frame.camera.eye - target.position);
    cameras.push_back(aimedAt(close, target.position));

    for (const auto& camera : cameras) {
        frame.camera = camera;
        const auto g = renderFrame(frame, kW, kH);
        const int slices = renderer::sphereSlicesFor(
            scene::projectedSphereRadiusPixels(camera, kH, target.position, target.halfExtents.x));
        const double inside = target.halfExtents.x * (1.0 - std::cos(M_PI * std::sqrt(2.0) / slices));
        int checked = 0;
        for (int y = 0; y < kH; ++y) {
            for (int x = 0; x < kW; ++x) {
                const float depth = g.depth.at(x, y)[0];
                const std::uint32_t id = g.ids.at(x, y);
                const glm::dvec3 p = unproject(camera, x, y, depth, kW, kH);
                ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << x << "," << y;
                if (id == scene::kIdNone) {
                    EXPECT_EQ(depth, 1.0f) << "sky pixel " << x << "," << y << " has geometry depth";
                    continue;
                }
                ASSERT_LT(depth, 1.0f);
                const double d = glm::length(p - glm::dvec3(camera.eye));
                const double tolerance = 1e-3 + 2.4e-6 * d * d;
                if (id == scene::kIdTarget) {
                    const double off = glm::length(p - glm::dvec3(target.position)) - target.halfExtents.x;
                    EXPECT_LE(off, tolerance) << "target pixel " << x << "," << y;
                    EXPECT_GE(off, -inside - tolerance) << "target pixel " << x << "," << y;
                } else {
                    ASSERT_EQ(id, scene::kIdHangar);
                    double best = 1e30;
                    for (std::size_t i = 0; i + 2 < hangar.vertices.size(); i += 3)
                        best = std::min(
                            best,
                            pointTriangleDistance(p, hangar.vertices[i].position, hangar.vertices[i + 1].position,
                                                  hangar.vertices[i + 2].position));
                    EXPECT_LE(best, tolerance) << "hangar pixel " << x << "," << y << " at " << d << " m";
                }
                ++checked;
            }
        }
        EXPECT_GT(checked, kW * kH / 2);
    }
}

TEST(ConventionalRenderer, NoNaNOrInfAnywhereEvenAtTheFarPlaneAndNearGeometry) {
    const auto shooter = shooterScene(kW, kH, 5);
    scene::FrameDescription frame{shooter.restingCamera(), shooter.snapshot(3.0)};
    for (float yawDeg : {0.0f, 90.0f, 180.0f, -45.0f}) {
        for (float pitchDeg : {0.0f, 80.0f, -80.0f}) {
            frame.camera.yaw = glm::radians(yawDeg);
            frame.camera.pitch = glm::radians(pitchDeg);
            const auto g = renderFrame(frame, kW, kH);
            for (float v : g.depth.data) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f && v <= 1.0f);
            for (float v : g.velocity.data) ASSERT_TRUE(std::isfinite(v));
            for (int y = 0; y < kH; ++y)
                for (int x = 0; x < kW; ++x) {
                    const glm::dvec3 p = unproject(frame.camera, x, y, g.depth.at(x, y)[0], kW, kH);
                    ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
                }
        }
    }
}

// A spinning box: each fragment's velocity is v + omega x (p - centre), p being the fragment's
// own world position (recovered here by unprojection, good to ~1 mm).
TEST(ConventionalRenderer, RotatingBodyVelocityFollowsAngularVelocity) {
    const auto shooter = shooterScene(kW, kH);
    scene::FrameDescription frame{shooter.restingCamera(), {}};
    scene::ObjectState box;
    box.id = 42;
    box.shape = scene::Shape::Box;
    box.position = {0.0f, 4.5f, -4.0f};
    box.halfExtents = {1.2f, 0.15f, 0.15f};
    box.orientation = glm::angleAxis(0.3f, glm::normalize(glm::vec3(0.2f, 0.1f, 1.0f)));
    box.velocity = {0.5f, -0.25f, 0.0f};
    box.angularVelocity = {0.0f, 1.0f, 6.0f};
    frame.scene.objects.push_back(box);
    const auto g = renderFrame(frame, kW, kH);
    int pixels = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            if (g.ids.at(x, y) != 42u) continue;
            ++pixels;
            const glm::dvec3 p = unproject(frame.camera, x, y, g.depth.at(x, y)[0], kW, kH);
            const glm::dvec3 expected =
                glm::dvec3(box.velocity) + glm::cross(glm::dvec3(box.angularVelocity), p - glm::dvec3(box.position));
            const float* v = g.velocity.at(x, y);
            // 6 rad/s times ~2 mm of position error, plus float rounding.
            EXPECT_NEAR(v[0], expected.x, 0.02) << x << "," << y;
            EXPECT_NEAR(v[1], expected.y, 0.02) << x << "," << y;
            EXPECT_NEAR(v[2], expected.z, 0.02) << x << "," << y;
        }
    EXPECT_GT(pixels, 50);
}

// Reference images: the scene as it looked when a person last approved it.
TEST(ConventionalRenderer, MatchesReferenceImages) {
    const auto shooter = shooterScene(160, 90, 1);
    scene::FrameDescription frame{shooter.restingCamera(), shooter.snapshot(1.0)};
    EXPECT_TRUE(testing::matchesReference("hallway_t1", renderFrame(frame, 160, 90).colour));
    frame.camera = aimedAt(frame.camera, frame.scene.objects.front().position);
    EXPECT_TRUE(testing::matchesReference("aimed_at_target_t1", renderFrame(frame, 160, 90).colour));
    frame.camera.yaw = glm::radians(-70.0f);
    frame.camera.pitch = glm::radians(15.0f);
    EXPECT_TRUE(testing::matchesReference("left_wall", renderFrame(frame, 160, 90).colour));
}

TEST(GBuffer, RefusesSizesOutsideTheLimits) {
    testing::glContext();
    EXPECT_THROW(renderer::GBuffer(0, 10), std::invalid_argument);
    EXPECT_THROW(renderer::GBuffer(10, -1), std::invalid_argument);
    EXPECT_THROW(renderer::GBuffer(16385, 10), std::invalid_argument);
}

}  // namespace
}  // namespace warplab
