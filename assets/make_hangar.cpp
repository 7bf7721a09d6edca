// Generates the hangar hallway model (assets/hangar.obj + assets/hangar.mtl).
//
//   g++ -std=c++17 -Wall -Wextra -I. assets/make_hangar.cpp -o /tmp/make_hangar
//   /tmp/make_hangar assets
//
// Every main dimension comes from scene/hangar_layout.h, so the walls the renderer draws are the
// walls the target's physics box assumes. The output is deterministic (no randomness, fixed
// "%.4f" formatting, stable ordering) so regenerating gives byte-identical files and a diff of
// the committed OBJ means the geometry really changed.
//
// The scene is built only from closed convex solids (boxes, slanted hexahedra, prisms,
// cylinders). Each face is written with a flat normal and counter-clockwise winding seen from
// outside its solid, both derived from the solid's centroid, so back-face culling is safe and
// depth discontinuities (what the image-warping methods are tested on) are real geometry.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <string>
#include <system_error>
#include <vector>

#include "scene/hangar_layout.h"

namespace {

using L = warplab::scene::HangarLayout;

// Attached parts reach this far into whatever they are attached to, so no visible face of one
// solid is coplanar with a face of another (no z-fighting).
constexpr double kEmbed = 0.02;

struct Vec3 {
    double x = 0.0, y = 0.0, z = 0.0;
};

Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double length(Vec3 a) { return std::sqrt(dot(a, a)); }

// Fixed formatting, and never "-0.0000": the same geometry must always print the same bytes.
std::string fmt(double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.4f", value);
    std::string text = buffer;
    if (text == "-0.0000") text = "0.0000";
    return text;
}

std::string fmt(Vec3 v) { return fmt(v.x) + " " + fmt(v.y) + " " + fmt(v.z); }

struct Material {
    const char* name;
    Vec3 kd;
    Vec3 ks;
    double ns;
    const char* comment;
};

// Kept to a handful so the renderer can batch per material; colours chosen to be told apart
// in the id-free colour buffer and in difference images.
const Material kMaterials[] = {
    {"hull_metal", {0.42, 0.43, 0.45}, {0.35, 0.35, 0.35}, 48.0, "floor, ceiling, walls"},
    {"rib_steel", {0.28, 0.29, 0.31}, {0.50, 0.50, 0.50}, 64.0, "ribs, beams, frames, panel rims"},
    {"panel_bluegrey", {0.20, 0.24, 0.30}, {0.25, 0.27, 0.30}, 32.0, "wall panel insets, doors"},
    {"deck_dark", {0.14, 0.14, 0.15}, {0.20, 0.20, 0.20}, 16.0, "floor deck and grating"},
    {"hazard_yellow", {0.95, 0.74, 0.05}, {0.30, 0.30, 0.30}, 24.0, "hazard stripes"},
    {"hazard_black", {0.04, 0.04, 0.04}, {0.30, 0.30, 0.30}, 24.0, "hazard stripes"},
    {"crate_orange", {0.85, 0.38, 0.08}, {0.15, 0.15, 0.15}, 12.0, "cargo crates"},
    {"pipe_steel", {0.62, 0.64, 0.67}, {0.80, 0.80, 0.80}, 96.0, "pipes and railing"},
};

// Collects geometry group by group, then writes one OBJ: all positions, all normals, then the
// faces of each group (g), split by material (usemtl) in the order materials were first used.
class ObjWriter {
public:
    void group(const std::string& name) { groups_.push_back({name, {}}); }

    void material(const std::string& name) {
        bool known = false;
        for (const Material& m : kMaterials) known = known || name == m.name;
        if (!known) fail("unknown material '" + name + "'");
        material_ = name;
    }

    // A convex solid: corner positions and faces as cyclic corner lists. Corners may coincide
    // (wedges built as collapsed hexahedra); faces that collapse are dropped. The winding of
    // each face is fixed here, from the solid's centroid, rather than trusted from the caller.
    void solid(const std::vector<Vec3>& corners, const std::vector<std::vector<int>>& faces) {
        if (groups_.empty() || material_.empty()) fail("solid before group/material");
        Vec3 centroid;
        for (const Vec3& c : corners) centroid = centroid + c;
        centroid = (1.0 / static_cast<double>(corners.size())) * centroid;

        for (std::vector<int> face : faces) {
            // Newell's method: robust for polygons with repeated corners.
            Vec3 normal;
            Vec3 faceCentre;
            for (std::size_t i = 0; i < face.size(); ++i) {
                const Vec3 a = corners[face[i]];
                const Vec3 b = corners[face[(i + 1) % face.size()]];
                normal = normal + Vec3{(a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y)};
                faceCentre = faceCentre + a;
            }
            faceCentre = (1.0 / static_cast<double>(face.size())) * faceCentre;
            const double area2 = length(normal);
            if (area2 < 1e-9) continue;  // collapsed face of a wedge
            normal = (1.0 / area2) * normal;
            if (dot(normal, faceCentre - centroid) < 0.0) {
                normal = -1.0 * normal;
                std::reverse(face.begin(), face.end());
            }
            const int n = normalIndex(normal);
            // Fan triangulation; faces are convex.
            for (std::size_t i = 1; i + 1 < face.size(); ++i) {
                const Vec3 p0 = corners[face[0]];
                const Vec3 p1 = corners[face[i]];
                const Vec3 p2 = corners[face[i + 1]];
                if (length(cross(p1 - p0, p2 - p0)) < 1e-9) continue;
                const int i0 = positionIndex(p0);
                const int i1 = positionIndex(p1);
                const int i2 = positionIndex(p2);
                if (i0 == i1 || i1 == i2 || i0 == i2) continue;  // collapsed by rounding
                triangles(material_).push_back("f " + std::to_string(i0) + "//" + std::to_string(n) + " " +
                                               std::to_string(i1) + "//" + std::to_string(n) + " " +
                                               std::to_string(i2) + "//" + std::to_string(n));
                ++triangleCount_;
            }
        }
    }

    int triangleCount() const { return triangleCount_; }

    std::string text(const std::string& mtlFile) const {
        std::string out;
        out += "# Hangar hallway for warplab. Generated by assets/make_hangar.cpp from\n";
        out += "# scene/hangar_layout.h; do not edit by hand, regenerate instead.\n";
        out += "# Metres, y up, hallway along -z, far end open onto space.\n";
        out += "# " + std::to_string(positions_.size()) + " positions, " + std::to_string(normals_.size()) +
            " normals, " + std::to_string(triangleCount_) + " triangles\n";
        out += "mtllib " + mtlFile + "\n";
        for (const std::string& p : positions_) out += "v " + p + "\n";
        for (const std::string& n : normals_) out += "vn " + n + "\n";
        for (const Group& g : groups_) {
            if (g.batches.empty()) continue;
            out += "g " + g.name + "\n";
            for (const Batch& b : g.batches) {
                out += "usemtl " + b.material + "\n";
                for (const std::string& f : b.faces) out += f + "\n";
            }
        }
        return out;
    }

    [[noreturn]] static void fail(const std::string& message) {
        std::cerr << "make_hangar: internal error: " << message << "\n";
        std::exit(3);
    }

private:
    struct Batch {
        std::string material;
        std::vector<std::string> faces;
    };
    struct Group {
        std::string name;
        std::vector<Batch> batches;
    };

    std::vector<std::string>& triangles(const std::string& material) {
        std::vector<Batch>& batches = groups_.back().batches;
        for (Batch& b : batches)
            if (b.material == material) return b.faces;
        batches.push_back({material, {}});
        return batches.back().faces;
    }

    int positionIndex(Vec3 p) { return intern(fmt(p), positions_, positionIds_); }
    int normalIndex(Vec3 n) { return intern(fmt(n), normals_, normalIds_); }

    static int intern(const std::string& key, std::vector<std::string>& list, std::map<std::string, int>& ids) {
        const auto found = ids.find(key);
        if (found != ids.end()) return found->second;
        list.push_back(key);
        const int id = static_cast<int>(list.size());  // OBJ indices are 1-based
        ids.emplace(key, id);
        return id;
    }

    std::vector<Group> groups_;
    std::string material_;
    std::vector<std::string> positions_, normals_;
    std::map<std::string, int> positionIds_, normalIds_;
    int triangleCount_ = 0;
};

// Corner i of a hexahedron sits at the (-/+) x, y, z side given by bits 0, 1, 2 of i.
const std::vector<std::vector<int>> kHexFaces = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                                 {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};

void box(ObjWriter& obj, Vec3 lo, Vec3 hi) {
    if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z)) ObjWriter::fail("empty box");
    std::vector<Vec3> c(8);
    for (int i = 0; i < 8; ++i) c[i] = {(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z};
    obj.solid(c, kHexFaces);
}

// A box of half size `half` centred at `centre`, turned by `yawDeg` about the vertical axis.
void turnedBox(ObjWriter& obj, Vec3 centre, Vec3 half, double yawDeg) {
    const double a = yawDeg * 3.14159265358979323846 / 180.0;
    const double ca = std::cos(a), sa = std::sin(a);
    std::vector<Vec3> c(8);
    for (int i = 0; i < 8; ++i) {
        const double x = (i & 1) ? half.x : -half.x;
        const double y = (i & 2) ? half.y : -half.y;
        const double z = (i & 4) ? half.z : -half.z;
        c[i] = centre + Vec3{ca * x + sa * z, y, -sa * x + ca * z};
    }
    obj.solid(c, kHexFaces);
}

// Closed cylinder from p0 to p1 with flat-shaded sides.
void cylinder(ObjWriter& obj, Vec3 p0, Vec3 p1, double radius, int sides) {
    const Vec3 axis = p1 - p0;
    const Vec3 w = (1.0 / length(axis)) * axis;
    const Vec3 helper = std::fabs(w.y) < 0.9 ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
    const Vec3 u = (1.0 / length(cross(helper, w))) * cross(helper, w);
    const Vec3 v = cross(w, u);
    std::vector<Vec3> c(2 * sides);
    for (int i = 0; i < sides; ++i) {
        const double t = 2.0 * 3.14159265358979323846 * i / sides;
        const Vec3 r = radius * std::cos(t) * u + radius * std::sin(t) * v;
        c[i] = p0 + r;
        c[sides + i] = p1 + r;
    }
    std::vector<std::vector<int>> faces;
    for (int i = 0; i < sides; ++i) {
        const int j = (i + 1) % sides;
        faces.push_back({i, j, sides + j, sides + i});
    }
    std::vector<int> cap0, cap1;
    for (int i = 0; i < sides; ++i) {
        cap0.push_back(i);
        cap1.push_back(sides + i);
    }
    faces.push_back(cap0);
    faces.push_back(cap1);
    obj.solid(c, faces);
}

// A straight frame member with 45-degree yellow/black hazard stripes across its front.
// The member spans [a0, a1] along its length axis and [b0, b0 + width] across it (the stripe
// slant equals the width); depth [z0, z1] is along z for the far door. `vertical` says whether
// the length axis is y (a jamb) or x (a lintel). (a1 - a0 - width) must be a multiple of the
// pitch, so the stripes meet both ends in a corner and every piece is a parallelogram prism or
// a wedge (no pentagons).
void hazardMember(ObjWriter& obj, bool vertical, bool mirror, double a0, double a1, double b0, double width, double z0,
                  double z1) {
    const double pitch = width;
    const double n = (a1 - a0 - width) / pitch;
    const int bands = static_cast<int>(std::lround(n));
    if (std::fabs(n - bands) > 1e-6 || bands < 1) ObjWriter::fail("hazard member length");
    // Stripe k runs from a = a0 + k * pitch at b = b0 to a0 + k * pitch + width at b = b0 + width
    // (or the other way round when mirrored). Pieces: wedge, bands parallelograms, wedge.
    auto cut = [&](int k, bool farSide) {  // a coordinate of cut line k at one side of b
        double a = a0 + k * pitch + ((farSide != mirror) ? width : 0.0);
        if (k < 0) a = a0;
        if (k > bands) a = a1;
        return a < a0 ? a0 : (a > a1 ? a1 : a);
    };
    for (int colour = 0; colour < 2; ++colour) {
        obj.material(colour == 0 ? "hazard_yellow" : "hazard_black");
        for (int piece = 0; piece <= bands + 1; ++piece) {
            if (piece % 2 != colour) continue;
            // Piece between cut lines piece-1 and piece; cut -1 is the a0 end, bands+1 the a1 end.
            std::vector<Vec3> c(8);
            for (int i = 0; i < 8; ++i) {
                const bool farB = (i & 2) != 0;
                const bool upper = (i & 1) != 0;
                const double a = upper ? cut(piece, farB) : cut(piece - 1, farB);
                const double b = farB ? b0 + width : b0;
                const double z = (i & 4) ? z1 : z0;
                c[i] = vertical ? Vec3{b, a, z} : Vec3{a, b, z};
            }
            obj.solid(c, kHexFaces);
        }
    }
}

// The z ranges of the bays between the end walls and the ribs, front (higher z) first.
struct Bay {
    double zNear, zFar;  // zNear > zFar
};

double ribCentreZ(int i) { return static_cast<double>(L::kFirstRibZ) - i * static_cast<double>(L::kRibSpacing); }

std::vector<Bay> bays() {
    std::vector<Bay> result;
    double zNear = L::kBackZ;
    for (int i = 0; i < L::kRibCount; ++i) {
        const double zc = ribCentreZ(i);
        result.push_back({zNear, zc + 0.5 * L::kRibThickness});
        zNear = zc - 0.5 * L::kRibThickness;
    }
    result.push_back({zNear, L::kFarZ});
    return result;
}

constexpr double W = L::kHalfWidth;
constexpr double H = L::kHeight;
constexpr double kShell = 0.2;  // thickness of floor, ceiling and wall slabs, outside the hall

// Far doorway: opening |x| < kDoorHalfWidth, y < kDoorHeight, framed by hazard members
// kFrameWidth wide. Chosen so both member lengths are whole multiples of the stripe pitch.
constexpr double kFrameWidth = 0.6;
constexpr double kDoorHalfWidth = 5.1;
constexpr double kDoorHeight = 7.2;
constexpr double kFrameDepth = 0.4;  // how far the far frame stands into the hallway

// Side door on the +x wall, centred in the bay behind the target's bay.
constexpr double kSideDoorZ = -15.0;
constexpr double kSideDoorHalfWidth = 1.5;
constexpr double kSideDoorHeight = 4.2;

void shell(ObjWriter& obj) {
    const double zBack = L::kBackZ + kShell;
    const double zFar = L::kFarZ - kShell;
    obj.group("shell_floor");
    obj.material("hull_metal");
    box(obj, {-W - kShell, -kShell, zFar}, {W + kShell, 0.0, zBack});
    obj.group("shell_ceiling");
    obj.material("hull_metal");
    box(obj, {-W - kShell, H, zFar}, {W + kShell, H + kShell, zBack});
    obj.group("shell_walls");
    obj.material("hull_metal");
    box(obj, {-W - kShell, -kShell, zFar}, {-W, H + kShell, zBack});
    box(obj, {W, -kShell, zFar}, {W + kShell, H + kShell, zBack});
    obj.group("shell_back_wall");
    obj.material("hull_metal");
    box(obj, {-W, 0.0 - kEmbed, L::kBackZ}, {W, H + kEmbed, zBack});
    // A recessed look for the wall behind the camera: two raised panels either side of a
    // closed hatch, so turning round does not show a blank plane.
    obj.material("panel_bluegrey");
    box(obj, {-W + 0.8, 1.0, L::kBackZ - 0.15}, {-2.2, H - 1.0, L::kBackZ + kEmbed});
    box(obj, {2.2, 1.0, L::kBackZ - 0.15}, {W - 0.8, H - 1.0, L::kBackZ + kEmbed});
    obj.material("rib_steel");
    box(obj, {-1.6, 0.0 - kEmbed, L::kBackZ - 0.25}, {1.6, 4.0, L::kBackZ + kEmbed});

    // Far end: a wall with a big opening onto space; nothing lies beyond it.
    obj.group("far_wall");
    obj.material("hull_metal");
    const double f0 = L::kFarZ - kShell, f1 = L::kFarZ + kEmbed;
    box(obj, {-W - kEmbed, -kEmbed, f0}, {-kDoorHalfWidth, H + kEmbed, f1});
    box(obj, {kDoorHalfWidth, -kEmbed, f0}, {W + kEmbed, H + kEmbed, f1});
    box(obj, {-kDoorHalfWidth, kDoorHeight, f0}, {kDoorHalfWidth, H + kEmbed, f1});
}

void ribs(ObjWriter& obj) {
    obj.group("ribs");
    obj.material("rib_steel");
    const double d = L::kRibDepth;
    for (int i = 0; i < L::kRibCount; ++i) {
        const double z0 = ribCentreZ(i) - 0.5 * L::kRibThickness;
        const double z1 = ribCentreZ(i) + 0.5 * L::kRibThickness;
        box(obj, {-W - kEmbed, -kEmbed, z0}, {-W + d, H + kEmbed, z1});  // left post
        box(obj, {W - d, -kEmbed, z0}, {W + kEmbed, H + kEmbed, z1});  // right post
        box(obj, {-W + d, H - d, z0}, {W - d, H + kEmbed, z1});  // top
        box(obj, {-W + d, -kEmbed, z0}, {W - d, d, z1});  // floor sill
    }
}

void ceilingBeams(ObjWriter& obj) {
    obj.group("ceiling_beams");
    obj.material("rib_steel");
    const double beamDepth = 0.38;  // stays inside the rib depth: clear of the target box
    const double halfWidth = 0.2;
    for (const Bay& bay : bays()) {
        for (double x : {-4.5, 0.0, 4.5}) {
            box(obj, {x - halfWidth, H - beamDepth, bay.zFar - kEmbed},
                {x + halfWidth, H + kEmbed, bay.zNear + kEmbed});
        }
        // A cross joist mid-bay gives the ceiling a second depth step across the view.
        const double zm = 0.5 * (bay.zNear + bay.zFar);
        if (bay.zNear - bay.zFar > 3.0)
            box(obj, {-W + kEmbed, H - 0.22, zm - 0.15}, {W - kEmbed, H + kEmbed, zm + 0.15});
    }
}

void wallPanels(ObjWriter& obj) {
    obj.group("wall_panels");
    const double margin = 0.3;
    const double panelDepth = 0.12, insetDepth = 0.06, insetMargin = 0.35;
    const double rows[2][2] = {{0.8, 4.3}, {4.7, H - 0.8}};
    const std::vector<Bay> all = bays();
    for (std::size_t b = 0; b < all.size(); ++b) {
        const double z0 = all[b].zFar + margin, z1 = all[b].zNear - margin;
        for (int side = -1; side <= 1; side += 2) {
            for (int row = 0; row < 2; ++row) {
                const bool door = side > 0 && row == 0 && z0 < kSideDoorZ && kSideDoorZ < z1;
                if (door) continue;
                const double y0 = rows[row][0], y1 = rows[row][1];
                const double wall = side * W;
                const double face = side * (W - panelDepth);
                const double inset = side * (W - panelDepth - insetDepth);
                auto slab = [&](double xa, double xb, double ya, double yb, double za, double zb) {
                    box(obj, {std::min(xa, xb), ya, za}, {std::max(xa, xb), yb, zb});
                };
                obj.material("rib_steel");  // the panel's rim, darker than its inset
                slab(wall + side * kEmbed, face, y0, y1, z0, z1);
                obj.material("panel_bluegrey");
                // Lower panels get one long raised inset, upper panels two, so the wall's depth
                // steps are not all at the same spacing.
                if (row == 0) {
                    slab(face + side * kEmbed, inset, y0 + insetMargin, y1 - insetMargin, z0 + insetMargin,
                         z1 - insetMargin);
                } else {
                    const double zm = 0.5 * (z0 + z1);
                    slab(face + side * kEmbed, inset, y0 + insetMargin, y1 - insetMargin, z0 + insetMargin,
                         zm - 0.5 * insetMargin);
                    slab(face + side * kEmbed, inset, y0 + insetMargin, y1 - insetMargin, zm + 0.5 * insetMargin,
                         z1 - insetMargin);
                }
            }
        }
    }
}

void deck(ObjWriter& obj) {
    obj.group("deck");
    obj.material("deck_dark");
    for (const Bay& bay : bays()) {
        const double z0 = bay.zFar + 0.1, z1 = bay.zNear - 0.1;
        // Side deck plates, a few centimetres proud of the hull floor.
        box(obj, {-W + 0.4, -kEmbed, z0}, {-2.6, 0.03, z1});
        box(obj, {2.6, -kEmbed, z0}, {W - 0.4, 0.03, z1});
        // Grating stripes down the central walkway: thin, high-contrast depth edges.
        for (int k = 0; k < 7; ++k) {
            const double x = -2.1 + 0.7 * k;
            box(obj, {x - 0.09, -kEmbed, z0}, {x + 0.09, 0.06, z1});
        }
    }
}

void crates(ObjWriter& obj) {
    obj.group("crates");
    obj.material("crate_orange");
    // Close to the camera, right of the view axis, in the bay behind the first rib (a crate on
    // the floor cannot straddle the rib's sill): a stack tall enough that the corner of its
    // turned top crate shows in the lower right of the default view, the nearest depth edge
    // in that view.
    box(obj, {1.6, 0.0, -2.7}, {3.6, 2.2, -0.9});
    turnedBox(obj, {2.6, 2.2 + 0.7, -1.9}, {0.7, 0.7, 0.7}, 20.0);
    // Further down the hallway, alternating sides, each inside a bay (clear of rib sills) and
    // well off the centre line so the far opening stays in sight.
    box(obj, {-7.3, 0.0, -16.6}, {-5.1, 2.2, -14.4});
    turnedBox(obj, {-4.3, 0.55, -13.6}, {0.55, 0.55, 0.55}, 30.0);
    box(obj, {5.0, 0.0, -24.0}, {7.0, 2.0, -22.0});
    turnedBox(obj, {6.0, 2.0 + 0.6, -23.0}, {0.6, 0.6, 0.6}, -15.0);
    box(obj, {-7.2, 0.0, -33.5}, {-5.4, 1.6, -28.5});
    box(obj, {4.2, 0.0, -48.0}, {6.6, 2.4, -45.6});
    box(obj, {5.2, 0.0, -45.2}, {6.8, 1.4, -43.6});
    turnedBox(obj, {-6.2, 0.5, -41.0}, {0.5, 0.5, 0.5}, 40.0);
}

void pipes(ObjWriter& obj) {
    // Along the -x wall from the back wall well past the target's bay; they pass through the
    // ribs (which hide the joins) and sit in the gaps between panel rows.
    obj.group("pipes");
    obj.material("pipe_steel");
    const double z0 = L::kBackZ + kEmbed, z1 = ribCentreZ(3);
    cylinder(obj, {-W + 0.25, 4.5, z0}, {-W + 0.25, 4.5, z1}, 0.15, 12);
    cylinder(obj, {-W + 0.2, 0.45, z0}, {-W + 0.2, 0.45, z1}, 0.1, 12);
    cylinder(obj, {-W + 0.22, H - 0.6, z0}, {-W + 0.22, H - 0.6, z1}, 0.12, 12);

    // Hand railing along the +x wall near the camera: thin posts and a rail, ending before the
    // side door. Posts avoid the ribs.
    obj.group("railing");
    obj.material("pipe_steel");
    const double x = W - 0.35, top = 1.1;
    const double railStart = L::kBackZ + kEmbed;
    const double railEnd = kSideDoorZ + kSideDoorHalfWidth + 0.7;
    cylinder(obj, {x, top, railStart}, {x, top, railEnd}, 0.045, 10);
    for (double z : {1.6, -0.8, -5.0, -7.5, -10.0, -12.4}) {
        cylinder(obj, {x, -kEmbed, z}, {x, top, z}, 0.03, 8);
    }
}

void sideDoor(ObjWriter& obj) {
    obj.group("side_door");
    const double z0 = kSideDoorZ - kSideDoorHalfWidth, z1 = kSideDoorZ + kSideDoorHalfWidth;
    const double frame = 0.3, frameDepth = 0.4;
    obj.material("panel_bluegrey");
    // Two leaves with a seam between them, set just in front of the wall.
    box(obj, {W - 0.1, 0.0, z0}, {W + kEmbed, kSideDoorHeight, kSideDoorZ - 0.02});
    box(obj, {W - 0.1, 0.0, kSideDoorZ + 0.02}, {W + kEmbed, kSideDoorHeight, z1});
    obj.material("rib_steel");
    box(obj, {W - frameDepth, 0.0, z0 - frame}, {W + kEmbed, kSideDoorHeight + frame, z0});
    box(obj, {W - frameDepth, 0.0, z1}, {W + kEmbed, kSideDoorHeight + frame, z1 + frame});
    box(obj, {W - frameDepth, kSideDoorHeight, z0}, {W + kEmbed, kSideDoorHeight + frame, z1});
    // A hazard-yellow kick plate so the door reads as a door from down the hallway.
    obj.material("hazard_yellow");
    box(obj, {W - 0.16, 0.0, z0 + 0.1}, {W - 0.1 + kEmbed, 0.4, z1 - 0.1});
}

void farDoor(ObjWriter& obj) {
    obj.group("far_door");
    const double z0 = L::kFarZ - kShell, z1 = L::kFarZ + kFrameDepth;
    const double top = kDoorHeight + kFrameWidth;
    // Jambs run the full height; the lintel sits between them.
    hazardMember(obj, true, false, 0.0, top, -kDoorHalfWidth - kFrameWidth, kFrameWidth, z0, z1);
    hazardMember(obj, true, true, 0.0, top, kDoorHalfWidth, kFrameWidth, z0, z1);
    hazardMember(obj, false, false, -kDoorHalfWidth, kDoorHalfWidth, kDoorHeight, kFrameWidth, z0, z1);
}

bool writeFile(const std::filesystem::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) return false;
    out << text;
    out.close();
    return static_cast<bool>(out);
}

std::string mtlText() {
    std::string out;
    out += "# Materials of the warplab hangar hallway. Generated by assets/make_hangar.cpp.\n";
    for (const Material& m : kMaterials) {
        out += "\n# " + std::string(m.comment) + "\n";
        out += "newmtl " + std::string(m.name) + "\n";
        out += "Ka " + fmt(0.1 * m.kd) + "\n";
        out += "Kd " + fmt(m.kd) + "\n";
        out += "Ks " + fmt(m.ks) + "\n";
        out += "Ns " + fmt(m.ns) + "\n";
        out += "d 1.0000\n";
        out += "illum 2\n";
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2 || std::string(argv[1]).empty() || std::string(argv[1]) == "-h" || std::string(argv[1]) == "--help") {
        std::cerr << "usage: make_hangar OUTPUT_DIR\n"
                     "Writes hangar.obj and hangar.mtl (the warplab hangar hallway) into the "
                     "existing directory OUTPUT_DIR.\n";
        return 2;
    }
    const std::filesystem::path dir = argv[1];
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) {
        std::cerr << "make_hangar: output directory '" << dir.string() << "' does not exist or is not a directory.\n";
        return 1;
    }

    ObjWriter obj;
    shell(obj);
    ribs(obj);
    ceilingBeams(obj);
    wallPanels(obj);
    deck(obj);
    crates(obj);
    pipes(obj);
    sideDoor(obj);
    farDoor(obj);

    const std::filesystem::path objPath = dir / "hangar.obj";
    const std::filesystem::path mtlPath = dir / "hangar.mtl";
    if (!writeFile(mtlPath, mtlText())) {
        std::cerr << "make_hangar: cannot write '" << mtlPath.string() << "'.\n";
        return 1;
    }
    if (!writeFile(objPath, obj.text("hangar.mtl"))) {
        std::cerr << "make_hangar: cannot write '" << objPath.string() << "'.\n";
        return 1;
    }
    std::cout << "make_hangar: wrote " << objPath.string() << " (" << obj.triangleCount() << " triangles) and "
              << mtlPath.string() << "\n";
    return 0;
}
