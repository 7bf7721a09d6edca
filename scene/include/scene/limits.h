// Limits that the renderer, protocol validation, the command line and the bench must agree on,
// so that a value one of them accepts is never refused by another. Plain values, no GL; help
// texts and error messages are made from them rather than repeating the numbers.
#pragma once

namespace warplab::scene {

// A warp's sources reach at most this share of the displayed width and height beyond each
// side (protocol display.guard_band, --guard-band): 0.5 already renders 4x the pixels.
inline constexpr double kMaxGuardBand = 0.5;

// Supersampling's samples per pixel side at most (protocol display.supersampling, --ssaa):
// 4x4 = 16 samples per pixel.
inline constexpr int kMaxSupersampling = 4;

// Largest side of a render target in pixels (GBuffer, and every --width / --height): the
// GL 4.x minimum of GL_MAX_TEXTURE_SIZE is 16384.
inline constexpr int kMaxImageSize = 16384;

// Smallest display a session or the bench stands for (`warplab render` alone goes down to 1).
inline constexpr int kMinDisplaySize = 16;

}  // namespace warplab::scene
