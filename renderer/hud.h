// The heads-up display, drawn last over a displayed frame: the reticle, the HIT / MISS /
// TIMEOUT banner of the pause after a shot, and a line of phase text. Text comes from
// SDL2_ttf with a DejaVu font, uploaded as textures; the object-id attachment is left
// untouched so the id under the reticle still names what the scene shows.
#pragma once

#include <memory>
#include <string>

#include "renderer/conventional.h"

namespace warplab::renderer {

struct HudContent {
    bool reticle = true;
    std::string banner;        // e.g. "HIT"; empty = none
    bool bannerGood = false;   // green when true, red when false
    std::string status;        // small text at the top, e.g. "Training: level 4"; empty = none
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
