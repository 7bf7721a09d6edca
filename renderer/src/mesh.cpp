#include "renderer/mesh.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>

#include <tiny_obj_loader.h>

namespace warplab::renderer {
namespace {

void computeBounds(MeshData& mesh) {
    if (mesh.vertices.empty()) return;
    mesh.boundsMin = mesh.boundsMax = mesh.vertices.front().position;
    for (const auto& v : mesh.vertices) {
        mesh.boundsMin = glm::min(mesh.boundsMin, v.position);
        mesh.boundsMax = glm::max(mesh.boundsMax, v.position);
    }
}

// tinyobjloader reads an unparsable coordinate ("nan", "1,5", "x") as 0 without a word; a
// model silently squashed to the origin is worse than a refusal, so check v/vn lines first.
void checkCoordinates(const std::string& path) {
    std::ifstream in(path);
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        if (line.rfind("v ", 0) != 0 && line.rfind("vn ", 0) != 0) continue;
        std::istringstream fields(line);
        std::string tag, token;
        fields >> tag;
        for (int i = 0; i < 3; ++i) {
            if (!(fields >> token))
                throw AssetError("cannot load model '" + path + "': line " + std::to_string(number) + " ('" + tag +
                                 "') has fewer than 3 coordinates");
            char* end = nullptr;
            const double value = std::strtod(token.c_str(), &end);
            if (end == token.c_str() || *end != '\0' || !std::isfinite(value))
                throw AssetError("cannot load model '" + path + "': line " + std::to_string(number) +
                                 " has coordinate '" + token + "', which is not a finite number");
        }
    }
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

MeshData loadObj(const std::string& path) {
    {
        std::ifstream probe(path);
        if (!probe) throw AssetError("cannot read model '" + path + "': file missing or unreadable");
    }
    checkCoordinates(path);
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    const auto slash = path.find_last_of('/');
    config.mtl_search_path = slash == std::string::npos ? "./" : path.substr(0, slash + 1);
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path, config)) {
        std::string err = reader.Error();
        while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
        throw AssetError("cannot load model '" + path + "': " + (err.empty() ? "parse failed" : err));
    }
    const auto& attrib = reader.GetAttrib();
    const auto& materials = reader.GetMaterials();
    MeshData mesh;
    const int vertexCount = static_cast<int>(attrib.vertices.size() / 3);
    const int normalCount = static_cast<int>(attrib.normals.size() / 3);
    for (const auto& shape : reader.GetShapes()) {
        std::size_t offset = 0;
        for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
            const int corners = shape.mesh.num_face_vertices[f];
            if (corners != 3)
                throw AssetError("cannot load model '" + path + "': face " + std::to_string(f + 1) + " of '" +
                                 shape.name + "' is degenerate (" + std::to_string(corners) + " corners)");
            MeshVertex tri[3];
            bool hasNormals = true;
            for (int c = 0; c < 3; ++c) {
                const auto idx = shape.mesh.indices[offset + static_cast<std::size_t>(c)];
                if (idx.vertex_index < 0 || idx.vertex_index >= vertexCount)
                    throw AssetError("cannot load model '" + path + "': face " + std::to_string(f + 1) + " of '" +
                                     shape.name + "' refers to a vertex that does not exist");
                const auto vi = static_cast<std::size_t>(idx.vertex_index) * 3;
                tri[c].position = {attrib.vertices[vi], attrib.vertices[vi + 1], attrib.vertices[vi + 2]};
                if (idx.normal_index >= 0 && idx.normal_index < normalCount) {
                    const auto ni = static_cast<std::size_t>(idx.normal_index) * 3;
                    tri[c].normal = {attrib.normals[ni], attrib.normals[ni + 1], attrib.normals[ni + 2]};
                } else {
                    hasNormals = false;
                }
                if (!finite(tri[c].position))
                    throw AssetError("cannot load model '" + path + "': a vertex of '" + shape.name +
                                     "' is not a finite number");
            }
            const glm::vec3 faceNormal =
                glm::cross(tri[1].position - tri[0].position, tri[2].position - tri[0].position);
            const float area2 = glm::length(faceNormal);
            const int materialId = shape.mesh.material_ids.empty() ? -1 : shape.mesh.material_ids[f];
            glm::vec3 kd(0.7f), ks(0.2f);
            float ns = 16.0f;
            if (materialId >= 0 && materialId < static_cast<int>(materials.size())) {
                const auto& m = materials[static_cast<std::size_t>(materialId)];
                kd = {m.diffuse[0], m.diffuse[1], m.diffuse[2]};
                ks = {m.specular[0], m.specular[1], m.specular[2]};
                ns = m.shininess > 0.0f ? m.shininess : 1.0f;
            }
            offset += 3;
            if (!(area2 > 0.0f)) continue;  // zero-area triangles draw nothing; skip them
            for (auto& v : tri) {
                if (!hasNormals || !finite(v.normal) || glm::length(v.normal) < 1e-6f) v.normal = faceNormal / area2;
                v.normal = glm::normalize(v.normal);
                v.diffuse = kd;
                v.specular = glm::vec4(ks, ns);
                mesh.vertices.push_back(v);
            }
        }
    }
    if (mesh.vertices.empty()) throw AssetError("cannot load model '" + path + "': it contains no triangles");
    computeBounds(mesh);
    return mesh;
}

MeshData makeUnitSphere(int slices, int stacks) {
    MeshData mesh;
    const float pi = 3.14159265358979f;
    auto point = [&](int i, int j) {
        const float theta = pi * static_cast<float>(j) / static_cast<float>(stacks);  // from +y down
        const float phi = 2.0f * pi * static_cast<float>(i) / static_cast<float>(slices);  // around y
        return glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
    };
    auto emit = [&](const glm::vec3& p) {
        mesh.vertices.push_back({p, p, glm::vec3(1.0f), glm::vec4(0.6f, 0.6f, 0.6f, 48.0f)});
    };
    for (int j = 0; j < stacks; ++j) {
        for (int i = 0; i < slices; ++i) {
            const glm::vec3 a = point(i, j), b = point(i, j + 1), c = point(i + 1, j + 1), d = point(i + 1, j);
            // Counter-clockwise seen from outside; the pole rows have one degenerate triangle each.
            if (j != 0) {
                emit(a);
                emit(b);
                emit(d);
            }
            if (j != stacks - 1) {
                emit(d);
                emit(b);
                emit(c);
            }
        }
    }
    computeBounds(mesh);
    return mesh;
}

int sphereSlicesFor(float radiusPixels) {
    constexpr double kMaxShortfallPixels = 0.125;
    for (int slices : kSphereSlices)
        if (radiusPixels * (1.0 - std::cos(M_PI / slices)) <= kMaxShortfallPixels) return slices;
    return kSphereSlices[std::size(kSphereSlices) - 1];
}

MeshData makeUnitBox() {
    MeshData mesh;
    for (int axis = 0; axis < 3; ++axis) {
        for (int sign = -1; sign <= 1; sign += 2) {
            glm::vec3 n(0.0f);
            n[axis] = static_cast<float>(sign);
            glm::vec3 u(0.0f), v(0.0f);
            u[(axis + 1) % 3] = 1.0f;
            v[(axis + 2) % 3] = 1.0f;
            if (sign < 0) std::swap(u, v);  // keep counter-clockwise winding from outside
            const glm::vec3 corners[4] = {n - u - v, n + u - v, n + u + v, n - u + v};
            for (int k : {0, 1, 2, 0, 2, 3})
                mesh.vertices.push_back({corners[k], n, glm::vec3(1.0f), glm::vec4(0.3f, 0.3f, 0.3f, 16.0f)});
        }
    }
    computeBounds(mesh);
    return mesh;
}

}  // namespace warplab::renderer
