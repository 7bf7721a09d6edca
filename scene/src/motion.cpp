#include "scene/motion.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace warplab::scene {

glm::mat4 modelMatrix(const ObjectState& o) {
    const glm::vec3 scale = o.shape == Shape::Sphere ? glm::vec3(o.halfExtents.x) : o.halfExtents;
    return glm::translate(glm::mat4(1.0f), o.position) * glm::mat4_cast(o.orientation) *
        glm::scale(glm::mat4(1.0f), scale);
}

ObjectState objectAt(const ObjectState& object, double fromTime, const SceneSnapshot& other) {
    for (const auto& o : other.objects)
        if (o.id == object.id) return o;
    const float dt = static_cast<float>(other.time - fromTime);
    ObjectState moved = object;
    moved.position += object.velocity * dt;
    const float speed = glm::length(object.angularVelocity);
    if (speed > 0.0f)
        moved.orientation =
            glm::normalize(glm::angleAxis(speed * dt, object.angularVelocity / speed) * object.orientation);
    return moved;
}

}  // namespace warplab::scene
