#include "render/output.h"

#include <algorithm>
#include <cmath>

#include "base/error.h"

namespace svbrdf {

Image to_display(const Image& linear, float exposure, const ColorConfig& color) {
  Image out = linear;
  const float scale = std::exp2(exposure);
  for (float& v : out.pixels) v *= scale;
  color.linear_to_display(out);
  return out;
}

void write_outputs(const Film& film, const OutputOptions& o, const ColorConfig& color) {
  namespace fs = std::filesystem;
  auto ensure_dir = [](const fs::path& p) {
    if (!p.has_parent_path()) return;
    std::error_code ec;
    fs::create_directories(p.parent_path(), ec);
    if (ec) throw input_error(p.string(), "cannot create the output folder: " + ec.message());
  };
  ensure_dir(o.exr);
  const Image radiance = film.radiance();
  write_image(o.exr, radiance, o.float32 ? PixelFormat::float32 : PixelFormat::half);
  fs::path png = o.png;
  if (png.empty()) png = fs::path(o.exr).replace_extension(".png");
  ensure_dir(png);
  write_image(png, to_display(radiance, o.exposure, color), PixelFormat::uint8);
  if (o.aovs) {
    auto aov = [&](const char* name) {
      fs::path p = o.exr;
      p.replace_extension(std::string(".") + name + ".exr");
      return p;
    };
    const PixelFormat f = o.float32 ? PixelFormat::float32 : PixelFormat::half;
    write_image(aov("albedo"), film.albedo(), f);
    write_image(aov("normal"), film.normal(), f);
    write_image(aov("depth"), film.depth(), PixelFormat::float32);
    write_image(aov("level"), film.mip_level(), f);
  }
}

}  // namespace svbrdf
