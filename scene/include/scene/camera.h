// Camera maths shared by the renderer (matrices), physics (fitting the target plane) and
// scoring (the aim ray). Plain GLM, no GL.
#pragma once

#include "scene/scene.h"

namespace warplab::scene {

// Unit view direction for a yaw/pitch (see CameraState for the convention).
glm::vec3 forwardDirection(float yaw, float pitch);

glm::mat4 viewMatrix(const CameraState& camera);
// OpenGL clip convention (z in [-1, 1]), aspect = width / height.
glm::mat4 projectionMatrix(const CameraState& camera, float aspect);

// The camera of an image `marginY` rows taller at the top and at the bottom than one of
// `height` rows, with the same centre and pixel pitch: a source rendered with a guard band.
// A horizontal margin needs nothing more: the wider image's aspect keeps the pitch.
CameraState widenedByRows(const CameraState& camera, int height, int marginY);

// Direction of the ray through a point of the image, given in normalised device coordinates
// (x, y in [-1, 1], y up). (0, 0) is the reticle.
glm::vec3 rayDirection(const CameraState& camera, float aspect, glm::vec2 ndc);

// The long semi-axis, in pixels of an image `height` rows tall, of the ellipse that `camera`
// projects the sphere at `centre` with `radius` to: exact for the cone of rays that touch it,
// so it grows off the view axis as perspective stretches the sphere. 0 for a sphere wholly
// behind the eye; infinity for one that reaches the eye's side plane or holds the eye.
float projectedSphereRadiusPixels(const CameraState& camera, int height, glm::vec3 centre, float radius);

}  // namespace warplab::scene
