// Closed-form bouncing target (seed 004 section 5.3.2) and the ray queries used for scoring.
// The closed form is checked against an independent event-by-event simulation (next wall
// hit, reflect, repeat) in long double, and bit for bit on dyadic inputs where both are exact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "physics/bouncing_target.h"
#include "physics/ray.h"
#include "scene/camera.h"
#include "scene/hangar_layout.h"

namespace warplab::physics {
namespace {

using Layout = scene::HangarLayout;

constexpr double kRadius = 0.35;
constexpr double kPi = 3.14159265358979323846;

// Independent reference: advance to the next wall contact, snap onto the wall, reflect.
// Only moves forwards in time; negative times are handled by time reversal (run the motion
// with the velocity negated).
class ReferenceTarget {
public:
    ReferenceTarget(const TargetPlane& plane, const TargetMotion& motion)
        : minX_(plane.minX),
          maxX_(plane.maxX),
          minY_(plane.minY),
          maxY_(plane.maxY),
          x_(motion.start.x),
          y_(motion.start.y),
          vx_(motion.velocity.x),
          vy_(motion.velocity.y) {}

    void advanceTo(long double target) {
        ASSERT_GE(target, now_) << "the reference only runs forwards";
        for (;;) {
            const long double dtX = timeToWall(x_, vx_, minX_, maxX_);
            const long double dtY = timeToWall(y_, vy_, minY_, maxY_);
            const long double dt = std::min(dtX, dtY);
            if (now_ + dt > target) {
                const long double rest = target - now_;
                x_ += vx_ * rest;
                y_ += vy_ * rest;
                now_ = target;
                return;
            }
            x_ += vx_ * dt;
            y_ += vy_ * dt;
            now_ += dt;
            if (dtX == dt) {
                x_ = vx_ > 0 ? maxX_ : minX_;
                vx_ = -vx_;
                ++bouncesX_;
            }
            if (dtY == dt) {
                y_ = vy_ > 0 ? maxY_ : minY_;
                vy_ = -vy_;
                ++bouncesY_;
            }
        }
    }

    long double x() const { return x_; }
    long double y() const { return y_; }
    long double vx() const { return vx_; }
    long double vy() const { return vy_; }
    int bouncesX() const { return bouncesX_; }
    int bouncesY() const { return bouncesY_; }

private:
    static long double timeToWall(long double p, long double v, long double min, long double max) {
        if (v > 0) return (max - p) / v;
        if (v < 0) return (min - p) / v;
        return std::numeric_limits<long double>::infinity();
    }

    long double minX_, maxX_, minY_, maxY_;
    long double x_, y_, vx_, vy_;
    long double now_ = 0;
    int bouncesX_ = 0, bouncesY_ = 0;
};

// Where long double is just double the reference accumulates one rounding per bounce.
const double kReferenceTolerance = std::numeric_limits<long double>::digits > 53 ? 1e-8 : 1e-6;

TargetPlane defaultPlane() { return fitTargetPlane(scene::CameraState{}, 16.0 / 9.0, kRadius); }

TargetPlane makePlane(double minX, double maxX, double minY, double maxY) {
    TargetPlane plane;
    plane.z = -7.0;
    plane.minX = minX;
    plane.maxX = maxX;
    plane.minY = minY;
    plane.maxY = maxY;
    return plane;
}

TargetMotion makeMotion(glm::dvec2 start, glm::dvec2 velocity) {
    TargetMotion motion;
    motion.start = start;
    motion.velocity = velocity;
    return motion;
}

void expectInside(const TargetPlane& plane, glm::dvec2 p, double t) {
    EXPECT_GE(p.x, plane.minX) << "t = " << t;
    EXPECT_LE(p.x, plane.maxX) << "t = " << t;
    EXPECT_GE(p.y, plane.minY) << "t = " << t;
    EXPECT_LE(p.y, plane.maxY) << "t = " << t;
}

template <typename F>
void expectInvalidArgumentNaming(F&& call, const std::string& parameter) {
    try {
        call();
        ADD_FAILURE() << "expected std::invalid_argument naming " << parameter;
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find(parameter), std::string::npos)
            << "message '" << e.what() << "' does not name " << parameter;
    }
}

// ---------------------------------------------------------------------------------------
// fitTargetPlane

// Projects world points with the renderer's own matrices (float, GL clip convention).
glm::vec3 toNdc(const scene::CameraState& camera, double aspect, glm::dvec3 world) {
    const glm::mat4 viewProjection =
        scene::projectionMatrix(camera, static_cast<float>(aspect)) * scene::viewMatrix(camera);
    const glm::vec4 clip = viewProjection * glm::vec4(glm::vec3(world), 1.0f);
    EXPECT_GT(clip.w, 0.0f) << "point behind the camera";
    return glm::vec3(clip) / clip.w;
}

TEST(FitTargetPlane, WholeCrossSectionVisibleAtInitialGazeAndFitTightly) {
    struct Case {
        scene::CameraState camera;
        double aspect;
    };
    std::vector<Case> cases;
    cases.push_back({scene::CameraState{}, 16.0 / 9.0});  // the study's setup
    cases.push_back({scene::CameraState{}, 4.0 / 3.0});
    cases.push_back({scene::CameraState{}, 3.0});  // wide: the vertical axis limits
    scene::CameraState offCentre;
    offCentre.eye = glm::vec3(2.0f, 3.0f, 0.5f);
    offCentre.verticalFovDeg = 75.0f;
    cases.push_back({offCentre, 16.0 / 9.0});

    for (const Case& c : cases) {
        SCOPED_TRACE("aspect " + std::to_string(c.aspect) + ", fov " + std::to_string(c.camera.verticalFovDeg));
        const TargetPlane plane = fitTargetPlane(c.camera, c.aspect, kRadius);
        EXPECT_LT(plane.z, c.camera.eye.z);
        float largestNdc = 0.0f;
        for (double x : {double(Layout::kClearMinX), double(Layout::kClearMaxX)}) {
            for (double y : {double(Layout::kClearMinY), double(Layout::kClearMaxY)}) {
                const glm::vec3 ndc = toNdc(c.camera, c.aspect, {x, y, plane.z});
                EXPECT_LE(std::fabs(ndc.x), 1.0f + 1e-5f) << "corner " << x << ", " << y;
                EXPECT_LE(std::fabs(ndc.y), 1.0f + 1e-5f) << "corner " << x << ", " << y;
                EXPECT_GT(ndc.z, -1.0f);
                EXPECT_LT(ndc.z, 1.0f);
                largestNdc = std::max({largestNdc, std::fabs(ndc.x), std::fabs(ndc.y)});
            }
        }
        // Tight: the plane sits where the view volume meets the walls, not anywhere beyond.
        EXPECT_GT(largestNdc, 1.0f - 1e-5f);
        // The centre's rectangle is strictly inside the picture.
        for (double x : {plane.minX, plane.maxX}) {
            for (double y : {plane.minY, plane.maxY}) {
                const glm::vec3 ndc = toNdc(c.camera, c.aspect, {x, y, plane.z});
                EXPECT_LT(std::fabs(ndc.x), 1.0f);
                EXPECT_LT(std::fabs(ndc.y), 1.0f);
            }
        }
    }
}

TEST(FitTargetPlane, DefaultCameraPlaneIsTheRadiusShrunkClearBoxBetweenRibs) {
    const TargetPlane plane = defaultPlane();
    EXPECT_DOUBLE_EQ(plane.minX, Layout::kClearMinX + kRadius);
    EXPECT_DOUBLE_EQ(plane.maxX, Layout::kClearMaxX - kRadius);
    EXPECT_DOUBLE_EQ(plane.minY, Layout::kClearMinY + kRadius);
    EXPECT_DOUBLE_EQ(plane.maxY, Layout::kClearMaxY - kRadius);
    // 16:9 at 60 degrees vertical: the side walls limit, 7.5 m / (tan 30deg * 16/9).
    EXPECT_NEAR(plane.z, -7.5 / (std::tan(kPi / 6.0) * 16.0 / 9.0), 1e-9);
    // The layout promises no rib in the target's plane; keep the whole sphere clear of them.
    for (int i = 0; i < Layout::kRibCount; ++i) {
        const double ribZ = Layout::kFirstRibZ - static_cast<double>(i) * Layout::kRibSpacing;
        EXPECT_GT(std::fabs(plane.z - ribZ), Layout::kRibThickness + kRadius) << "rib " << i;
    }
}

TEST(FitTargetPlane, RejectsBadArgumentsNamingTheParameter) {
    const scene::CameraState camera;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (double aspect : {0.0, -1.0, nan, std::numeric_limits<double>::infinity()}) {
        expectInvalidArgumentNaming([&] { fitTargetPlane(camera, aspect, kRadius); }, "aspect");
    }
    for (float fov : {0.0f, -10.0f, 180.0f, 200.0f, std::numeric_limits<float>::quiet_NaN()}) {
        scene::CameraState bad;
        bad.verticalFovDeg = fov;
        expectInvalidArgumentNaming([&] { fitTargetPlane(bad, 16.0 / 9.0, kRadius); }, "verticalFovDeg");
    }
    // Half the clear height is 4 m: a 4 m radius leaves no room to move.
    for (double radius : {0.0, -0.1, 4.0, 10.0, nan}) {
        expectInvalidArgumentNaming([&] { fitTargetPlane(camera, 16.0 / 9.0, radius); }, "radius");
    }
    EXPECT_NO_THROW(fitTargetPlane(camera, 16.0 / 9.0, 3.99));
}

// ---------------------------------------------------------------------------------------
// positionAt / velocityAt

TEST(BouncingTarget, DyadicMotionMatchesExactEventSimulationBitForBit) {
    // Every event time and position is a short binary fraction, so both the reference and
    // the closed form compute exactly and must agree to the last bit, hours in.
    const TargetPlane plane = makePlane(-8.0, 8.0, 0.5, 8.5);
    const TargetMotion motion = makeMotion({3.0, 5.0}, {4.0, -0.5});
    ReferenceTarget reference(plane, motion);
    for (double t = 0.0; t <= 36000.0; t += 37.375) {
        reference.advanceTo(t);
        const glm::dvec2 p = positionAt(plane, motion, t);
        const glm::dvec2 v = velocityAt(plane, motion, t);
        ASSERT_EQ(p.x, static_cast<double>(reference.x())) << "t = " << t;
        ASSERT_EQ(p.y, static_cast<double>(reference.y())) << "t = " << t;
        // Wall instants are excluded here (the reference reflects on arrival, as does the
        // closed form, but let the wall tests own that convention).
        if (p.x != plane.minX && p.x != plane.maxX) {
            ASSERT_EQ(v.x, static_cast<double>(reference.vx())) << "t = " << t;
        }
        if (p.y != plane.minY && p.y != plane.maxY) {
            ASSERT_EQ(v.y, static_cast<double>(reference.vy())) << "t = " << t;
        }
    }
    EXPECT_GT(reference.bouncesX(), 1000);
    EXPECT_GT(reference.bouncesY(), 1000);
}

TEST(BouncingTarget, HoursLaterStillInsideAndMatchesEventSimulation) {
    const TargetPlane plane = defaultPlane();
    const TargetMotion motion = spawnTarget(plane, 3.7, 42);
    ReferenceTarget reference(plane, motion);
    // Frames of a 120 Hz clock at several points up to ten hours, plus one odd instant.
    std::vector<double> times;
    for (double start : {0.0, 61.0, 3600.0, 36000.0}) {
        for (int k = 0; k < 240; ++k) times.push_back(start + k / 120.0);
    }
    times.push_back(36012.3456789);
    for (double t : times) {
        reference.advanceTo(t);
        const glm::dvec2 p = positionAt(plane, motion, t);
        expectInside(plane, p, t);
        ASSERT_NEAR(p.x, static_cast<double>(reference.x()), kReferenceTolerance) << "t = " << t;
        ASSERT_NEAR(p.y, static_cast<double>(reference.y()), kReferenceTolerance) << "t = " << t;
        const glm::dvec2 v = velocityAt(plane, motion, t);
        const bool nearWallX =
            std::fabs(p.x - plane.minX) < kReferenceTolerance || std::fabs(p.x - plane.maxX) < kReferenceTolerance;
        const bool nearWallY =
            std::fabs(p.y - plane.minY) < kReferenceTolerance || std::fabs(p.y - plane.maxY) < kReferenceTolerance;
        if (!nearWallX) {
            ASSERT_EQ(v.x, static_cast<double>(reference.vx())) << "t = " << t;
        }
        if (!nearWallY) {
            ASSERT_EQ(v.y, static_cast<double>(reference.vy())) << "t = " << t;
        }
    }
    EXPECT_GT(reference.bouncesX() + reference.bouncesY(), 10000);
}

TEST(BouncingTarget, NegativeTimeIsTheTimeReversedMotion) {
    const TargetPlane plane = defaultPlane();
    const TargetMotion motion = spawnTarget(plane, 5.3, 7);
    const TargetMotion reversed = makeMotion(motion.start, -motion.velocity);
    ReferenceTarget reference(plane, reversed);
    for (double back = 0.01; back < 600.0; back += 1.37) {
        reference.advanceTo(back);
        const glm::dvec2 p = positionAt(plane, motion, -back);
        expectInside(plane, p, -back);
        ASSERT_NEAR(p.x, static_cast<double>(reference.x()), kReferenceTolerance);
        ASSERT_NEAR(p.y, static_cast<double>(reference.y()), kReferenceTolerance);
        const glm::dvec2 v = velocityAt(plane, motion, -back);
        ASSERT_EQ(v.x, -static_cast<double>(reference.vx())) << "t = " << -back;
        ASSERT_EQ(v.y, -static_cast<double>(reference.vy())) << "t = " << -back;
    }
    EXPECT_GT(reference.bouncesX(), 50);
}

TEST(BouncingTarget, SeveralBouncesWithinOneDisplayFrame) {
    // 1 m wide box at 500 m/s: about four wall hits per 1/120 s frame on each axis.
    const TargetPlane plane = makePlane(0.0, 1.0, 2.0, 2.7);
    const TargetMotion motion = makeMotion({0.3, 2.2}, {500.0, -300.0});
    ReferenceTarget reference(plane, motion);
    const double frameStart = 1000.0 / 120.0;
    reference.advanceTo(frameStart);
    const int bouncesBefore = reference.bouncesX();
    constexpr int kSamples = 997;
    for (int i = 0; i <= kSamples; ++i) {
        const double t = frameStart + (1.0 / 120.0) * i / kSamples;
        reference.advanceTo(t);
        const glm::dvec2 p = positionAt(plane, motion, t);
        expectInside(plane, p, t);
        ASSERT_NEAR(p.x, static_cast<double>(reference.x()), kReferenceTolerance) << "t = " << t;
        ASSERT_NEAR(p.y, static_cast<double>(reference.y()), kReferenceTolerance) << "t = " << t;
        const glm::dvec2 v = velocityAt(plane, motion, t);
        if (std::fabs(p.x - plane.minX) > 1e-6 && std::fabs(p.x - plane.maxX) > 1e-6) {
            ASSERT_EQ(v.x, static_cast<double>(reference.vx())) << "t = " << t;
        }
    }
    EXPECT_GE(reference.bouncesX() - bouncesBefore, 4);
}

TEST(BouncingTarget, VelocityFlipsExactlyAtTheWallInstantAndIsTheOutgoingOneThere) {
    const TargetPlane plane = makePlane(0.0, 4.0, 0.0, 100.0);
    // 1e-12 s rather than the neighbouring double: one ulp of t can vanish in the rounding
    // of start + velocity * t and land on the wall instant itself.
    const auto before = [](double t) { return t - 1e-12; };
    const auto after = [](double t) { return t + 1e-12; };

    // Moving +x from 1: the max wall at t = 1.5, the min wall at t = 3.5, and going back in
    // time the min wall at t = -0.5.
    const TargetMotion forward = makeMotion({1.0, 50.0}, {2.0, 0.5});
    for (auto [wallTime, wallX, incoming] :
         {std::tuple{1.5, 4.0, 2.0}, std::tuple{3.5, 0.0, -2.0}, std::tuple{-0.5, 0.0, -2.0}}) {
        SCOPED_TRACE("wall instant " + std::to_string(wallTime));
        EXPECT_EQ(positionAt(plane, forward, wallTime).x, wallX);
        EXPECT_EQ(velocityAt(plane, forward, before(wallTime)).x, incoming);
        EXPECT_EQ(velocityAt(plane, forward, wallTime).x, -incoming);
        EXPECT_EQ(velocityAt(plane, forward, after(wallTime)).x, -incoming);
        EXPECT_EQ(velocityAt(plane, forward, wallTime).y, 0.5);  // the other axis untouched
        EXPECT_LT(std::fabs(positionAt(plane, forward, before(wallTime)).x - wallX), 1e-11);
        EXPECT_LT(std::fabs(positionAt(plane, forward, after(wallTime)).x - wallX), 1e-11);
    }

    // Moving -x from 1: the min wall at t = 0.5, the max wall at t = 2.5.
    const TargetMotion backward = makeMotion({1.0, 50.0}, {-2.0, 0.5});
    for (auto [wallTime, wallX, incoming] :
         {std::tuple{0.5, 0.0, -2.0}, std::tuple{2.5, 4.0, 2.0}, std::tuple{-1.5, 4.0, 2.0}}) {
        SCOPED_TRACE("wall instant " + std::to_string(wallTime) + ", moving -x");
        EXPECT_EQ(positionAt(plane, backward, wallTime).x, wallX);
        EXPECT_EQ(velocityAt(plane, backward, before(wallTime)).x, incoming);
        EXPECT_EQ(velocityAt(plane, backward, wallTime).x, -incoming);
        EXPECT_EQ(velocityAt(plane, backward, after(wallTime)).x, -incoming);
    }
}

TEST(BouncingTarget, AimedExactlyIntoACornerComesBackAlongTheSameLine) {
    // Reaches (4, 2) at t = 1 on both axes at once.
    const TargetPlane plane = makePlane(0.0, 4.0, 0.0, 2.0);
    const TargetMotion motion = makeMotion({1.0, 0.5}, {3.0, 1.5});
    EXPECT_EQ(positionAt(plane, motion, 1.0), glm::dvec2(4.0, 2.0));
    EXPECT_EQ(velocityAt(plane, motion, std::nextafter(1.0, 0.0)), glm::dvec2(3.0, 1.5));
    EXPECT_EQ(velocityAt(plane, motion, 1.0), glm::dvec2(-3.0, -1.5));
    for (double d : {0.0078125, 0.25, 0.5, 0.75, 1.0}) {
        EXPECT_EQ(positionAt(plane, motion, 1.0 + d), positionAt(plane, motion, 1.0 - d)) << "d = " << d;
        EXPECT_EQ(velocityAt(plane, motion, 1.0 + d), glm::dvec2(-3.0, -1.5)) << "d = " << d;
    }
    // Back at the start at t = 2, then on to the opposite corner (0, 0) at t = 1 + 4/3.
    EXPECT_EQ(positionAt(plane, motion, 2.0), motion.start);
    const glm::dvec2 farCorner = positionAt(plane, motion, 1.0 + 4.0 / 3.0);
    EXPECT_NEAR(farCorner.x, 0.0, 1e-14);
    EXPECT_NEAR(farCorner.y, 0.0, 1e-14);

    // The same on the fitted plane, with awkward numbers: aim from the middle at the top
    // right corner; after it the path stays on the incoming line.
    const TargetPlane fitted = defaultPlane();
    const glm::dvec2 middle(0.5 * (fitted.minX + fitted.maxX), 0.5 * (fitted.minY + fitted.maxY));
    const glm::dvec2 corner(fitted.maxX, fitted.maxY);
    const glm::dvec2 direction = glm::normalize(corner - middle);
    const TargetMotion aimed = makeMotion(middle, 4.0 * direction);
    const double cornerTime = glm::length(corner - middle) / 4.0;
    for (double d : {0.01, 0.3, 0.9 * cornerTime}) {
        const glm::dvec2 back = positionAt(fitted, aimed, cornerTime + d);
        const glm::dvec2 there = positionAt(fitted, aimed, cornerTime - d);
        EXPECT_NEAR(back.x, there.x, 1e-12) << "d = " << d;
        EXPECT_NEAR(back.y, there.y, 1e-12) << "d = " << d;
        // Signed distance of the point from the incoming line.
        const glm::dvec2 offset = back - middle;
        EXPECT_NEAR(offset.x * direction.y - offset.y * direction.x, 0.0, 1e-12);
        const glm::dvec2 v = velocityAt(fitted, aimed, cornerTime + d);
        EXPECT_EQ(v, -aimed.velocity) << "d = " << d;
    }
}

TEST(BouncingTarget, SpeedIsConservedExactly) {
    const TargetPlane plane = defaultPlane();
    for (std::uint64_t seed = 0; seed < 20; ++seed) {
        const TargetMotion motion = spawnTarget(plane, 0.5 + static_cast<double>(seed), seed);
        const double speed = glm::length(motion.velocity);
        for (double t : {-36000.0, -3.3, 0.0, 0.1, 7.77, 123.456, 3600.0, 36000.0, 1e7}) {
            const glm::dvec2 v = velocityAt(plane, motion, t);
            ASSERT_EQ(std::fabs(v.x), std::fabs(motion.velocity.x)) << "t = " << t;
            ASSERT_EQ(std::fabs(v.y), std::fabs(motion.velocity.y)) << "t = " << t;
            ASSERT_EQ(glm::length(v), speed) << "t = " << t;
        }
    }
}

TEST(BouncingTarget, NeverLeavesTheBoxForExtremeTimesAndSpeeds) {
    const TargetPlane plane = defaultPlane();
    for (std::uint64_t seed = 0; seed < 50; ++seed) {
        for (double speed : {0.001, 3.0, 1e4}) {
            const TargetMotion motion = spawnTarget(plane, speed, seed);
            for (double t : {-1e9, -36000.0, -1e-12, 0.0, 1e-300, 36000.0, 36000.0 + 1.0 / 120.0, 1e6, 1e9}) {
                expectInside(plane, positionAt(plane, motion, t), t);
            }
        }
    }
    // min + (max - min) rounds to above max for these bounds: the wall instant must still
    // report a position inside.
    const TargetPlane awkward = makePlane(-9.49, 0.83, 0.0, 1.0);
    const double length = awkward.maxX - awkward.minX;
    ASSERT_GT(awkward.minX + length, awkward.maxX) << "the case no longer exercises rounding";
    const TargetMotion fromMinWall = makeMotion({awkward.minX, 0.5}, {1.0, 0.0});
    EXPECT_EQ(positionAt(awkward, fromMinWall, length).x, awkward.maxX);
}

TEST(BouncingTarget, ZeroLengthAxisPinsTheCentreWithoutDividingByZero) {
    const TargetPlane slot = makePlane(-1.0, 3.0, 2.0, 2.0);
    const TargetMotion motion = makeMotion({0.0, 2.0}, {1.0, 5.0});
    for (double t : {-10.0, 0.0, 0.5, 1.0, 3.0, 1e6}) {
        const glm::dvec2 p = positionAt(slot, motion, t);
        const glm::dvec2 v = velocityAt(slot, motion, t);
        EXPECT_EQ(p.y, 2.0) << "t = " << t;
        EXPECT_EQ(v.y, 0.0) << "t = " << t;
        EXPECT_TRUE(std::isfinite(p.x)) << "t = " << t;
        EXPECT_EQ(std::fabs(v.x), 1.0) << "t = " << t;
    }
    EXPECT_EQ(positionAt(slot, motion, 3.0).x, 3.0);  // the x axis still bounces normally
    const TargetPlane point = makePlane(1.0, 1.0, 2.0, 2.0);
    EXPECT_EQ(positionAt(point, motion, 12.5), glm::dvec2(1.0, 2.0));
    EXPECT_EQ(velocityAt(point, motion, 12.5), glm::dvec2(0.0, 0.0));
}

TEST(BouncingTarget, RejectsNonFiniteTime) {
    const TargetPlane plane = defaultPlane();
    // 1e308 s is finite, but at 1e10 m/s the unfolded line overflows.
    const TargetMotion motion = makeMotion({0.0, 4.0}, {1e10, 1.0});
    for (double t : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), 1e308}) {
        expectInvalidArgumentNaming([&] { positionAt(plane, motion, t); }, "t");
        expectInvalidArgumentNaming([&] { velocityAt(plane, motion, t); }, "t");
    }
}

// ---------------------------------------------------------------------------------------
// spawnTarget

TEST(SpawnTarget, SameSeedSameBitsDifferentSeedsDiffer) {
    const TargetPlane plane = defaultPlane();
    const TargetMotion a = spawnTarget(plane, 4.0, 12345);
    const TargetMotion b = spawnTarget(plane, 4.0, 12345);
    EXPECT_EQ(a.start, b.start);
    EXPECT_EQ(a.velocity, b.velocity);

    std::set<std::pair<double, double>> starts, velocities;
    for (std::uint64_t seed = 0; seed < 200; ++seed) {
        const TargetMotion m = spawnTarget(plane, 4.0, seed);
        starts.insert({m.start.x, m.start.y});
        velocities.insert({m.velocity.x, m.velocity.y});
    }
    EXPECT_EQ(starts.size(), 200u);
    EXPECT_EQ(velocities.size(), 200u);
}

TEST(SpawnTarget, GoldenValuesPinTheGeneratorAcrossMachines) {
    // Pure integer PRNG, fma, sqrt and division: these bits must come out on every IEEE-754
    // machine and standard library. A change here changes every logged session's target.
    const TargetPlane plane = makePlane(-7.15, 7.15, 0.85, 8.15);
    const TargetMotion m = spawnTarget(plane, 4.0, 20240601);
    EXPECT_EQ(m.start.x, -0x1.5b684956178f3p+2);
    EXPECT_EQ(m.start.y, 0x1.521ded097ef65p+2);
    EXPECT_EQ(m.velocity.x, -0x1.7dd3d52fa5051p+1);
    EXPECT_EQ(m.velocity.y, -0x1.551a90aa2d33ap+1);
}

TEST(SpawnTarget, StartsAwayFromWallsAndMovesDiagonallyEnough) {
    const TargetPlane plane = defaultPlane();
    const double width = plane.maxX - plane.minX, height = plane.maxY - plane.minY;
    int quadrants[4] = {0, 0, 0, 0};
    double smallestAxisAngle = kPi;
    for (std::uint64_t seed = 0; seed < 2000; ++seed) {
        const TargetMotion m = spawnTarget(plane, 6.0, seed);
        ASSERT_GE(m.start.x, plane.minX + 0.1 * width - 1e-12);
        ASSERT_LE(m.start.x, plane.maxX - 0.1 * width + 1e-12);
        ASSERT_GE(m.start.y, plane.minY + 0.1 * height - 1e-12);
        ASSERT_LE(m.start.y, plane.maxY - 0.1 * height + 1e-12);
        ASSERT_NEAR(glm::length(m.velocity), 6.0, 1e-12);
        const double angleFromXAxis = std::atan2(std::fabs(m.velocity.y), std::fabs(m.velocity.x));
        const double angleFromNearestAxis = std::min(angleFromXAxis, kPi / 2 - angleFromXAxis);
        smallestAxisAngle = std::min(smallestAxisAngle, angleFromNearestAxis);
        ++quadrants[(m.velocity.x < 0 ? 1 : 0) + (m.velocity.y < 0 ? 2 : 0)];
    }
    EXPECT_GE(smallestAxisAngle, 10.0 * kPi / 180.0 - 1e-12);
    EXPECT_LT(smallestAxisAngle, 11.0 * kPi / 180.0);  // the excluded band is no wider
    for (int count : quadrants) {
        EXPECT_GT(count, 400);  // about 500 each: uniform over the four diagonal sectors
    }
}

TEST(SpawnTarget, RejectsBadArguments) {
    const TargetPlane plane = defaultPlane();
    expectInvalidArgumentNaming([&] { spawnTarget(plane, -1.0, 0); }, "speed");
    expectInvalidArgumentNaming([&] { spawnTarget(plane, std::numeric_limits<double>::quiet_NaN(), 0); }, "speed");
    expectInvalidArgumentNaming([&] { spawnTarget(makePlane(1.0, 0.0, 0.0, 1.0), 1.0, 0); }, "plane");
    EXPECT_NO_THROW(spawnTarget(makePlane(1.0, 1.0, 0.0, 1.0), 0.0, 0));
}

// ---------------------------------------------------------------------------------------
// targetObject

TEST(TargetObject, DescribesTheSphereForTheRenderer) {
    const TargetPlane plane = defaultPlane();
    const TargetMotion motion = spawnTarget(plane, 5.0, 99);
    const double t = 17.25;
    const scene::ObjectState object = targetObject(plane, motion, t, kRadius);
    const glm::dvec2 p = positionAt(plane, motion, t);
    const glm::dvec2 v = velocityAt(plane, motion, t);
    EXPECT_EQ(object.id, scene::kIdTarget);
    EXPECT_EQ(object.shape, scene::Shape::Sphere);
    EXPECT_EQ(object.position, glm::vec3(float(p.x), float(p.y), float(plane.z)));
    EXPECT_EQ(object.velocity, glm::vec3(float(v.x), float(v.y), 0.0f));
    EXPECT_EQ(object.halfExtents, glm::vec3(float(kRadius)));
    EXPECT_EQ(object.angularVelocity, glm::vec3(0.0f));
    expectInvalidArgumentNaming([&] { targetObject(plane, motion, t, 0.0); }, "radius");
}

// ---------------------------------------------------------------------------------------
// ray queries

TEST(RaySphereHit, HeadOnHitsTheNearSurfaceWhateverTheDirectionLength) {
    const glm::dvec3 centre(0.0, 4.5, -10.0);
    const glm::dvec3 eye(0.0, 4.5, 0.0);
    for (double length : {1.0, 0.001, 250.0}) {
        const auto hit = raySphereHit(eye, {0.0, 0.0, -length}, centre, 1.0);
        ASSERT_TRUE(hit.has_value());
        EXPECT_NEAR(*hit, 9.0, 1e-12);
    }
}

TEST(RaySphereHit, MissesBehindBesideAndJustPast) {
    const glm::dvec3 eye(0.0, 0.0, 0.0);
    const glm::dvec3 ahead(0.0, 0.0, -1.0);
    EXPECT_FALSE(raySphereHit(eye, ahead, {0.0, 0.0, 10.0}, 1.0).has_value());  // behind
    EXPECT_FALSE(raySphereHit(eye, ahead, {3.0, 0.0, -10.0}, 1.0).has_value());
    // A small distant target, grazed just inside and just outside its rim.
    const double radius = 0.01;
    EXPECT_TRUE(raySphereHit(eye, ahead, {radius * (1 - 1e-6), 0.0, -1000.0}, radius));
    EXPECT_FALSE(raySphereHit(eye, ahead, {radius * (1 + 1e-6), 0.0, -1000.0}, radius));
    // Exactly tangent counts as a hit, at the touching point.
    const auto tangent = raySphereHit({1.0, 0.0, 0.0}, ahead, {0.0, 0.0, -10.0}, 1.0);
    ASSERT_TRUE(tangent.has_value());
    EXPECT_NEAR(*tangent, 10.0, 1e-12);
}

TEST(RaySphereHit, FromInsideReturnsTheExitAndFromTheSurfaceZero) {
    const auto inside = raySphereHit({0.0, 0.0, 0.0}, {1.0, 1.0, 0.0}, {0.0, 0.0, 0.0}, 2.0);
    ASSERT_TRUE(inside.has_value());
    EXPECT_NEAR(*inside, 2.0, 1e-12);
    const auto surface = raySphereHit({0.0, 0.0, 2.0}, {0.0, 0.0, -1.0}, {0.0, 0.0, 0.0}, 2.0);
    ASSERT_TRUE(surface.has_value());
    EXPECT_NEAR(*surface, 0.0, 1e-12);
}

TEST(RaySphereHit, RejectsBadArguments) {
    expectInvalidArgumentNaming([] { raySphereHit({}, {0.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, 1.0); }, "dir");
    expectInvalidArgumentNaming([] { raySphereHit({}, {0.0, 0.0, -1.0}, {0.0, 0.0, -5.0}, -1.0); }, "radius");
}

TEST(AngleBetweenRayAndPoint, RightAnglesAndTinyNearMisses) {
    const glm::dvec3 eye(1.0, 2.0, 3.0);
    const glm::dvec3 ahead(0.0, 0.0, -2.0);
    EXPECT_NEAR(angleBetweenRayAndPoint(eye, ahead, eye + glm::dvec3(0, 0, -5)), 0.0, 1e-15);
    EXPECT_NEAR(angleBetweenRayAndPoint(eye, ahead, eye + glm::dvec3(4, 0, 0)), kPi / 2, 1e-15);
    EXPECT_NEAR(angleBetweenRayAndPoint(eye, ahead, eye + glm::dvec3(0, 0, 9)), kPi, 1e-15);
    EXPECT_NEAR(angleBetweenRayAndPoint(eye, ahead, eye + glm::dvec3(0, 7, -7)), kPi / 4, 1e-15);
    // A 1e-9 rad miss at 7 m: acos of the cosine would round this to 0.
    const double tiny = angleBetweenRayAndPoint(eye, ahead, eye + glm::dvec3(7e-9, 0, -7));
    EXPECT_NEAR(tiny, 1e-9, 1e-15);
    expectInvalidArgumentNaming([&] { angleBetweenRayAndPoint(eye, ahead, eye); }, "point");
    expectInvalidArgumentNaming([&] { angleBetweenRayAndPoint(eye, {}, eye + ahead); }, "dir");
}

}  // namespace
}  // namespace warplab::physics
