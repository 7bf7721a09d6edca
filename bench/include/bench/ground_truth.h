// The ground truth the benchmark judges upconversion methods with: for every pixel of a
// displayed frame, where its surface point exactly was in a source frame (the scene-assisted
// correspondence of seed 000 section 9), whether it was visible there, and the error
// statistics of seed 000 Figure 11. Plain C++ on read-back images, no GL: the scene's exact
// rigid motion is known, so nothing is estimated.
//
// Pixel coordinates are continuous and top-down: pixel column i, row j (row 0 at the top) has
// its centre at (i + 0.5, j + 0.5). Errors: std::invalid_argument naming the function and the
// mismatched sizes (or the inconsistent input).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "image/image.h"
#include "scene/scene.h"

namespace warplab::bench {

// Where each display pixel's surface point was in one source frame.
struct Correspondence {
    int width = 0, height = 0;  // the display frame's size
    int sourceWidth = 0, sourceHeight = 0;  // the source image's size, which coords are in
    // Source-image coordinates per display pixel (row-major, top-down). May lie outside the
    // image. NaN where the point has no position in the source: its object is absent from the
    // source snapshot, or the point is behind the source camera.
    std::vector<glm::vec2> coords;
    // 1 if the point is visible in the source frame: inside the image, in front of the camera
    // between its near and far planes, and consistent with the source G-buffer around it.
    // Among the 2x2 source pixels whose centres surround the point (its bilinear footprint),
    // those with the point's id must exist and the point's eye-space depth d must lie within
    // [min - tol, max + tol] of their depths, tol = kDepthToleranceRelative * d +
    // kDepthToleranceAbsolute. Any same-id pixel matching within tol passes; so does a point
    // between its neighbours on a surface seen edge-on (depth varies fast across pixels there),
    // and one at a silhouette where only some neighbours show its object. Sky (id 0): one of
    // the 2x2 pixels is sky.
    std::vector<std::uint8_t> visible;
};

// 1 % of the eye-space depth covers the depth change over the up to 0.71 px to the farthest
// 2x2 neighbour on surfaces up to ~80 degrees from face-on at 540 rows (steeper ones pass the
// span test), and float32 window-depth quantisation (relative 1.2e-6 per metre of depth,
// 2.4e-4 at the 200 m far plane); the 5 mm floor covers points close to the near plane. A point
// hidden by another part of its own object lies further by that part's thickness (the
// target's diameter, 0.7 m at 7 m: 10 %), well outside it.
inline constexpr double kDepthToleranceRelative = 0.01;
inline constexpr double kDepthToleranceAbsolute = 0.005;  // metres

// Display frame rendered at display.camera / display.scene.time, source likewise; depth images
// are window-space depth in [0, 1] as the G-buffer stores it (1 = far plane / sky), ids are
// scene::ObjectId. Each surface point is moved back along its object's exact rigid motion
// (position and orientation of the object with the same id in each snapshot; the hangar,
// id 1, is static) and projected with the source camera. Sky pixels are directions at
// infinity: only the camera rotation applies. Display and source may differ in size. Throws
// if an id other than 0 and 1 in displayIds is missing from display.scene (its motion would be
// unknown) or a snapshot lists an id twice.
Correspondence trueCorrespondence(const scene::FrameDescription& display, const image::ImageF& displayDepth,
                                  const image::ImageU32& displayIds, const scene::FrameDescription& source,
                                  const image::ImageF& sourceDepth, const image::ImageU32& sourceIds);

// 1 for pixels whose ground-truth surface point is visible in none of the given sources (all
// the same size; at least one).
std::vector<std::uint8_t> disoccludedMask(const std::vector<const Correspondence*>& perSource);

// The pixels a frame's sources cannot show, split by why, so that one pair of masks serves
// every method of the frame (the bench passes the latest 15 Hz source). `border`: the true surface point lies outside every source image (or has no
// position there: behind the camera, absent): content turned or moved into view, which no
// source holds. `occluded`: inside at least one source image but visible in none: hidden
// behind something there, a true disocclusion. Together they are disoccludedMask(perSource).
struct UnseenMasks {
    std::vector<std::uint8_t> border, occluded;
};
UnseenMasks unseenMasks(const std::vector<const Correspondence*>& perSource);

// Mean absolute error over R, G and B (0..255 units) between a method's frame and the ground
// truth, over pixels whose mask entry is non-zero; NaN when none is (callers write an empty
// CSV field).
double maskedMeanAbsoluteError(const image::ImageRGBA8& method, const image::ImageRGBA8& truth,
                               const std::vector<std::uint8_t>& mask);

// Shares of display pixels whose reported correspondence lies within 0.1, 0.5 and 1 px of the
// true one (strictly less), over all pixels and over pixels whose true point is visible in the
// source (seed 000 Figure 11, E_total^all and E_total^hit). NaN shares where there are no
// samples.
struct CorrespondenceStats {
    double allLt0p1 = 0, allLt0p5 = 0, allLt1 = 0;
    double hitLt0p1 = 0, hitLt0p5 = 0, hitLt1 = 0;
    std::size_t samples = 0, hitSamples = 0;
};

// Accumulates one (reported, truth) pair per add(), so a two-source method pools both
// sources' samples. `reported` uses the Correspondence convention; a NaN component means the
// method claims no correspondence there and counts as an error of +infinity, as does a
// truth coordinate that is NaN (the point has no source position to find).
class CorrespondenceAccumulator {
public:
    void add(const std::vector<glm::vec2>& reported, const Correspondence& truth);
    CorrespondenceStats stats() const;

private:
    std::size_t samples_ = 0, hitSamples_ = 0;
    std::size_t all_[3] = {0, 0, 0};
    std::size_t hit_[3] = {0, 0, 0};
};

}  // namespace warplab::bench
