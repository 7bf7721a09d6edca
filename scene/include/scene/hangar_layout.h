// The hangar hallway's dimensions, shared by the asset generator (assets/make_hangar.cpp),
// the physics box the target bounces in, and the camera's default placement. One place, so
// the target never bounces inside a wall the renderer draws somewhere else.
//
// World frame: metres, y up, the hallway runs along -z; the camera stands near z = 0 and
// looks down the hallway towards the far end, which opens onto space (so some pixels see
// nothing but the far plane).
#pragma once

namespace warplab::scene {

struct HangarLayout {
    // Outer shell: wall panels at x = +-kHalfWidth, floor at y = 0, ceiling at y = kHeight.
    static constexpr float kHalfWidth = 8.0f;
    static constexpr float kHeight = 9.0f;
    // End wall behind the camera, and the far end of the hallway (an open door onto space).
    static constexpr float kBackZ = 2.0f;
    static constexpr float kFarZ = -60.0f;

    // Structural ribs: rectangular frames across the hallway at z = kFirstRibZ - i * kRibSpacing
    // (i = 0 .. kRibCount-1), kRibThickness deep along z, protruding kRibDepth inward from
    // walls, ceiling and floor. The ribs are spaced so that none stands in the target's plane
    // (between the first and second rib for any usual field of view).
    static constexpr float kFirstRibZ = -3.0f;
    static constexpr float kRibSpacing = 8.0f;
    static constexpr int kRibCount = 7;
    static constexpr float kRibThickness = 0.5f;
    static constexpr float kRibDepth = 0.5f;

    // The clear cross-section inside the ribs: where the target may bounce.
    // 15 m x 8 m, close to the display's 16:9 as the thesis' hallway (seed 004 section 5.3.2).
    static constexpr float kClearMinX = -kHalfWidth + kRibDepth;
    static constexpr float kClearMaxX = kHalfWidth - kRibDepth;
    static constexpr float kClearMinY = kRibDepth;
    static constexpr float kClearMaxY = kHeight - kRibDepth;

    // Default eye: centred in the clear cross-section, so the view volume meets the walls at
    // about the same distance horizontally and vertically.
    static constexpr float kEyeX = 0.0f;
    static constexpr float kEyeY = 0.5f * (kClearMinY + kClearMaxY);
    static constexpr float kEyeZ = 0.0f;
};

}  // namespace warplab::scene
