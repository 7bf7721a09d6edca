// Scripted, deterministic sequences for `warplab bench` (DESIGN "Speed against error"): each
// is a pure function from display time to what the frame shows, so every method and the
// ground-truth render see exactly the same instant, and a run repeats bit for bit.
//
// Object velocities and angular velocities are the exact time derivatives of positions and
// orientations: the velocity buffer and the warp's extrapolation are only as right as they
// are. At a bounce instant the velocity is the one after the bounce, as for the target.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace warplab::game {

struct SequenceConfig {
    double aspect = 16.0 / 9.0;  // width / height; fits the target's plane to the view
    float verticalFovDeg = 60.0f;
    double durationScale = 1.0;  // stretches the run, never the motion (speeds stay put)
    std::uint64_t seed = 1;  // the target's spawn; the rest is scripted
};

class BenchSequence {
public:
    virtual ~BenchSequence() = default;
    virtual std::string name() const = 0;
    virtual std::string description() const = 0;  // one line for the bench summary
    virtual double duration() const = 0;  // seconds of display time
    // Exact for any t (also outside [0, duration]); snapshot.time = t.
    virtual scene::FrameDescription at(double t) const = 0;
};

// "pan", "track", "translate", "spheres", "thin", in the order the bench runs them.
std::vector<std::string> sequenceNames();

// Throws std::invalid_argument naming an unknown name (and listing the valid ones), or the
// config field that is out of range (aspect, verticalFovDeg, durationScale).
std::unique_ptr<BenchSequence> makeSequence(const std::string& name, const SequenceConfig& config);

}  // namespace warplab::game
