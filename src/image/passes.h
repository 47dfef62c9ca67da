#pragma once

namespace streak {

// The passes a render is asked for besides the beauty (--passes), written as named channels of
// its Image (exposure::PassFrame fills them):
// - depth: "Z", the coverage-weighted mean view depth of what shows in the pixel over its samples
//   and the shutter, and "Z.min", the nearest; 1e10 (Blender's value) where nothing shows;
// - objectId, materialId: Cryptomatte layers "CryptoObject00..." and "CryptoMaterial00...",
//   `cryptoRanks` ranked (ID, coverage) pairs of the scene's object (mesh) and material names.
// - deep: a DeepImage beside the colour (Image::deep): per pixel, its visible surfaces as deep
//   samples, at most `deepSamples` of them (plus the background's, when `deepBackground`).
struct PassRequest {
    bool depth = false;
    bool objectId = false;
    bool materialId = false;
    int cryptoRanks = 6;
    bool deep = false;
    int deepSamples = 16;
    bool deepBackground = true;

    bool any() const { return depth || objectId || materialId || deep; }
};

// The depth passes' value where nothing shows (Blender's).
inline constexpr float kEmptyDepth = 1e10f;

}  // namespace streak
