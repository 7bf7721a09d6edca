// What the simulated participant perceives of a displayed frame, from its pixels only: the
// objects in it (by the id image's segmentation, where and how big and what colour from the
// pixels), pictures of the scene to recognise a view and how far it turned, and the text and
// pointer on screen. No GL: the eye (participants/eye.h) reads the frame back and calls these.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "game/game.h"
#include "image/image.h"

namespace warplab::participants {

// ---------------------------------------------------------------------------------------------
// Perception

// One object as the displayed image shows it. The id image is the frame's segmentation into
// objects -- what a person sees as one thing -- so identity across frames is the id; where it
// is and how big and what colour come from its pixels only.
struct SeenObject {
    std::uint32_t id = 0;
    glm::dvec2 centre{0.0};  // centroid of its pixels, display pixels (x right, y down, centres at +0.5)
    double radiusPx = 0.0;  // radius of the disc with its area, display pixels
    glm::dvec3 colour{0.0};  // mean displayed colour, 0..1
    int pixels = 0;  // percept pixels it covers
    bool greenish() const { return colour.g > colour.r; }
};

// The game objects (ids from scene::kIdTarget up; hangar and sky are background) in a displayed
// frame read back at the percept resolution, by id. `toDisplay`: display pixels per image pixel
// in x and y. Image rows are top-down (image/image.h).
std::vector<SeenObject> findObjects(const image::ImageU32& ids, const image::ImageRGBA8& colour, glm::dvec2 toDisplay);

// The displayed image's scene -- without the objects in it, which move on their own -- as a
// grey picture of block means: blurred, enough to recognise a view seen before and how far it
// has turned, or sharp, to tell how far it turned since the last frame.
struct Thumbnail {
    int width = 0, height = 0;
    std::vector<float> luma;  // 0..1, rows top-down; NaN where objects cover the cell
    glm::dvec2 cellPx{1.0};  // display pixels per cell in x and y
    float at(int x, int y) const { return luma[static_cast<std::size_t>(y) * width + x]; }
};
// Block means of the luminance over `block` x `block` pixels, leaving out game objects' pixels.
Thumbnail thumbnailOf(const image::ImageRGBA8& colour, const image::ImageU32& ids, int block, glm::dvec2 toDisplay);
// The shift, in cells, that best lines `before` up with `now` (content at c in `before` is at
// c + shift in `now`): least mean squared difference over the cells of the central
// `centreShare` of `now` that overlap `before`, searched within `radius` of `guess`, refined
// below a cell by a parabola through the best cost and its neighbours. Shifts whose overlap
// covers less than `minOverlapShare` of that central part do not count; nullopt if none does.
std::optional<glm::dvec2> bestShift(const Thumbnail& before, const Thumbnail& now, glm::ivec2 guess, glm::ivec2 radius,
                                    double centreShare, double minOverlapShare);
// Where the centre of the view `before` lies in the view `now`, in display pixels from the
// centre of `now`, over the blurred pictures: shifts up to half the picture each way.
std::optional<glm::dvec2> whereViewIs(const Thumbnail& before, const Thumbnail& now);

// Everything the participant gets of one displayed frame.
struct Percept {
    double time = 0.0;  // when the frame was on screen (the display clock)
    bool sceneShown = true;  // false: a screen without the scene (ready, rating, done)
    std::vector<SeenObject> objects;  // found in the displayed image
    Thumbnail picture;  // the scene, blurred (4 x 4 pixel cells)
    Thumbnail detail;  // the scene, sharp (one cell per percept pixel)
    // The pointer drawn into the frame: the reticle at the centre, or the cursor where this
    // frame draws it (so it has the condition's frame rate and lag). Display pixels.
    game::PointerKind pointer = game::PointerKind::None;
    glm::dvec2 pointerAt{0.0};
    // Text on screen.
    std::string phaseText;
    std::string banner;  // "HIT", "MISS", "TIMEOUT" or ""
    bool promptsEnter = false;  // "Press Enter to begin"
    std::optional<game::QuestionPrompt> question;
};

// How far the scene moved on screen from the frame `before` to the frame `now`, display pixels,
// searched around `guessPx` (coarse over the blurred pictures, then sharp): a turn of the view,
// seen in the pictures.
std::optional<glm::dvec2> howFarViewMoved(const Percept& before, const Percept& now, glm::dvec2 guessPx = {});

}  // namespace warplab::participants
