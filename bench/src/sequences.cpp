#include "bench/sequences.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "physics/target_scene.h"
#include "physics/bouncing_target.h"
#include "scene/hangar_layout.h"

namespace warplab::game {
namespace {

using Layout = scene::HangarLayout;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegrees = kPi / 180.0;

// Long enough for a few bounces and sweeps, short enough that the bench's ground-truth
// renders of every method stay affordable.
constexpr double kBaseDuration = 3.0;
constexpr double kTargetRadius = 0.35;  // the shooter's target, so errors compare with studies

// value = amplitude * sin(2 pi t / period + phase). The time is reduced modulo the period
// first (fmod is exact), so the angle stays small and the rounding does not grow with t.
struct Sinusoid {
    double amplitude;
    double period;
    double phase = 0.0;

    double angle(double t) const { return 2.0 * kPi * (std::fmod(t, period) / period) + phase; }
    double value(double t) const { return amplitude * std::sin(angle(t)); }
    double rate(double t) const { return amplitude * (2.0 * kPi / period) * std::cos(angle(t)); }
};

scene::CameraState restingCamera(const SequenceConfig& config) {
    scene::CameraState camera;
    camera.eye = {Layout::kEyeX, Layout::kEyeY, Layout::kEyeZ};
    camera.verticalFovDeg = config.verticalFovDeg;
    return camera;
}

physics::TargetScene shooterTarget(const SequenceConfig& config, double speed) {
    physics::TargetSceneConfig shooter;
    shooter.verticalFovDeg = config.verticalFovDeg;
    shooter.aspect = config.aspect;
    shooter.targetRadius = kTargetRadius;
    shooter.targetSpeed = speed;
    shooter.seed = config.seed;
    return physics::TargetScene(shooter);
}

class ScriptedSequence : public BenchSequence {
public:
    explicit ScriptedSequence(const SequenceConfig& config) : config_(config) {}
    double duration() const override { return kBaseDuration * config_.durationScale; }

protected:
    SequenceConfig config_;
};

// ---------------------------------------------------------------------------------------

class PanSequence final : public ScriptedSequence {
public:
    explicit PanSequence(const SequenceConfig& config)
        : ScriptedSequence(config), target_(shooterTarget(config, 4.0)) {}

    std::string name() const override { return "pan"; }
    std::string description() const override {
        return "camera yaw sweeps +-25 deg (2.5 s), pitch +-6 deg; target bouncing at 4 m/s";
    }

    scene::FrameDescription at(double t) const override {
        scene::FrameDescription frame;
        frame.camera = restingCamera(config_);
        frame.camera.yaw = static_cast<float>(kYaw.value(t));
        frame.camera.pitch = static_cast<float>(kPitch.value(t));
        frame.scene = target_.snapshot(t);
        return frame;
    }

private:
    // Peak yaw rate 25 deg * 2 pi / 2.5 s ~ 63 deg/s: ~4 deg, some 70 pixels at 1080p, per
    // 1/15 s, so sample-and-hold at 15 Hz is plainly wrong. The pitch period is not a
    // rational multiple of the yaw's that repeats within the run, so the path is no loop.
    static constexpr Sinusoid kYaw{25.0 * kDegrees, 2.5};
    static constexpr Sinusoid kPitch{6.0 * kDegrees, 1.9};
    physics::TargetScene target_;
};

// ---------------------------------------------------------------------------------------

class TrackSequence final : public ScriptedSequence {
public:
    explicit TrackSequence(const SequenceConfig& config)
        : ScriptedSequence(config), target_(shooterTarget(config, 3.0)) {}

    std::string name() const override { return "track"; }
    std::string description() const override {
        return "camera follows the target (3 m/s) with an 80 ms reaction lag, like a player";
    }

    scene::FrameDescription at(double t) const override {
        scene::FrameDescription frame;
        frame.camera = restingCamera(config_);
        // A player aims where they last saw the target, so the view trails it by a reaction
        // time and the target drifts off the reticle whenever it turns at a wall.
        const physics::TargetPlane& plane = target_.plane();
        const glm::dvec2 seen = physics::positionAt(plane, target_.motion(), t - kReactionLag);
        const glm::dvec3 aim = glm::dvec3(seen, plane.z) - glm::dvec3(frame.camera.eye);
        frame.camera.yaw = static_cast<float>(std::atan2(aim.x, -aim.z));
        frame.camera.pitch = static_cast<float>(std::atan2(aim.y, std::hypot(aim.x, aim.z)));
        frame.scene = target_.snapshot(t);
        return frame;
    }

private:
    static constexpr double kReactionLag = 0.080;  // seconds
    physics::TargetScene target_;
};

// ---------------------------------------------------------------------------------------

class TranslateSequence final : public ScriptedSequence {
public:
    explicit TranslateSequence(const SequenceConfig& config)
        : ScriptedSequence(config), target_(shooterTarget(config, 3.0)) {}

    std::string name() const override { return "translate"; }
    std::string description() const override {
        return "eye slides +-1.5 m sideways (3 s) and +-0.3 m vertically; disocclusion";
    }

    scene::FrameDescription at(double t) const override {
        // The studies never move the eye; the bench does, because only a moving viewpoint
        // uncovers what was hidden behind the crates, the ribs and the target.
        scene::FrameDescription frame;
        frame.camera = restingCamera(config_);
        frame.camera.eye.x = static_cast<float>(Layout::kEyeX + kSway.value(t));
        frame.camera.eye.y = static_cast<float>(Layout::kEyeY + kBob.value(t));
        frame.scene = target_.snapshot(t);
        return frame;
    }

private:
    static constexpr Sinusoid kSway{1.5, 3.0};
    static constexpr Sinusoid kBob{0.3, 2.2};
    physics::TargetScene target_;
};

// ---------------------------------------------------------------------------------------

// The falling spheres of the click game (seed: Yang et al. 2011), scripted: each sphere
// bounces elastically on the floor forever, so its height is a parabola folded by the
// bounce period, exact at any t with no integrator. No sphere meets another: each keeps to
// its own x lane.
constexpr double kGravity = 9.81;
// The floor the spheres bounce on: the clear box's bottom (the top of the ribs' floor sills),
// so they stay inside the box the target keeps to. It lies 0.44 m above the deck plates, so
// the spheres land on an invisible step; the bench judges motion, not realism.
constexpr float kFloorY = Layout::kClearMinY;
// Extent of the spheres along z: in the bay between the first two ribs, in front of the
// camera, clear of both ribs' sills.
constexpr double kSpheresNearZ = -6.6;
constexpr double kSpheresFarZ = -10.4;
constexpr double kLaneWidth = 1.6;
constexpr double kFirstLaneX = -6.4;  // eight lanes: x in [-6.4, 6.4], all in view

struct FallingSphere {
    float radius;
    double dropHeight;  // apex of the centre above its floor contact, metres
    double phase;  // fraction of a bounce period at t = 0 (0 = leaving the floor)
    glm::dvec2 driftStart;  // (x, z) at t = 0
    glm::dvec2 drift;  // (x, z) velocity, m/s; at least 0.08 per axis, never zero
};

const std::array<FallingSphere, 8> kSpheres{{
    {0.30f, 3.2, 0.000, {-5.6, -7.5}, {0.12, -0.20}},
    {0.45f, 2.4, 0.375, {-4.0, -9.2}, {-0.10, 0.25}},
    {0.25f, 3.8, 0.750, {-2.4, -8.0}, {0.15, 0.18}},
    {0.40f, 2.0, 0.125, {-0.8, -9.6}, {-0.14, -0.22}},
    {0.50f, 3.0, 0.500, {0.8, -7.2}, {0.08, 0.24}},
    {0.35f, 2.7, 0.875, {2.4, -8.6}, {-0.16, -0.15}},
    {0.28f, 3.5, 0.250, {4.0, -9.0}, {0.11, 0.21}},
    {0.42f, 2.2, 0.625, {5.6, -7.8}, {-0.09, -0.23}},
}};

const glm::vec3 kRed{0.85f, 0.15f, 0.12f};
const glm::vec3 kGreen{0.15f, 0.75f, 0.2f};

struct Bounce {
    double height;  // of the centre above its floor contact
    double velocity;  // vertical
};

// Elastic bouncing from rest at dropHeight: the fall takes sqrt(2h/g), one period is two of
// those, and within a period the centre follows the parabola about the apex. At a contact
// instant the velocity is the one after it (upwards), as the target's is after a wall.
Bounce bounceAt(double dropHeight, double phase, double t) {
    const double fallTime = std::sqrt(2.0 * dropHeight / kGravity);
    const double period = 2.0 * fallTime;
    double sinceContact = std::fmod(std::fma(phase, period, t), period);
    // A tiny negative remainder may round up to the full period: that is the instant just
    // before a contact, which tau = fallTime below describes correctly.
    if (sinceContact < 0.0) sinceContact += period;
    const double sinceApex = sinceContact - fallTime;
    const double height = dropHeight - 0.5 * kGravity * sinceApex * sinceApex;
    return {std::max(height, 0.0), -kGravity * sinceApex};
}

// Where the sphere's centre may drift: its lane, and the spheres' z extent, both shrunk by
// the radius. The target's fold is the same closed form in any plane; its "y" is our z.
physics::TargetPlane driftBox(std::size_t lane, double radius) {
    physics::TargetPlane box;
    box.minX = kFirstLaneX + kLaneWidth * static_cast<double>(lane) + radius;
    box.maxX = kFirstLaneX + kLaneWidth * static_cast<double>(lane + 1) - radius;
    box.minY = kSpheresFarZ + radius;
    box.maxY = kSpheresNearZ - radius;
    return box;
}

class SpheresSequence final : public ScriptedSequence {
public:
    using ScriptedSequence::ScriptedSequence;

    std::string name() const override { return "spheres"; }
    std::string description() const override {
        return "8 red/green spheres bouncing under gravity in their own lanes; fixed camera";
    }

    scene::FrameDescription at(double t) const override {
        scene::FrameDescription frame;
        frame.camera = restingCamera(config_);
        frame.camera.pitch = static_cast<float>(-10.0 * kDegrees);  // the floor in view
        frame.scene.time = t;
        for (std::size_t i = 0; i < kSpheres.size(); ++i) {
            const FallingSphere& sphere = kSpheres[i];
            const physics::TargetPlane box = driftBox(i, sphere.radius);
            physics::TargetMotion motion;
            motion.start = sphere.driftStart;
            motion.velocity = sphere.drift;
            const glm::dvec2 xz = physics::positionAt(box, motion, t);
            const glm::dvec2 xzVelocity = physics::velocityAt(box, motion, t);
            const Bounce bounce = bounceAt(sphere.dropHeight, sphere.phase, t);

            // Rounding the centre to float must not sink it into the floor.
            const double contact = double(kFloorY) + double(sphere.radius);
            float y = static_cast<float>(contact + bounce.height);
            if (double(y) < contact) y = std::nextafter(y, std::numeric_limits<float>::max());

            scene::ObjectState object;
            object.id = scene::kIdFirstSphere + static_cast<std::uint32_t>(i);
            object.shape = scene::Shape::Sphere;
            object.position = {static_cast<float>(xz.x), y, static_cast<float>(xz.y)};
            object.halfExtents = glm::vec3(sphere.radius);
            object.velocity = glm::vec3(glm::dvec3(xzVelocity.x, bounce.velocity, xzVelocity.y));
            object.colour = i % 2 == 0 ? kRed : kGreen;
            frame.scene.objects.push_back(object);
        }
        return frame;
    }
};

// ---------------------------------------------------------------------------------------

// The windmill blades of seed 000 Figure 4: thin geometry moving many times its own width per
// frame, which a search along the motion easily steps over.
class ThinSequence final : public ScriptedSequence {
public:
    explicit ThinSequence(const SequenceConfig& config)
        : ScriptedSequence(config), target_(shooterTarget(config, 3.0)) {}

    std::string name() const override { return "thin"; }
    std::string description() const override {
        return "3.2 m x 8 cm bar spinning at 1.5 rev/s about the view axis at 5 m; target behind";
    }

    scene::FrameDescription at(double t) const override {
        scene::FrameDescription frame;
        frame.camera = restingCamera(config_);
        frame.scene = target_.snapshot(t);

        // The quaternion of a turn by theta is periodic in 2 turns, not one; reducing t
        // modulo two turns keeps it continuous (no sign flip at a wrap) and the angle small.
        const double twoTurns = 2.0 / kTurnsPerSecond;
        double sinceStart = std::fmod(t, twoTurns);
        if (sinceStart < 0.0) sinceStart += twoTurns;
        const double halfAngle = 0.5 * kStartAngle + kPi * kTurnsPerSecond * sinceStart;

        scene::ObjectState bar;
        bar.id = scene::kIdSpinningBar;
        bar.shape = scene::Shape::Box;
        bar.position = {static_cast<float>(kSlide.value(t)), Layout::kEyeY, -5.0f};
        bar.velocity = {static_cast<float>(kSlide.rate(t)), 0.0f, 0.0f};
        bar.orientation =
            glm::quat(static_cast<float>(std::cos(halfAngle)), 0.0f, 0.0f, static_cast<float>(std::sin(halfAngle)));
        bar.angularVelocity = {0.0f, 0.0f, static_cast<float>(2.0 * kPi * kTurnsPerSecond)};
        bar.halfExtents = {1.6f, 0.04f, 0.04f};
        bar.colour = {0.95f, 0.8f, 0.2f};
        frame.scene.objects.push_back(bar);
        return frame;
    }

private:
    static constexpr double kTurnsPerSecond = 1.5;  // tips at ~15 m/s
    static constexpr double kStartAngle = 0.3;  // radians; not axis-aligned at t = 0
    static constexpr Sinusoid kSlide{0.6, 4.0};  // slow sideways drift of the hub
    physics::TargetScene target_;
};

// ---------------------------------------------------------------------------------------

void require(bool ok, const char* field, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("SequenceConfig.") + field + ": " + what);
}

}  // namespace

std::vector<std::string> sequenceNames() { return {"pan", "track", "translate", "spheres", "thin"}; }

std::unique_ptr<BenchSequence> makeSequence(const std::string& name, const SequenceConfig& config) {
    require(std::isfinite(config.aspect) && config.aspect > 0.0, "aspect", "must be positive and finite");
    require(config.verticalFovDeg > 0.0f && config.verticalFovDeg < 180.0f, "verticalFovDeg",
            "must lie in (0, 180) degrees");
    require(std::isfinite(config.durationScale) && config.durationScale > 0.0, "durationScale",
            "must be positive and finite");

    if (name == "pan") return std::make_unique<PanSequence>(config);
    if (name == "track") return std::make_unique<TrackSequence>(config);
    if (name == "translate") return std::make_unique<TranslateSequence>(config);
    if (name == "spheres") return std::make_unique<SpheresSequence>(config);
    if (name == "thin") return std::make_unique<ThinSequence>(config);

    std::string valid;
    for (const std::string& known : sequenceNames()) {
        valid += (valid.empty() ? "" : ", ") + known;
    }
    throw std::invalid_argument("unknown bench sequence '" + name + "' (valid: " + valid + ")");
}

}  // namespace warplab::game
