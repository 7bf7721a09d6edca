#include "scene_geometry.h"

#include <cstddef>

#include "gl/check.h"
#include "gl/program.h"
#include "renderer/mesh.h"
#include "scene/camera.h"
#include "scene/motion.h"

namespace warplab::renderer {
namespace {

GpuMesh upload(const MeshData& mesh) {
    GpuMesh gpu;
    gpu.vao = gl::VertexArray::create();
    gpu.vbo = gl::Buffer::create();
    glBindVertexArray(gpu.vao.id());
    glBindBuffer(GL_ARRAY_BUFFER, gpu.vbo.id());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(MeshVertex)),
                 mesh.vertices.data(), GL_STATIC_DRAW);
    const auto stride = static_cast<GLsizei>(sizeof(MeshVertex));
    auto attrib = [&](GLuint index, GLint size, std::size_t offset) {
        glEnableVertexAttribArray(index);
        glVertexAttribPointer(index, size, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(offset));
    };
    attrib(0, 3, offsetof(MeshVertex, position));
    attrib(1, 3, offsetof(MeshVertex, normal));
    attrib(2, 3, offsetof(MeshVertex, diffuse));
    attrib(3, 4, offsetof(MeshVertex, specular));
    glBindVertexArray(0);
    gpu.vertexCount = static_cast<GLsizei>(mesh.vertices.size());
    gl::checkErrors("uploading a mesh");
    return gpu;
}

}  // namespace

SceneGeometry::SceneGeometry(const DataPaths& paths)
    : hangar_(upload(loadObj(paths.assetDir + "/hangar.obj"))),
      box_(upload(makeUnitBox())),
      empty_(gl::VertexArray::create()) {
    for (int slices : kSphereSlices) spheres_.push_back(upload(makeUnitSphere(slices, slices / 2)));
}

void SceneGeometry::drawSky(const gl::Program& program) const {
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glUniform1i(gl::uniform(program, "uSky"), 1);
    glUniform1ui(gl::uniform(program, "uObjectId"), scene::kIdNone);
    glBindVertexArray(empty_.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glUniform1i(gl::uniform(program, "uSky"), 0);
}

void SceneGeometry::draw(const scene::SceneSnapshot& scene, const scene::CameraState& camera, int height,
                         const std::function<void(const Item&)>& prepare) const {
    auto drawMesh = [](const GpuMesh& mesh) {
        glBindVertexArray(mesh.vao.id());
        glDrawArrays(GL_TRIANGLES, 0, mesh.vertexCount);
    };
    prepare({scene::kIdHangar, glm::mat4(1.0f), nullptr});
    drawMesh(hangar_);
    for (const auto& object : scene.objects) {
        prepare({object.id, scene::modelMatrix(object), &object});
        if (object.shape == scene::Shape::Sphere) {
            const float onScreen =
                scene::projectedSphereRadiusPixels(camera, height, object.position, object.halfExtents.x);
            const int slices = sphereSlicesFor(onScreen);
            std::size_t level = 0;
            while (kSphereSlices[level] != slices) ++level;
            drawMesh(spheres_[level]);
        } else {
            drawMesh(box_);
        }
    }
    glBindVertexArray(0);
}

}  // namespace warplab::renderer
