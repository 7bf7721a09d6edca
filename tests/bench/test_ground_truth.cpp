// The benchmark's ground truth (bench/ground_truth.h) on G-buffers made by an analytic ray
// caster here -- a floor and a back wall (the hangar, id 1), spheres from the snapshot, sky
// elsewhere -- so every expected coordinate comes from closed-form geometry and an
// independently built camera basis, not from the matrices the code under test inverts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "bench/ground_truth.h"
#include "image/image.h"
#include "scene/scene.h"

namespace warplab::bench {
namespace {

constexpr int kW = 160;
constexpr int kH = 90;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The hangar stand-in: floor y = 0 for kWallZ <= z <= 40, and a wall z = kWallZ facing +z,
// |x| <= 15, 0 <= y <= 12. At 40 m the floor is seen ~84 degrees from face-on, where depth
// changes by ~10 % from one row to the next: the edge-on case for the visibility test.
constexpr double kWallZ = -40.0;

// Camera basis built as glm::lookAt does, in double, from the yaw/pitch convention.
struct Basis {
    glm::dvec3 eye, forward, right, up;
    double tanHalf, aspect, nearPlane, farPlane;
    int width, height;
};

Basis basisOf(const scene::CameraState& c, int w = kW, int h = kH) {
    const double yaw = c.yaw, pitch = c.pitch;
    Basis b;
    b.eye = glm::dvec3(c.eye);
    b.forward = {std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch)};
    b.right = glm::normalize(glm::cross(b.forward, glm::dvec3(0, 1, 0)));
    b.up = glm::cross(b.right, b.forward);
    b.tanHalf = std::tan(double(c.verticalFovDeg) * 3.14159265358979323846 / 360.0);
    b.aspect = double(w) / double(h);
    b.nearPlane = c.nearPlane;
    b.farPlane = c.farPlane;
    b.width = w;
    b.height = h;
    return b;
}

// Direction through the centre of pixel (x, y), top-down; its forward component is 1, so a
// ray parameter t is the eye-space depth.
glm::dvec3 pixelRay(const Basis& b, int x, int y) {
    const double nx = 2.0 * (x + 0.5) / b.width - 1.0, ny = 1.0 - 2.0 * (y + 0.5) / b.height;
    return b.forward + b.right * (nx * b.tanHalf * b.aspect) + b.up * (ny * b.tanHalf);
}

// Top-down continuous image coordinates of a world point (or, with direction = true, of a
// direction at infinity).
glm::dvec2 projectPoint(const Basis& b, const glm::dvec3& p, bool direction = false) {
    const glm::dvec3 d = direction ? p : p - b.eye;
    const double z = glm::dot(d, b.forward);
    const double nx = glm::dot(d, b.right) / (z * b.tanHalf * b.aspect);
    const double ny = glm::dot(d, b.up) / (z * b.tanHalf);
    return {(nx + 1.0) * 0.5 * b.width, (1.0 - ny) * 0.5 * b.height};
}

struct Hit {
    double t = std::numeric_limits<double>::infinity();
    std::uint32_t id = scene::kIdNone;
};

Hit castRay(const glm::dvec3& o, const glm::dvec3& d, const scene::SceneSnapshot& snapshot) {
    Hit best;
    const auto consider = [&](double t, std::uint32_t id) {
        if (t > 0.0 && t < best.t) best = {t, id};
    };
    if (d.y < 0.0) {
        const double t = -o.y / d.y;
        const double z = o.z + t * d.z;
        if (z >= kWallZ && z <= 40.0) consider(t, scene::kIdHangar);
    }
    if (d.z < 0.0) {
        const double t = (kWallZ - o.z) / d.z;
        const glm::dvec3 p = o + t * d;
        if (std::abs(p.x) <= 15.0 && p.y >= 0.0 && p.y <= 12.0) consider(t, scene::kIdHangar);
    }
    for (const auto& obj : snapshot.objects) {
        const glm::dvec3 oc = o - glm::dvec3(obj.position);
        const double r = obj.halfExtents.x;
        const double a = glm::dot(d, d), bh = glm::dot(oc, d), c = glm::dot(oc, oc) - r * r;
        const double disc = bh * bh - a * c;
        if (disc >= 0.0) consider((-bh - std::sqrt(disc)) / a, obj.id);
    }
    return best;
}

struct GBuffer {
    image::ImageF depth;
    image::ImageU32 ids;
};

// Window depth as GL stores it for glm::perspective (OpenGL clip, depth range [0, 1]), rounded
// to float as a DEPTH_COMPONENT32F attachment does.
GBuffer render(const scene::FrameDescription& frame) {
    const Basis b = basisOf(frame.camera);
    GBuffer g{image::ImageF::make(kW, kH, 1), image::ImageU32::make(kW, kH)};
    const double n = b.nearPlane, f = b.farPlane;
    for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
            const Hit hit = castRay(b.eye, pixelRay(b, x, y), frame.scene);
            if (hit.id == scene::kIdNone || hit.t > f) {
                g.depth.at(x, y)[0] = 1.0f;
                continue;
            }
            const double ndcZ = (f + n) / (f - n) - 2.0 * f * n / ((f - n) * hit.t);
            g.depth.at(x, y)[0] = float(0.5 * ndcZ + 0.5);
            g.ids.at(x, y) = hit.id;
        }
    }
    return g;
}

scene::ObjectState sphere(std::uint32_t id, glm::vec3 position, float radius) {
    scene::ObjectState o;
    o.id = id;
    o.shape = scene::Shape::Sphere;
    o.position = position;
    o.halfExtents = glm::vec3(radius);
    return o;
}

scene::FrameDescription frameAt(double time, std::vector<scene::ObjectState> objects, float yaw = 0.0f) {
    scene::FrameDescription f;
    f.camera.yaw = yaw;
    f.scene.time = time;
    f.scene.objects = std::move(objects);
    return f;
}

Correspondence correspond(const scene::FrameDescription& display, const scene::FrameDescription& source) {
    const GBuffer d = render(display), s = render(source);
    return trueCorrespondence(display, d.depth, d.ids, source, s.depth, s.ids);
}

std::size_t index(int x, int y) { return std::size_t(y) * kW + x; }

// True when every source pixel within 1.5 px of c shows `id`: then the point at c must be
// judged visible (or, for another id, hidden) whatever the rounding at the footprint's edge.
bool surroundedBy(const image::ImageU32& ids, glm::dvec2 c, std::uint32_t id) {
    for (int y = int(std::floor(c.y - 1.5)); y <= int(std::floor(c.y + 1.5)); ++y)
        for (int x = int(std::floor(c.x - 1.5)); x <= int(std::floor(c.x + 1.5)); ++x)
            if (x < 0 || y < 0 || x >= ids.width || y >= ids.height || ids.at(x, y) != id) return false;
    return true;
}

TEST(GroundTruth, IdenticalFramesMapEveryPixelOntoItsOwnCentre) {
    const auto frame = frameAt(1.0, {sphere(scene::kIdTarget, {1.0f, 4.5f, -6.0f}, 0.6f)}, 0.2f);
    const GBuffer g = render(frame);
    const Correspondence c = trueCorrespondence(frame, g.depth, g.ids, frame, g.depth, g.ids);
    ASSERT_EQ(c.width, kW);
    ASSERT_EQ(c.height, kH);
    int counts[3] = {0, 0, 0};  // sky, hangar, target: all three kinds of pixel are exercised
    for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
            const std::size_t i = index(x, y);
            EXPECT_NEAR(c.coords[i].x, x + 0.5, 1e-3) << x << "," << y;
            EXPECT_NEAR(c.coords[i].y, y + 0.5, 1e-3) << x << "," << y;
            EXPECT_EQ(c.visible[i], 1) << x << "," << y;
            ++counts[std::min<std::uint32_t>(g.ids.at(x, y), 2)];
        }
    }
    EXPECT_GT(counts[0], 100);
    EXPECT_GT(counts[1], 1000);
    EXPECT_GT(counts[2], 100);
}

// The camera turns; the hangar is static, so each point lands where the source camera sees
// it. The eye does not move, so depth quantisation cannot move a point sideways: exact.
TEST(GroundTruth, CameraYawMovesStaticSurfacesToTheirProjection) {
    const auto source = frameAt(0.0, {}, 0.0f);
    const auto display = frameAt(1.0 / 60.0, {}, 0.12f);
    const GBuffer s = render(source), d = render(display);
    const Correspondence c = trueCorrespondence(display, d.depth, d.ids, source, s.depth, s.ids);
    const Basis db = basisOf(display.camera), sb = basisOf(source.camera);
    int checked = 0, visibleChecked = 0;
    for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
            if (d.ids.at(x, y) != scene::kIdHangar) continue;
            const glm::dvec3 ray = pixelRay(db, x, y);
            const glm::dvec3 p = db.eye + castRay(db.eye, ray, display.scene).t * ray;
            const glm::dvec2 expected = projectPoint(sb, p);
            const std::size_t i = index(x, y);
            EXPECT_NEAR(c.coords[i].x, expected.x, 1e-3) << x << "," << y;
            EXPECT_NEAR(c.coords[i].y, expected.y, 1e-3) << x << "," << y;
            ++checked;
            // Static scene, same eye: everything seen now was seen before unless it was
            // outside the source image. The edge-on floor far away must pass too.
            const bool inside = expected.x >= 0 && expected.x < kW && expected.y >= 0 && expected.y < kH;
            if (!inside) {
                EXPECT_EQ(c.visible[i], 0) << x << "," << y;
            }
            if (surroundedBy(s.ids, expected, scene::kIdHangar)) {
                EXPECT_EQ(c.visible[i], 1) << x << "," << y;
                ++visibleChecked;
            }
        }
    }
    EXPECT_GT(checked, 4000);
    EXPECT_GT(visibleChecked, 3000);
}

// Sky is at infinity: only the camera's rotation moves it, never its translation.
TEST(GroundTruth, SkyFollowsTheCameraRotationOnly) {
    auto source = frameAt(0.0, {}, -0.05f);
    source.camera.pitch = 0.03f;
    auto display = frameAt(0.1, {}, 0.1f);
    display.camera.pitch = -0.02f;
    display.camera.eye += glm::vec3(2.0f, 0.5f, -3.0f);  // translation must not matter for sky
    const GBuffer s = render(source), d = render(display);
    const Correspondence c = trueCorrespondence(display, d.depth, d.ids, source, s.depth, s.ids);
    const Basis db = basisOf(display.camera), sb = basisOf(source.camera);
    int sky = 0;
    for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
            if (d.ids.at(x, y) != scene::kIdNone) continue;
            const glm::dvec2 expected = projectPoint(sb, pixelRay(db, x, y), true);
            const std::size_t i = index(x, y);
            EXPECT_NEAR(c.coords[i].x, expected.x, 1e-3) << x << "," << y;
            EXPECT_NEAR(c.coords[i].y, expected.y, 1e-3) << x << "," << y;
            if (surroundedBy(s.ids, expected, scene::kIdNone)) {
                EXPECT_EQ(c.visible[i], 1) << x << "," << y;
            }
            if (surroundedBy(s.ids, expected, scene::kIdHangar)) {
                EXPECT_EQ(c.visible[i], 0) << x << "," << y;
            }
            ++sky;
        }
    }
    EXPECT_GT(sky, 1000);
}

// The target moved by a known offset (and turned) between source and display: each of its
// points goes back by exactly that motion; the hangar's pixels stay where they are.
TEST(GroundTruth, MovingObjectsPixelsShiftByTheirProjectedMotion) {
    const glm::vec3 at{0.5f, 4.0f, -7.0f};
    const glm::vec3 offset{0.4f, -0.25f, 0.6f};
    auto movedFrom = sphere(scene::kIdTarget, at - offset, 0.7f);
    auto movedTo = sphere(scene::kIdTarget, at, 0.7f);
    for (const bool turning : {false, true}) {
        SCOPED_TRACE(turning ? "translated and turned" : "translated");
        // Turned 0.4 rad about an oblique axis: a point keeps its place on the body.
        const glm::dquat turn =
            turning ? glm::angleAxis(0.4, glm::normalize(glm::dvec3(0.3, 1.0, 0.2))) : glm::dquat(1, 0, 0, 0);
        movedFrom.orientation = glm::quat(1, 0, 0, 0);
        movedTo.orientation = glm::quat(turn);
        const auto source = frameAt(0.0, {movedFrom});
        const auto display = frameAt(0.05, {movedTo});
        const GBuffer s = render(source), d = render(display);
        const Correspondence c = trueCorrespondence(display, d.depth, d.ids, source, s.depth, s.ids);
        const Basis b = basisOf(display.camera);
        int target = 0;
        for (int y = 0; y < kH; ++y) {
            for (int x = 0; x < kW; ++x) {
                const std::uint32_t id = d.ids.at(x, y);
                const std::size_t i = index(x, y);
                if (id == scene::kIdTarget) {
                    const glm::dvec3 ray = pixelRay(b, x, y);
                    const glm::dvec3 p = b.eye + castRay(b.eye, ray, display.scene).t * ray;
                    // Back along the exact motion: undo the turn about the display centre, then the move.
                    const glm::dvec3 back = glm::dvec3(movedFrom.position) + glm::inverse(turn) * (p - glm::dvec3(at));
                    const glm::dvec2 expected = projectPoint(b, back);
                    EXPECT_NEAR(c.coords[i].x, expected.x, 1e-3) << x << "," << y;
                    EXPECT_NEAR(c.coords[i].y, expected.y, 1e-3) << x << "," << y;
                    ++target;
                } else {
                    // The same camera: static surfaces and sky do not move at all.
                    EXPECT_NEAR(c.coords[i].x, x + 0.5, 1e-3) << x << "," << y;
                    EXPECT_NEAR(c.coords[i].y, y + 0.5, 1e-3) << x << "," << y;
                }
            }
        }
        EXPECT_GT(target, 150);  // ~7.8 px radius: ~190 pixels
        // Without the turn, the point at the target's centre pixel faces the camera in both frames.
        const int cx = int(std::floor(projectPoint(b, glm::dvec3(at)).x)),
                  cy = int(std::floor(projectPoint(b, glm::dvec3(at)).y));
        ASSERT_EQ(d.ids.at(cx, cy), scene::kIdTarget);
        if (!turning) {
            EXPECT_EQ(c.visible[index(cx, cy)], 1);
        }
    }
}

// A wall point that a sphere (present only in the source) covers is not visible there; wall
// points clear of it are. The display camera also moved sideways, so coordinates differ.
TEST(GroundTruth, PointHiddenBehindAnotherObjectIsNotVisible) {
    auto display = frameAt(0.1, {});
    display.camera.eye.x += 0.5f;
    const auto source = frameAt(0.0, {sphere(scene::kIdFirstSphere, {0.0f, 4.5f, -8.0f}, 1.5f)});
    const GBuffer s = render(source), d = render(display);
    const Correspondence c = trueCorrespondence(display, d.depth, d.ids, source, s.depth, s.ids);
    const Basis db = basisOf(display.camera), sb = basisOf(source.camera);
    int hidden = 0, shown = 0;
    for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
            if (d.ids.at(x, y) != scene::kIdHangar) continue;
            const glm::dvec3 ray = pixelRay(db, x, y);
            const glm::dvec3 p = db.eye + castRay(db.eye, ray, display.scene).t * ray;
            const glm::dvec2 expected = projectPoint(sb, p);
            const std::size_t i = index(x, y);
            // Translation with a float depth: a few 1e-5 px of parallax error at most.
            EXPECT_NEAR(c.coords[i].x, expected.x, 1e-3) << x << "," << y;
            EXPECT_NEAR(c.coords[i].y, expected.y, 1e-3) << x << "," << y;
            if (surroundedBy(s.ids, expected, scene::kIdFirstSphere)) {
                EXPECT_EQ(c.visible[i], 0) << x << "," << y;
                ++hidden;
            } else if (surroundedBy(s.ids, expected, scene::kIdHangar)) {
                EXPECT_EQ(c.visible[i], 1) << x << "," << y;
                ++shown;
            }
        }
    }
    EXPECT_GT(hidden, 200);
    EXPECT_GT(shown, 3000);
}

// Half a turn about the vertical: what faces the camera now faced away in the source, hidden
// by the sphere's own front (same id, but ~1.4 m further: far outside the depth tolerance).
TEST(GroundTruth, PointOnTheFarSideOfItsOwnObjectIsNotVisible) {
    auto now = sphere(scene::kIdTarget, {0.0f, 4.5f, -7.0f}, 0.7f);
    auto before = now;
    now.orientation = glm::angleAxis(3.14159265f, glm::vec3(0, 1, 0));
    const auto display = frameAt(0.1, {now});
    const auto source = frameAt(0.0, {before});
    const Correspondence c = correspond(display, source);
    const Basis b = basisOf(display.camera);
    const glm::dvec2 centre = projectPoint(b, glm::dvec3(now.position));
    int hidden = 0;
    for (int y = int(centre.y) - 3; y <= int(centre.y) + 3; ++y)
        for (int x = int(centre.x) - 3; x <= int(centre.x) + 3; ++x) hidden += c.visible[index(x, y)] == 0;
    EXPECT_EQ(hidden, 49);
}

// No position in the source: the object did not exist then, or the point is behind the
// source camera (a projection through w < 0 would land mirrored inside the image).
TEST(GroundTruth, NoSourcePositionGivesNaNAndNotVisible) {
    const auto display = frameAt(0.1, {sphere(scene::kIdFirstSphere + 3, {0.0f, 4.5f, -6.0f}, 1.0f)});
    const auto c = correspond(display, frameAt(0.0, {}));
    const std::size_t centre = index(kW / 2, kH / 2);
    EXPECT_TRUE(std::isnan(c.coords[centre].x) && std::isnan(c.coords[centre].y));
    EXPECT_EQ(c.visible[centre], 0);

    const auto turnedAway = correspond(frameAt(0.1, {}), frameAt(0.0, {}, 3.14159265f));
    int nan = 0;
    for (std::size_t i = 0; i < turnedAway.coords.size(); ++i) {
        nan += std::isnan(turnedAway.coords[i].x) ? 1 : 0;
        EXPECT_EQ(turnedAway.visible[i], 0);
    }
    EXPECT_EQ(nan, kW * kH);
}

TEST(GroundTruth, RejectsMismatchedSizesAndUnknownIds) {
    const auto frame = frameAt(0.0, {});
    const GBuffer g = render(frame);
    auto smallIds = image::ImageU32::make(kW - 1, kH);
    try {
        trueCorrespondence(frame, g.depth, smallIds, frame, g.depth, g.ids);
        FAIL() << "expected std::invalid_argument";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("trueCorrespondence"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("159x90"), std::string::npos) << e.what();
    }
    auto rgb = image::ImageF::make(kW, kH, 3);
    EXPECT_THROW(trueCorrespondence(frame, g.depth, g.ids, frame, rgb, g.ids), std::invalid_argument);
    // An id on screen that the display snapshot does not list: its motion is unknown.
    auto strayIds = g.ids;
    strayIds.at(3, 4) = 77;
    try {
        trueCorrespondence(frame, g.depth, strayIds, frame, g.depth, g.ids);
        FAIL() << "expected std::invalid_argument";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("77"), std::string::npos) << e.what();
    }
    const auto twice = frameAt(0.0, {sphere(20, {0, 4, -5}, 0.5f), sphere(20, {1, 4, -5}, 0.5f)});
    EXPECT_THROW(trueCorrespondence(twice, g.depth, g.ids, frame, g.depth, g.ids), std::invalid_argument);
}

Correspondence handMade(int w, int h, std::vector<glm::vec2> coords, std::vector<std::uint8_t> visible) {
    Correspondence c;
    c.width = c.sourceWidth = w;
    c.height = c.sourceHeight = h;
    c.coords = std::move(coords);
    c.visible = std::move(visible);
    return c;
}

TEST(Disocclusion, MaskIsPixelsVisibleInNoSource) {
    const std::vector<glm::vec2> coords(4, glm::vec2(0.5f));
    const auto previous = handMade(2, 2, coords, {1, 0, 1, 0});
    const auto next = handMade(2, 2, coords, {1, 1, 0, 0});
    EXPECT_EQ(disoccludedMask({&previous, &next}), (std::vector<std::uint8_t>{0, 0, 0, 1}));
    EXPECT_EQ(disoccludedMask({&previous}), (std::vector<std::uint8_t>{0, 1, 0, 1}));
    const auto other = handMade(4, 1, coords, {1, 1, 1, 1});
    EXPECT_THROW(disoccludedMask({&previous, &other}), std::invalid_argument);
    EXPECT_THROW(disoccludedMask({}), std::invalid_argument);
    EXPECT_THROW(disoccludedMask({&previous, nullptr}), std::invalid_argument);
}

// What no source shows, split by why: off-screen in every source (border) against inside one
// but hidden in all (a true disocclusion). Mixing them let border fill pass for disocclusion
// quality (96 % of the old, mixed mask was border on `pan`).
TEST(Disocclusion, UnseenPixelsAreSplitIntoBorderAndOccluded) {
    const float f = float(kNaN);
    // Sources 4x2 pixels; four display pixels.
    // 0: visible in the previous source.      -> neither
    // 1: inside both images, visible in none.  -> occluded
    // 2: outside both (left of one, below the other). -> border
    // 3: no position in one, outside the other -> border; 4: inside only the next -> occluded
    auto previous = handMade(5, 1, {{1.5f, 0.5f}, {2.5f, 1.5f}, {-0.5f, 1.0f}, {f, f}, {9.0f, 0.5f}}, {1, 0, 0, 0, 0});
    auto next = handMade(5, 1, {{1.5f, 0.5f}, {0.0f, 2.0f}, {1.0f, 2.5f}, {4.5f, 0.5f}, {4.0f, 0.0f}}, {0, 0, 0, 0, 0});
    previous.sourceWidth = next.sourceWidth = 4;
    previous.sourceHeight = next.sourceHeight = 2;
    const UnseenMasks masks = unseenMasks({&previous, &next});
    EXPECT_EQ(masks.border, (std::vector<std::uint8_t>{0, 0, 1, 1, 0}));
    EXPECT_EQ(masks.occluded, (std::vector<std::uint8_t>{0, 1, 0, 0, 1}));
    // Together: the pixels visible in no source.
    const auto unseen = disoccludedMask({&previous, &next});
    for (std::size_t i = 0; i < unseen.size(); ++i) EXPECT_EQ(unseen[i], masks.border[i] | masks.occluded[i]) << i;
    EXPECT_THROW(unseenMasks({}), std::invalid_argument);
}

TEST(Disocclusion, MaskedMeanAbsoluteErrorOverRgbOfMaskedPixels) {
    auto a = image::ImageRGBA8::make(3, 1), b = image::ImageRGBA8::make(3, 1);
    const std::uint8_t pa[12] = {10, 20, 30, 255, 100, 100, 100, 0, 0, 0, 0, 0};
    const std::uint8_t pb[12] = {13, 14, 39, 0, 70, 100, 100, 9, 200, 200, 200, 0};  // alpha ignored
    std::copy(pa, pa + 12, a.pixels.begin());
    std::copy(pb, pb + 12, b.pixels.begin());
    EXPECT_DOUBLE_EQ(maskedMeanAbsoluteError(a, b, {1, 0, 0}), 6.0);  // (3 + 6 + 9) / 3
    EXPECT_DOUBLE_EQ(maskedMeanAbsoluteError(a, b, {1, 1, 0}), 8.0);  // (18 + 30) / 6
    EXPECT_DOUBLE_EQ(maskedMeanAbsoluteError(a, b, {0, 0, 1}), 200.0);
    EXPECT_TRUE(std::isnan(maskedMeanAbsoluteError(a, b, {0, 0, 0})));
    EXPECT_THROW(maskedMeanAbsoluteError(a, b, {1, 1}), std::invalid_argument);
    EXPECT_THROW(maskedMeanAbsoluteError(a, image::ImageRGBA8::make(1, 3), {1, 1, 1}), std::invalid_argument);
}

// Errors chosen away from the thresholds except where the strict "<" is the point: an error of
// exactly 1 px (dyadic coordinates, exact in float) is not "< 1".
TEST(CorrespondenceStats, SharesOverAllAndVisiblePixelsPoolBothSources) {
    const float f = float(kNaN);
    // Source 1: errors 0.05, 0.3, 0.75 (hidden), none claimed, 1.0 exactly.
    const auto truth1 =
        handMade(5, 1, {{0.5f, 0.5f}, {1.5f, 0.5f}, {2.5f, 0.5f}, {3.5f, 0.5f}, {4.5f, 0.5f}}, {1, 1, 0, 1, 1});
    const std::vector<glm::vec2> reported1 = {{0.55f, 0.5f}, {1.5f, 0.8f}, {2.5f, 1.25f}, {f, 0.5f}, {5.5f, 0.5f}};
    CorrespondenceAccumulator acc;
    acc.add(reported1, truth1);
    CorrespondenceStats s = acc.stats();
    EXPECT_EQ(s.samples, 5u);
    EXPECT_EQ(s.hitSamples, 4u);
    EXPECT_DOUBLE_EQ(s.allLt0p1, 1.0 / 5);
    EXPECT_DOUBLE_EQ(s.allLt0p5, 2.0 / 5);
    EXPECT_DOUBLE_EQ(s.allLt1, 3.0 / 5);
    EXPECT_DOUBLE_EQ(s.hitLt0p1, 1.0 / 4);
    EXPECT_DOUBLE_EQ(s.hitLt0p5, 2.0 / 4);
    EXPECT_DOUBLE_EQ(s.hitLt1, 2.0 / 4);

    // Source 2: errors 0 (hidden), 0 but the truth has no position (error +inf), 0.6, 0.09
    // diagonally (0.06, 0.0675), 2 (hidden).
    const auto truth2 =
        handMade(5, 1, {{0.5f, 0.5f}, {f, f}, {2.5f, 0.5f}, {3.5f, 0.5f}, {4.5f, 0.5f}}, {0, 1, 1, 1, 0});
    const std::vector<glm::vec2> reported2 = {{0.5f, 0.5f}, {1.5f, 0.5f}, {2.5f, 1.1f}, {3.56f, 0.5675f}, {6.5f, 0.5f}};
    acc.add(reported2, truth2);
    s = acc.stats();
    EXPECT_EQ(s.samples, 10u);
    EXPECT_EQ(s.hitSamples, 7u);
    EXPECT_DOUBLE_EQ(s.allLt0p1, 3.0 / 10);  // 0.05; 0, 0.09
    EXPECT_DOUBLE_EQ(s.allLt0p5, 4.0 / 10);  // + 0.3
    EXPECT_DOUBLE_EQ(s.allLt1, 6.0 / 10);  // + 0.75, 0.6
    EXPECT_DOUBLE_EQ(s.hitLt0p1, 2.0 / 7);  // 0.05, 0.09
    EXPECT_DOUBLE_EQ(s.hitLt0p5, 3.0 / 7);  // + 0.3
    EXPECT_DOUBLE_EQ(s.hitLt1, 4.0 / 7);  // + 0.6

    EXPECT_THROW(acc.add(std::vector<glm::vec2>(4), truth1), std::invalid_argument);
}

TEST(CorrespondenceStats, NoSamplesGiveNaNShares) {
    CorrespondenceAccumulator empty;
    const CorrespondenceStats none = empty.stats();
    EXPECT_EQ(none.samples, 0u);
    EXPECT_TRUE(std::isnan(none.allLt1) && std::isnan(none.hitLt1));

    CorrespondenceAccumulator allHidden;
    allHidden.add({{0.5f, 0.5f}}, handMade(1, 1, {{0.5f, 0.5f}}, {0}));
    const CorrespondenceStats s = allHidden.stats();
    EXPECT_DOUBLE_EQ(s.allLt0p1, 1.0);
    EXPECT_EQ(s.hitSamples, 0u);
    EXPECT_TRUE(std::isnan(s.hitLt0p1) && std::isnan(s.hitLt0p5) && std::isnan(s.hitLt1));
}

}  // namespace
}  // namespace warplab::bench
