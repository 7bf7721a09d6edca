// Making the frames a session displayed, shared by `replay --render` and live
// sessions in a window, so both show exactly what the mode makes.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "game/game.h"
#include "renderer/conventional.h"
#include "renderer/hud.h"
#include "renderer/upconvert.h"

namespace warplab::present {

// The HUD of a shown frame: reticle or cursor, banner, phase text, question screen. Display
// pixels are scaled to the frame's by toFrameX/Y.
renderer::HudContent hudFor(const game::ShownFrame& shown, double toFrameX, double toFrameY);
// The HUD's photodiode marker in `corner`, black; none when it is off.
std::optional<renderer::HudPhotonMarker> hudPhotonMarker(protocol::PhotonMarker corner);

// Makes each displayed frame the way its mode makes it, from the conventional renders it
// keeps: a held or rendered frame is its source copied (hold120); warped and interpolated
// frames use the mode's method.
class FrameMaker {
public:
    // `rendering`: the protocol's guard band (warp modes' sources) and supersampling.
    FrameMaker(const renderer::DataPaths& paths, int width, int height, const protocol::RenderSettings& rendering);

    // Call for every frame the game steps, shown or not: held, lagged and warped frames need
    // the sources rendered before them.
    void keepSource(const game::ShownFrame& shown);
    // Draws the frame `shown` into `display` (no HUD).
    void make(const game::ShownFrame& shown, renderer::DisplayFrame& display);
    // The kept source whose copy make() would show as `shown`, pixel for pixel (a held or rendered
    // frame of a source rendered without a guard band), or null: a reader of the displayed
    // pixels may read them there and skip the copy.
    const renderer::SourceFrame* shownUnchanged(const game::ShownFrame& shown) const;
    // What the maker changed since the last call, one sentence each: a condition's method the
    // GL context cannot run, shown by its fallback (warp-splat by warp-sparse8 below OpenGL 4.3).
    std::vector<std::string> takeNotes();

private:
    renderer::UpconversionMethod& method(const std::string& name);
    // A source as rendered, and the frame it was asked to show (its camera not widened).
    struct Kept {
        std::unique_ptr<renderer::SourceFrame> frame;
        scene::FrameDescription shows;
    };
    Kept render(const scene::FrameDescription& frame, renderer::GuardBand band,
                const scene::FrameDescription* flowTo = nullptr);

    renderer::DataPaths paths_;
    renderer::ConventionalRenderer conventional_;
    int width_, height_;
    renderer::GuardBand warpBand_;  // for the sources of warp modes
    std::map<std::int64_t, Kept> sources_;  // by session frame
    // Source frames no longer needed, for the next renders: a G-buffer made anew per render (its
    // textures and framebuffer) costs llvmpipe more than drawing a small frame into it.
    std::vector<std::unique_ptr<renderer::SourceFrame>> spare_;
    void release(Kept& kept);
    std::map<std::string, std::unique_ptr<renderer::UpconversionMethod>> methods_;  // by the name asked for
    std::vector<std::string> notes_;
};

}  // namespace warplab::present
