// Renderer-private: the scene's meshes on the GPU and the loop that draws them. Every pass that
// rasterises the scene -- the conventional frame, the flow fields of bidirectional
// reprojection, scene-assisted B-frames -- draws the same triangles the same way through it.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/conventional.h"
#include "gl/objects.h"
#include "scene/scene.h"

namespace warplab::renderer {

// A mesh on the GPU: interleaved MeshVertex records (attributes 0 position, 1 normal,
// 2 diffuse, 3 specular), drawn as a triangle list.
struct GpuMesh {
    gl::VertexArray vao;
    gl::Buffer vbo;
    GLsizei vertexCount = 0;
};

class SceneGeometry {
public:
    // Loads assets/hangar.obj (AssetError naming it) and builds the unit sphere and box.
    explicit SceneGeometry(const DataPaths& paths);

    // What one draw call is about: the hangar (object == nullptr, identity model) or an object.
    struct Item {
        std::uint32_t id = 0;
        glm::mat4 model{1.0f};
        const scene::ObjectState* object = nullptr;
    };
    // Draws the hangar, then every object of `scene`, calling `prepare` before each draw so
    // the caller can set its program's per-draw uniforms. The caller binds program and target.
    // `camera` and `height` (the target's rows) are what the scene is seen with: each sphere is
    // drawn with the tessellation its size on screen needs (sphereSlicesFor), so every pass
    // that draws one frame's scene with one camera at one size draws the same triangles.
    void draw(const scene::SceneSnapshot& scene, const scene::CameraState& camera, int height,
              const std::function<void(const Item&)>& prepare) const;
    // For passes that give pixels with no surface a value too (flow fields, scene-assisted
    // reprojection): one far-plane triangle over the whole target, drawn with `program`'s
    // uSky = 1 and uObjectId = none, depth test and writes off; then depth testing is restored
    // (GL_LESS, writes on) and uSky set back to 0 for the scene that follows.
    void drawSky(const gl::Program& program) const;

private:
    GpuMesh hangar_, box_;
    std::vector<GpuMesh> spheres_;  // one per kSphereSlices, coarsest first
    gl::VertexArray empty_;  // the sky triangle's positions come from gl_VertexID
};

}  // namespace warplab::renderer
