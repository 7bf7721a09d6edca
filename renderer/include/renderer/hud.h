// The heads-up display, drawn last over a displayed frame: the reticle or the cursor, the
// HIT / MISS / TIMEOUT banner of the pause after a shot, a line of phase text, a question
// screen (a scale, a choice, or text typed on screen), a screen of instructions and a photodiode
// marker. Text comes from SDL2_ttf with a DejaVu font, uploaded as textures; the object-id
// attachment is left untouched so the id under the reticle still names what the scene shows.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/conventional.h"

namespace warplab::renderer {

// A question screen, one of three kinds (the games' questions after a block). Boxes are in the
// frame's pixels (x right, y down; x, y, width, height), laid out by the game; the HUD draws
// into them.
struct HudQuestion {
    enum class Kind : std::uint8_t {
        Likert,  // a row of boxes, each labelled with its value, the end labels under its outer edges
        Choice,  // a list of wide boxes, each its number and its option, left-aligned
        Text,  // one box, the field: what was typed so far and a caret, the hint under it
    };
    Kind kind = Kind::Likert;
    std::string prompt;  // the statement or question, above the boxes
    std::vector<glm::vec4> boxes;
    std::vector<std::string> boxLabels;  // what box i says (Likert, choice); a box without one is bare
    int highlighted = -1;  // the box under the cursor
    std::string minLabel, maxLabel;  // Likert: under the first and the last box
    std::string typed;  // text: the answer so far (UTF-8); its end shows when it is wider than the field
    std::string hint;  // how to answer, under everything else (the game's words); "" = none
};

// A square for a photodiode, flush in a corner of the frame: black, or white on the frame that
// answers a press. Drawn last, opaque, so a sensor over it sees one clean edge.
struct HudPhotonMarker {
    enum class Corner : std::uint8_t { TopLeft, TopRight, BottomLeft, BottomRight };
    Corner corner = Corner::TopLeft;
    bool lit = false;
    // Its side: 4 % of the frame's height, at least 16 pixels (a sensor's aperture), whole
    // pixels so that its edge falls between two.
    static int sidePixels(int frameWidth, int frameHeight);
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
    std::optional<HudPhotonMarker> photonMarker;  // none: no marker
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
