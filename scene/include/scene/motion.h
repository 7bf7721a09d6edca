// Rigid motion of the scene's objects between two instants, for the passes that relate one
// frame to another (flow fields, scene-assisted reprojection). Plain GLM, no GL.
#pragma once

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace warplab::scene {

// The model matrix an object is drawn with: translate * rotate * scale (a sphere's radius is
// halfExtents.x).
glm::mat4 modelMatrix(const ObjectState& object);

// `object` (depicted at fromTime) as it is in `other`, a snapshot of another instant: the
// object with the same id there; where `other` lacks it (spawned or removed in between), the
// object carried rigidly along its own linear and angular velocity to other.time.
ObjectState objectAt(const ObjectState& object, double fromTime, const SceneSnapshot& other);

}  // namespace warplab::scene
