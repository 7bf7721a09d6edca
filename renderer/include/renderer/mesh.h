// Triangle meshes as plain data: the hangar from its OBJ, and the unit sphere and box the
// moving objects are drawn with. No GL here; the renderer uploads them.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace warplab::renderer {

struct MeshVertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec3 diffuse;  // Phong kd
    glm::vec4 specular;  // Phong ks in rgb, shininess in w
};

// Non-indexed triangle list: vertices[3i .. 3i+2] is triangle i.
struct MeshData {
    std::vector<MeshVertex> vertices;
    glm::vec3 boundsMin{0.0f};
    glm::vec3 boundsMax{0.0f};
};

// A missing, unreadable or malformed asset; the message names the file.
class AssetError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Loads an OBJ (with its MTL for colours) through tinyobjloader. Throws AssetError naming the
// file and, where the parser says, the line.
MeshData loadObj(const std::string& path);

MeshData makeUnitSphere(int slices, int stacks);  // radius 1, centred at the origin
MeshData makeUnitBox();  // half extents 1, centred at the origin

// The sphere's tessellations, coarsest first: `slices` around, slices / 2 stacks.
inline constexpr int kSphereSlices[] = {8, 16, 32, 64};
// The coarsest of kSphereSlices whose silhouette, for a sphere `radiusPixels` in radius on
// screen, lies within an eighth of a pixel of the true sphere's (its vertices are on the sphere,
// so the polygon falls short by radius * (1 - cos(pi / slices)) at most); the finest beyond
// that. Its id mask, sampled at pixel centres, then differs from the true sphere's only where a
// centre lies that close to the edge. Spheres a few pixels across -- the simulated participant's
// small percepts, distant targets -- cost 128 or 512 triangles, not 4096.
int sphereSlicesFor(float radiusPixels);

}  // namespace warplab::renderer
