// Making the frames a session displayed, shared by `replay --render` and live
// sessions in a window, so both show exactly what the condition makes.
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

// Makes each displayed frame the way its condition makes it (its schedule's `made`), from the
// conventional renders it keeps: a render shown as it is, or the condition's method for warped and
// interpolated frames, repeated ones too.
//
// A source is rendered when a frame made needs it, not when the game steps the frame that
// renders it: a live session on a machine that cannot keep the refresh steps through display
// frames it does not show, and rendering their sources too would cost the time the skip is
// meant to win back, so that every late frame made the next one later (a picture frozen for
// a minute while the game played on). Rendered late, a source is the same picture: it is drawn
// from the world as the schedule sampled it (ShownFrame::render), never from the time it is drawn.
class FrameMaker {
public:
    // `rendering`: the protocol's guard band (warp conditions' sources) and supersampling.
    FrameMaker(const renderer::DataPaths& paths, int width, int height, const protocol::RenderSettings& rendering);

    // Builds (compiles) now every method the study's conditions make frames with, so that no
    // condition's first frames wait for a shader compiler: a hitch in the stimulus.
    void prepareFor(const game::Study& study);
    // Call for every frame the game steps, shown or not: held, lagged and warped frames need
    // the sources rendered before them. Notes what the frame renders; draws nothing.
    void keepSource(const game::ShownFrame& shown);
    // Draws the frame `shown` into `display` (no HUD).
    void make(const game::ShownFrame& shown, renderer::DisplayFrame& display);
    // The kept source whose copy make() would show as `shown`, pixel for pixel (a held or rendered
    // frame of a source rendered without a guard band), rendered now if it was not yet, or null:
    // a reader of the displayed pixels may read them there and skip the copy.
    const renderer::SourceFrame* shownUnchanged(const game::ShownFrame& shown);
    // How many conventional renders the maker has drawn: what a skipped frame must not add to.
    std::int64_t rendersDrawn() const { return rendersDrawn_; }
    // What the maker changed since the last call, one sentence each: a condition's method the
    // GL context cannot run, shown by its fallback (warp-splat by warp-sparse8 below OpenGL 4.3).
    std::vector<std::string> takeNotes();

private:
    renderer::UpconversionMethod& method(const std::string& name);
    // A source: the frame it was asked to show (its camera not widened), how to render it, and
    // once a frame made has needed it, the render (null until then).
    struct Kept {
        std::unique_ptr<renderer::SourceFrame> frame;
        scene::FrameDescription shows;
        renderer::GuardBand band;
        std::optional<scene::FrameDescription> flowTo;  // bidirectional reprojection's backward flow
    };
    // The kept source, rendered if it was not yet.
    renderer::SourceFrame& rendered(Kept& kept);

    renderer::DataPaths paths_;
    renderer::ConventionalRenderer conventional_;
    int width_, height_;
    renderer::GuardBand warpBand_;  // for the sources of warp conditions
    std::map<std::int64_t, Kept> sources_;  // by session frame
    // Source frames no longer needed, for the next renders: a G-buffer made anew per render (its
    // textures and framebuffer) costs llvmpipe more than drawing a small frame into it.
    std::vector<std::unique_ptr<renderer::SourceFrame>> spare_;
    void release(Kept& kept);
    std::map<std::string, std::unique_ptr<renderer::UpconversionMethod>> methods_;  // by the name asked for
    std::vector<std::string> notes_;
    std::int64_t rendersDrawn_ = 0;
};

}  // namespace warplab::present
