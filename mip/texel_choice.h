#pragma once
// Internal to mip/ (mip.cpp, mip_record_lookup.cpp): which texel a MipTexture lookup reads, the same
// whether its data are in memory or in records.
#include "mip/mip.h"
#include "mip/mip_lookup.h"

namespace svbrdf {

// brdf's stochastic tap among `levels` levels where the texture has its BRDF pyramid (`brdf`) and the
// tint is white or the pyramid `tintable`; the parameter filters' trilinear taps (level −1), read later;
// else the nearest level-0 texel (level0, and brdf on a tinted hit of a texture not built for tints).
inline MipTexture::Choice choose_texel(const MipTexture& texture, WrapModes wrap, TextureFilter filter,
                                       const Footprint& f, const Rgb& tint, float u, bool brdf, bool tintable,
                                       int levels) {
  MipTexture::Choice c{filter, f, tint};
  if (filter == TextureFilter::brdf && brdf && (tint == Rgb(1.0f) || tintable)) {
    const FilterTap t = select_tap(texture.extent(), levels, f, u, wrap);  // O(1), mip_lookup.h
    c.level = t.level, c.i = t.i, c.j = t.j;
  } else if (reads_param_pyramid(filter)) {
    c.level = -1;
  } else {
    const glm::ivec2 t = texture.nearest_texel(f.uv);
    c.level = 0, c.i = t.x, c.j = t.y;
  }
  return c;
}

}  // namespace svbrdf
