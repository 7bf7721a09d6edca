// The heads-up display, drawn last over a displayed frame: the reticle or the cursor, the
// HIT / MISS / TIMEOUT banner of the pause after a shot, a line of phase text, the rating
// screen and a screen of instructions. Text comes from
// SDL2_ttf with a DejaVu font, uploaded as textures; the object-id attachment is left
// untouched so the id under the reticle still names what the scene shows.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/conventional.h"

namespace warplab::renderer {

// A rating screen: the statement, and one box per answer to click, in the frame's pixels
// (x right, y down; x, y, width, height), numbered from firstValue.
struct HudQuestion {
    std::string prompt;
    std::vector<glm::vec4> boxes;
    int highlighted = -1;  // the box under the cursor
    int firstValue = 1;
    std::string minLabel, maxLabel;  // under the first and the last box
};

struct HudContent {
    bool backdrop = false;  // a plain dark screen under everything else (no scene shown)
    bool reticle = true;
    std::optional<glm::vec2> cursor;  // the click game's cursor, frame pixels, x right, y down
    std::optional<HudQuestion> question;
    std::string banner;  // e.g. "HIT"; empty = none
    bool bannerGood = false;  // green when true, red when false
    std::string status;  // small text at the top, e.g. "Training: level 4"; empty = none
    // Text to read in the middle of the screen (a phase's instructions), wrapped to the frame's
    // width; a line break starts a new line. Empty = none.
    std::string paragraph;
};

class HudRenderer {
public:
    // Throws AssetError naming the font file when it is missing or unreadable.
    HudRenderer(const DataPaths& paths, const std::string& fontPath = kDefaultFont);
    ~HudRenderer();
    HudRenderer(const HudRenderer&) = delete;
    HudRenderer& operator=(const HudRenderer&) = delete;

    // Draws over the colour attachment of `target` (a G-buffer or a display frame's buffer).
    void draw(const HudContent& content, GBuffer& target);

    static constexpr const char* kDefaultFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf";

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    std::string fontPath_;
};

}  // namespace warplab::renderer
