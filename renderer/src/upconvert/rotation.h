// Renderer-private: late warp by camera rotation (Kim et al., HPG 2020; NVIDIA Reflex 2 Frame
// Warp). Use makeMethod("rotation") or, with the bench's queued source, "late-rotation".
#pragma once

#include "renderer/upconvert.h"

namespace warplab::renderer {

std::unique_ptr<UpconversionMethod> makeRotation(const DataPaths& paths);

// Window coordinates of a `width` x `height` display seen from `display` (bottom-up, pixel
// centres at +0.5, w = 1) to homogeneous window coordinates of a `sourceWidth` x
// `sourceHeight` image seen from `source`, through the two cameras' view rotations alone; the
// third component is the ray's depth along the source's view axis (> 0 in front of it).
glm::dmat3 rotationHomography(const scene::CameraState& display, int width, int height,
                              const scene::CameraState& source, int sourceWidth, int sourceHeight);

}  // namespace warplab::renderer
