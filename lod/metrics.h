#pragma once
// The metrics of the distance-LOD comparison, over the object's pixels:
//
//   relative MSE   e = Σ_p Σ_c (X − R)² / Σ_p Σ_c R²           (p over the mask, c over R, G, B)
//   flux bias      b = Σ_p Σ_c X / Σ_p Σ_c R − 1                (the total radiant flux toward the
//                                                                camera, relative)
//   peak ratio     q = max_p Y(X) / max_p Y(R)                  (Y: Rec.709 luminance; the brightest
//                                                                highlight pixel against the
//                                                                reference's)
//
// X is the image under test, R the reference (the first ground-truth render). The noise floor is
// the same metrics between two ground-truth renders that differ only in their seed.
//
// The object mask: the pixels whose depth AOV is positive in the reference render, i.e. where some
// camera sample hit geometry. The LOD scenes fill the frame (scenes/lod_scenes.h), so there it is
// every pixel; the definition stays right for scenes that do not.
#include <cstdint>
#include <vector>

#include "textures/image.h"

namespace svbrdf {

struct LodMetrics {
  double rel_mse = 0.0;
  double flux_bias = 0.0;
  double peak_ratio = 1.0;
};

// 1 where depth > 0. `depth` is a one-channel image (Film::depth()).
std::vector<std::uint8_t> object_mask(const Image& depth);

// Throws svbrdf::Error (internal) when the images differ in size or the mask selects nothing or the
// reference is black over it.
LodMetrics compare_images(const Image& x, const Image& reference, const std::vector<std::uint8_t>& mask);

double luminance(const Image& im, int x, int y);

// The relative standard deviation σ of one render's total flux (Σ_p Σ_c), estimated from two renders
// that differ only in their seed: per pixel, (S₁ − S₂)²/2 estimates the variance of S (S: the sum of
// the pixel's channels) and pixels are independent, so Var(Σ S) ≈ Σ_p (S₁ − S₂)²/2; σ = √that / Σ S₁.
// A flux bias measured against one ground truth carries about √2·σ of noise (its own and the
// image's, when both have similar variance).
double flux_noise(const Image& a, const Image& b, const std::vector<std::uint8_t>& mask);

// A false-color error image: per pixel |Y(X) − Y(R)| / mean_mask Y(R), mapped through a perceptual
// color map (black → purple → orange → yellow, like matplotlib's "inferno") from 0 to `full_scale`
// (clamped); pixels outside the mask are mid gray. RGB in [0, 1], display-referred.
Image false_color_error(const Image& x, const Image& reference, const std::vector<std::uint8_t>& mask,
                        double full_scale);
// The color map itself, t ∈ [0, 1] (for the legend).
void error_color(double t, float rgb[3]);

}  // namespace svbrdf
