// The plain description of what a frame shows: the camera and the moving objects at one
// instant. `game` and the bench sequences produce it, `renderer` draws it; nothing here
// touches OpenGL, so physics, games and scoring can use the same camera maths without a
// context.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace warplab::scene {

// Object ids written to the id buffer. 0 is "nothing" (sky / far plane).
enum ObjectId : std::uint32_t {
    kIdNone = 0,
    kIdHangar = 1,
    kIdTarget = 2,
    kIdSpinningBar = 3,  // the bench's thin fast-rotating object (sequence "thin")
    kIdFirstSphere = 16,  // falling spheres of the click game: kIdFirstSphere + index
};

// First-person camera: the eye never translates in the studies, the mouse turns it.
// yaw = 0, pitch = 0 looks down the hallway (-z); positive yaw turns right (towards +x),
// positive pitch looks up. Angles in radians.
struct CameraState {
    glm::vec3 eye{0.0f, 4.5f, 0.0f};
    float yaw = 0.0f;
    float pitch = 0.0f;
    float verticalFovDeg = 60.0f;
    float nearPlane = 0.05f;
    float farPlane = 200.0f;
};

enum class Shape : std::uint8_t { Sphere, Box };

// A rigid body as the renderer needs it. Velocities are world-space; a fragment at world
// point p moves with velocity + cross(angularVelocity, p - position) (seed 004 section 5.2.3),
// which is what the velocity buffer stores.
struct ObjectState {
    std::uint32_t id = kIdTarget;
    Shape shape = Shape::Sphere;
    glm::vec3 position{0.0f};
    glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};
    glm::vec3 halfExtents{0.35f};  // sphere: x is the radius; box: half size per axis
    glm::vec3 velocity{0.0f};
    glm::vec3 angularVelocity{0.0f};  // radians per second, world axes
    glm::vec3 colour{0.9f, 0.25f, 0.15f};
};

struct SceneSnapshot {
    double time = 0.0;  // scene time this snapshot depicts, seconds
    std::vector<ObjectState> objects;
};

// What one rendered frame depicts.
struct FrameDescription {
    CameraState camera;
    SceneSnapshot scene;
};

}  // namespace warplab::scene
