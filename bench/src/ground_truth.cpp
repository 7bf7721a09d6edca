#include "bench/ground_truth.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "scene/camera.h"

namespace warplab::bench {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string sizeText(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

void checkFrameImages(const char* function, const char* which, const image::ImageF& depth, const image::ImageU32& ids) {
    const std::size_t n = std::size_t(std::max(depth.width, 0)) * std::size_t(std::max(depth.height, 0));
    if (depth.width < 1 || depth.height < 1 || depth.channels != 1 || depth.data.size() != n)
        throw std::invalid_argument(std::string(function) + ": the " + which +
                                    " depth image must be 1-channel and at least 1x1 with width*height values, got " +
                                    sizeText(depth.width, depth.height) + " with " + std::to_string(depth.channels) +
                                    " channels and " + std::to_string(depth.data.size()) + " values.");
    if (ids.width != depth.width || ids.height != depth.height || ids.data.size() != n)
        throw std::invalid_argument(std::string(function) + ": the " + which + " id image (" +
                                    sizeText(ids.width, ids.height) + ", " + std::to_string(ids.data.size()) +
                                    " values) does not match its depth image (" + sizeText(depth.width, depth.height) +
                                    ").");
}

// The camera matrices exactly as the renderer builds them (float, aspect = w / h as float),
// then widened: the inverse is taken in double so unprojecting and reprojecting adds no
// error beyond the stored depth's own.
struct CameraMaths {
    glm::dmat4 projection, viewProjection, inverseProjection, inverseViewProjection;
    double nearPlane, farPlane;
    int width, height;

    CameraMaths(const scene::CameraState& camera, int w, int h)
        : projection(scene::projectionMatrix(camera, float(w) / float(h))),
          viewProjection(projection * glm::dmat4(scene::viewMatrix(camera))),
          inverseProjection(glm::inverse(projection)),
          inverseViewProjection(glm::inverse(viewProjection)),
          nearPlane(camera.nearPlane),
          farPlane(camera.farPlane),
          width(w),
          height(h) {}

    glm::dvec2 ndcOfPixelCentre(int x, int y) const {
        return {2.0 * (x + 0.5) / width - 1.0, 1.0 - 2.0 * (y + 0.5) / height};
    }
    glm::dvec3 unproject(glm::dvec2 ndc, double windowDepth) const {
        const glm::dvec4 p = inverseViewProjection * glm::dvec4(ndc, 2.0 * windowDepth - 1.0, 1.0);
        return glm::dvec3(p) / p.w;
    }
    // Eye-space depth (distance along the view axis) of a stored window depth at a pixel.
    double eyeDepth(int x, int y, double windowDepth) const {
        const glm::dvec4 p = inverseProjection * glm::dvec4(ndcOfPixelCentre(x, y), 2.0 * windowDepth - 1.0, 1.0);
        return -p.z / p.w;
    }
    // Clip space to top-down continuous image coordinates.
    glm::dvec2 toImage(const glm::dvec4& clip) const {
        return {(clip.x / clip.w + 1.0) * 0.5 * width, (1.0 - clip.y / clip.w) * 0.5 * height};
    }
};

// The model matrix the renderer draws an object with (renderer/conventional.cpp), in double.
glm::dmat4 modelMatrix(const scene::ObjectState& o) {
    const glm::dvec3 scale = o.shape == scene::Shape::Sphere ? glm::dvec3(o.halfExtents.x) : glm::dvec3(o.halfExtents);
    return glm::translate(glm::dmat4(1.0), glm::dvec3(o.position)) * glm::mat4_cast(glm::dquat(o.orientation)) *
        glm::scale(glm::dmat4(1.0), scale);
}

std::map<std::uint32_t, glm::dmat4> modelMatrices(const scene::SceneSnapshot& snapshot, const char* which) {
    std::map<std::uint32_t, glm::dmat4> out;
    for (const auto& o : snapshot.objects) {
        if (!out.emplace(o.id, modelMatrix(o)).second)
            throw std::invalid_argument(std::string("trueCorrespondence: the ") + which + " snapshot lists object id " +
                                        std::to_string(o.id) + " twice.");
    }
    return out;
}

// Display world -> source world for each object: source model * inverse display model, so a
// surface point keeps its object-space position. NaN matrix where the object is absent from
// the source (it did not exist then: no correspondence).
std::map<std::uint32_t, glm::dmat4> motions(const scene::SceneSnapshot& display, const scene::SceneSnapshot& source) {
    const auto from = modelMatrices(display, "display");
    const auto to = modelMatrices(source, "source");
    std::map<std::uint32_t, glm::dmat4> out;
    for (const auto& [id, model] : from) {
        const auto it = to.find(id);
        out[id] = it == to.end() ? glm::dmat4(kNaN) : it->second * glm::inverse(model);
    }
    // The hangar never moves, whatever a snapshot says about id 1.
    out[scene::kIdHangar] = glm::dmat4(1.0);
    return out;
}

bool hasNaN(glm::dvec2 v) { return std::isnan(v.x) || std::isnan(v.y); }

}  // namespace

Correspondence trueCorrespondence(const scene::FrameDescription& display, const image::ImageF& displayDepth,
                                  const image::ImageU32& displayIds, const scene::FrameDescription& source,
                                  const image::ImageF& sourceDepth, const image::ImageU32& sourceIds) {
    checkFrameImages("trueCorrespondence", "display", displayDepth, displayIds);
    checkFrameImages("trueCorrespondence", "source", sourceDepth, sourceIds);
    const int w = displayDepth.width, h = displayDepth.height;
    const int sw = sourceDepth.width, sh = sourceDepth.height;
    const CameraMaths from(display.camera, w, h);
    const CameraMaths to(source.camera, sw, sh);
    const auto motion = motions(display.scene, source.scene);

    Correspondence out;
    out.width = w;
    out.height = h;
    out.sourceWidth = sw;
    out.sourceHeight = sh;
    out.coords.assign(std::size_t(w) * h, glm::vec2(float(kNaN)));
    out.visible.assign(std::size_t(w) * h, 0);

    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(y) * w + x;
            const std::uint32_t id = displayIds.at(x, y);
            const glm::dvec2 ndc = from.ndcOfPixelCentre(x, y);

            glm::dvec4 clip;  // the point (or sky direction) in the source's clip space
            if (id == scene::kIdNone) {
                // Sky: a direction at infinity. Two points on the pixel's view ray give it; w = 0
                // drops the source camera's translation, so only its rotation applies.
                const glm::dvec3 dir = from.unproject(ndc, 1.0) - from.unproject(ndc, 0.0);
                clip = to.viewProjection * glm::dvec4(dir, 0.0);
            } else {
                const auto it = motion.find(id);
                if (it == motion.end())
                    throw std::invalid_argument("trueCorrespondence: display pixel (" + std::to_string(x) + ", " +
                                                std::to_string(y) + ") shows object id " + std::to_string(id) +
                                                ", which the display snapshot does not list.");
                const glm::dvec3 p = from.unproject(ndc, displayDepth.at(x, y)[0]);
                clip = to.viewProjection * (it->second * glm::dvec4(p, 1.0));
            }
            // Behind the source camera (or absent from the source): no image position; a
            // projection through w <= 0 would land mirrored inside the image.
            if (!(clip.w > 0.0)) continue;
            const glm::dvec2 uv = to.toImage(clip);
            out.coords[i] = glm::vec2(uv);
            if (hasNaN(uv) || uv.x < 0.0 || uv.y < 0.0 || uv.x >= sw || uv.y >= sh) continue;

            // The 2x2 source pixels whose centres surround uv (clipped at the image border).
            const int x0 = int(std::floor(uv.x - 0.5)), y0 = int(std::floor(uv.y - 0.5));
            if (id == scene::kIdNone) {
                bool sky = false;
                for (int sy = std::max(y0, 0); sy <= std::min(y0 + 1, sh - 1); ++sy)
                    for (int sx = std::max(x0, 0); sx <= std::min(x0 + 1, sw - 1); ++sx)
                        sky = sky || sourceIds.at(sx, sy) == scene::kIdNone;
                out.visible[i] = sky;
                continue;
            }
            // For a point, clip.w is its eye-space depth in the source (perspective projection).
            const double depth = clip.w;
            if (depth < to.nearPlane || depth > to.farPlane) continue;
            double lo = std::numeric_limits<double>::infinity(), hi = -lo;
            for (int sy = std::max(y0, 0); sy <= std::min(y0 + 1, sh - 1); ++sy) {
                for (int sx = std::max(x0, 0); sx <= std::min(x0 + 1, sw - 1); ++sx) {
                    if (sourceIds.at(sx, sy) != id) continue;
                    const double d = to.eyeDepth(sx, sy, sourceDepth.at(sx, sy)[0]);
                    lo = std::min(lo, d);
                    hi = std::max(hi, d);
                }
            }
            const double tol = kDepthToleranceRelative * depth + kDepthToleranceAbsolute;
            out.visible[i] = depth >= lo - tol && depth <= hi + tol;  // false when no same-id pixel (lo = +inf)
        }
    }
    return out;
}

namespace {

// The sources a mask is made of: at least one, none null, all of one display size.
void checkSources(const std::vector<const Correspondence*>& perSource, const char* caller) {
    if (perSource.empty())
        throw std::invalid_argument(std::string(caller) + ": needs at least one source's correspondence, got none.");
    for (std::size_t s = 0; s < perSource.size(); ++s) {
        const Correspondence* c = perSource[s];
        if (c == nullptr)
            throw std::invalid_argument(std::string(caller) + ": source " + std::to_string(s) + " is null.");
        const std::size_t n = std::size_t(std::max(c->width, 0)) * std::size_t(std::max(c->height, 0));
        if (c->width != perSource[0]->width || c->height != perSource[0]->height || c->visible.size() != n ||
            c->coords.size() != n)
            throw std::invalid_argument(std::string(caller) + ": source " + std::to_string(s) + " is " +
                                        sizeText(c->width, c->height) + " with " + std::to_string(c->visible.size()) +
                                        " visibility entries and " + std::to_string(c->coords.size()) +
                                        " coordinates; source 0 is " +
                                        sizeText(perSource[0]->width, perSource[0]->height) + ".");
    }
}

}  // namespace

std::vector<std::uint8_t> disoccludedMask(const std::vector<const Correspondence*>& perSource) {
    checkSources(perSource, "disoccludedMask");
    std::vector<std::uint8_t> mask(perSource[0]->visible.size(), 1);
    for (const Correspondence* c : perSource)
        for (std::size_t i = 0; i < mask.size(); ++i)
            if (c->visible[i]) mask[i] = 0;
    return mask;
}

UnseenMasks unseenMasks(const std::vector<const Correspondence*>& perSource) {
    checkSources(perSource, "unseenMasks");
    const std::vector<std::uint8_t> unseen = disoccludedMask(perSource);
    UnseenMasks out;
    out.border.assign(unseen.size(), 0);
    out.occluded.assign(unseen.size(), 0);
    for (std::size_t i = 0; i < unseen.size(); ++i) {
        if (!unseen[i]) continue;
        bool inside = false;
        for (const Correspondence* c : perSource) {
            const glm::vec2 p = c->coords[i];  // NaN compares false: no position is outside
            inside =
                inside || (p.x >= 0.0f && p.y >= 0.0f && p.x <= float(c->sourceWidth) && p.y <= float(c->sourceHeight));
        }
        (inside ? out.occluded : out.border)[i] = 1;
    }
    return out;
}

double maskedMeanAbsoluteError(const image::ImageRGBA8& method, const image::ImageRGBA8& truth,
                               const std::vector<std::uint8_t>& mask) {
    const std::size_t n = std::size_t(std::max(truth.width, 0)) * std::size_t(std::max(truth.height, 0));
    if (method.width != truth.width || method.height != truth.height || method.pixels.size() != 4 * n ||
        truth.pixels.size() != 4 * n || mask.size() != n)
        throw std::invalid_argument("maskedMeanAbsoluteError: the method image (" +
                                    sizeText(method.width, method.height) + ", " +
                                    std::to_string(method.pixels.size()) + " bytes), the truth (" +
                                    sizeText(truth.width, truth.height) + ", " + std::to_string(truth.pixels.size()) +
                                    " bytes) and the mask (" + std::to_string(mask.size()) + " entries) must agree.");
    // Integer sum: exact for any image up to 16384x16384 (at most 765 per pixel).
    std::uint64_t sum = 0, pixels = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (!mask[i]) continue;
        ++pixels;
        for (int c = 0; c < 3; ++c)
            sum += std::uint64_t(std::abs(int(method.pixels[4 * i + c]) - int(truth.pixels[4 * i + c])));
    }
    return pixels == 0 ? kNaN : double(sum) / (3.0 * double(pixels));
}

void CorrespondenceAccumulator::add(const std::vector<glm::vec2>& reported, const Correspondence& truth) {
    const std::size_t n = std::size_t(std::max(truth.width, 0)) * std::size_t(std::max(truth.height, 0));
    if (truth.coords.size() != n || truth.visible.size() != n || reported.size() != n)
        throw std::invalid_argument("CorrespondenceAccumulator::add: " + std::to_string(reported.size()) +
                                    " reported coordinates, the truth is " + sizeText(truth.width, truth.height) +
                                    " with " + std::to_string(truth.coords.size()) + " coordinates and " +
                                    std::to_string(truth.visible.size()) + " visibility entries.");
    constexpr double kThresholds[3] = {0.1, 0.5, 1.0};
    for (std::size_t i = 0; i < n; ++i) {
        // Distance in double; NaN on either side (no claim, or no true position) compares false
        // against every threshold, i.e. counts as an error of +infinity.
        const double dx = double(reported[i].x) - double(truth.coords[i].x);
        const double dy = double(reported[i].y) - double(truth.coords[i].y);
        const double error = std::sqrt(dx * dx + dy * dy);
        const bool hit = truth.visible[i] != 0;
        ++samples_;
        if (hit) ++hitSamples_;
        for (int k = 0; k < 3; ++k) {
            if (error < kThresholds[k]) {
                ++all_[k];
                if (hit) ++hit_[k];
            }
        }
    }
}

CorrespondenceStats CorrespondenceAccumulator::stats() const {
    CorrespondenceStats s;
    s.samples = samples_;
    s.hitSamples = hitSamples_;
    const auto share = [](std::size_t count, std::size_t total) {
        return total == 0 ? kNaN : double(count) / double(total);
    };
    s.allLt0p1 = share(all_[0], samples_);
    s.allLt0p5 = share(all_[1], samples_);
    s.allLt1 = share(all_[2], samples_);
    s.hitLt0p1 = share(hit_[0], hitSamples_);
    s.hitLt0p5 = share(hit_[1], hitSamples_);
    s.hitLt1 = share(hit_[2], hitSamples_);
    return s;
}

}  // namespace warplab::bench
