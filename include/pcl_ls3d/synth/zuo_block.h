#pragma once
/// \file zuo_block.h
/// \brief Strip blocks shaped like Zuo et al. (2012) Table 1, with per-strip errors of Table 2's
///        magnitudes: three parallel strips, strip 2 the reference (identity), strips 1 and 3
///        displaced by the LND corrections Zuo estimated for Hebei (urban) and Henan
///        (mountainous) — translations up to 3.6 m, angles up to 0.078°, scale −80 to +46 ppm
///        (Hebei 3&2's −220 ppm capped at −80 ppm) — applied about each strip's centre.
///
/// Table 1 at scale 1: strips 1999 m × ~1550 m (Hebei) / ~2510 m (Henan) across; side overlap
/// 17 % / 14 %; 4.1 / 2.3 pts/m²; noise σ 5 cm. `scale` shrinks length and swath alike (the
/// overlap share, density and errors stay).

#include <pcl_ls3d/synth/strip_block.h>

namespace pcl_ls3d {
namespace synth {

/// Settings of a Zuo Table 1-like block of the URBAN or MOUNTAIN scene.
StripSettings
zuoBlock(LandscapeType type, double scale = 1.0, std::uint32_t seed = 1);

/// Zuo's Table 2 LND corrections of strips 1 and 3 for the scene (tx ty tz [m], φ ω κ [rad],
/// m), strip 2 the identity; the per-strip `errors` of zuoBlock().
std::vector<Vector7d>
zuoErrors(LandscapeType type);

}  // namespace synth
}  // namespace pcl_ls3d
