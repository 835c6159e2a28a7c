#pragma once
/// The fixed colours of every render: one colour per SRP id (the same plane
/// has the same colour in every image and every storey), one per storey, the
/// trajectories, the map greys and the height scale. No palette colour is a
/// grey (r = g = b), so map points and text never take an SRP's colour.
#include <vector>

#include "render/figure.h"

namespace storey::render {

/// Colour of global SRP `id` (>= 0). The first kSrpPaletteSize ids get
/// pairwise different colours; further ids repeat the palette.
Rgb srpColour(int id);
inline constexpr int kSrpPaletteSize = 256;

/// Colour of storey `index`; index < 0 (no storey) is grey.
Rgb storeyColour(int index);

/// Map points in inspection views: a grey from dark (t = 0) to light (t = 1).
Rgb mapGrey(double t);

/// The height scale (viridis), t in [0, 1] clamped.
Rgb heightColour(double t);
/// `n` samples of heightColour from 0 to 1 (for the colour bar).
std::vector<Rgb> heightScale(int n = 64);

namespace colours {
inline constexpr Rgb kText{20, 20, 20};
inline constexpr Rgb kTrajectory{0, 0, 0};
inline constexpr Rgb kTruth{0, 0, 0};
inline constexpr Rgb kEstimate{214, 39, 40};
inline constexpr Rgb kComparison{31, 119, 180};
inline constexpr Rgb kStairs{90, 90, 90};
inline constexpr Rgb kFloorLine{60, 60, 60};
inline constexpr Rgb kFootprint{120, 120, 120};
inline constexpr Rgb kContext{200, 200, 200};  ///< map behind trajectories
}  // namespace colours

}  // namespace storey::render
