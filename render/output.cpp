#include "render/output.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/output_location.h"

namespace svbrdf {

namespace {

namespace fs = std::filesystem;

fs::path png_path(const OutputOptions& o) { return o.png.empty() ? fs::path(o.exr).replace_extension(".png") : o.png; }

// RGB with an alpha channel after it; `clear_transparent` zeroes the colour where alpha is 0.
Image with_alpha(const Image& rgb, const Image& alpha, bool clear_transparent) {
  Image out(rgb.width, rgb.height, 4);
  for (std::size_t p = 0; p < alpha.pixels.size(); ++p) {
    const float a = alpha.pixels[p];
    for (int c = 0; c < 3; ++c) out.pixels[p * 4 + c] = clear_transparent && a <= 0.0f ? 0.0f : rgb.pixels[p * 3 + c];
    out.pixels[p * 4 + 3] = a;
  }
  return out;
}

// The channels of an EXR of layers, gathered one image at a time.
struct ExrChannels {
  Image image;
  std::vector<std::string> names;

  void add(const Image& layer, std::vector<std::string> layer_names) {
    if (image.channels == 0) image = Image(layer.width, layer.height, 0);
    const int before = image.channels, after = before + layer.channels;
    std::vector<float> pixels(std::size_t(image.width) * image.height * after);
    for (std::size_t p = 0; p < std::size_t(image.width) * image.height; ++p) {
      std::copy_n(image.pixels.begin() + std::ptrdiff_t(p * before), before, pixels.begin() + std::ptrdiff_t(p * after));
      std::copy_n(layer.pixels.begin() + std::ptrdiff_t(p * layer.channels), layer.channels,
                  pixels.begin() + std::ptrdiff_t(p * after + before));
    }
    image.pixels = std::move(pixels);
    image.channels = after;
    names.insert(names.end(), layer_names.begin(), layer_names.end());
  }
};

// Premultiplied colour divided by its alpha: the colour of what covers the pixel.
Image unpremultiplied(Image rgb, const Image& alpha) {
  for (std::size_t p = 0; p < alpha.pixels.size(); ++p)
    if (alpha.pixels[p] > 0.0f)
      for (int c = 0; c < 3; ++c) rgb.pixels[p * 3 + c] /= alpha.pixels[p];
  return rgb;
}

}  // namespace

Image to_display(const Image& linear, float exposure, const ColorConfig& color, const std::string& display,
                 const std::string& view) {
  Image out = linear;
  const float scale = std::exp2(exposure);
  for (float& v : out.pixels) v *= scale;
  color.linear_to_display(out, display, view);
  return out;
}

std::vector<fs::path> output_paths(const OutputOptions& o) {
  if (o.tile) return {o.exr};
  return {o.exr, png_path(o)};
}

void prepare_outputs(const OutputOptions& o) {
  const std::vector<fs::path> paths = output_paths(o);
  for (std::size_t i = 0; i < paths.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (paths[i].lexically_normal() == paths[j].lexically_normal())
        throw input_error(paths[i].string(), "is named for two outputs (the EXR and --png must differ)");
  for (const fs::path& p : paths) {
    remove_stale_temp_files(p);
    check_output_location(p);
  }
}

RenderLayers render_layers(const Film& film, bool aovs) {
  // One EXR of layers, named as OpenEXR names them: the AOVs travel with the image they describe and
  // cannot be mismatched with it.
  ExrChannels exr;
  exr.add(with_alpha(film.radiance(), film.alpha(), false), {"R", "G", "B", "A"});
  if (aovs) {
    exr.add(film.albedo(), {"albedo.R", "albedo.G", "albedo.B"});
    exr.add(film.normal(), {"N.X", "N.Y", "N.Z"});
    exr.add(film.depth(), {"Z"});
    exr.add(film.mip_level(), {"mip_level.X"});
  }
  return {std::move(exr.image), std::move(exr.names), film.frame};
}

void write_outputs(const Film& film, const OutputOptions& o, const ColorConfig& color) {
  write_layers(render_layers(film, o.aovs), o, color);
}

void write_layers(const RenderLayers& layers, const OutputOptions& o, const ColorConfig& color) {
  // Again after the render: a folder removed meanwhile is made anew, and a path turned into a folder
  // is refused before anything is encoded.
  for (const fs::path& p : output_paths(o)) check_output_location(p);
  const Image& all = layers.image;
  if (all.channels < 4 || layers.names.size() != std::size_t(all.channels) || layers.names[3] != "A")
    throw Error(o.exr.string() + ": the layers to write do not begin with R, G, B, A", Error::Kind::internal);
  // Depth in float: half's 11-bit mantissa is a step of 1/64 at 32 m. A tile in float throughout.
  std::vector<PixelFormat> formats;
  for (const std::string& name : layers.names)
    formats.push_back(o.float32 || o.tile || name == "Z" ? PixelFormat::float32 : PixelFormat::half);
  // Each file is encoded and written before the next is encoded: one encoded image in memory at a
  // time, and nothing renamed until the last is on disk.
  StagedFiles files;
  if (!o.tile) {
    Image radiance(all.width, all.height, 3), alpha(all.width, all.height, 1);
    for (std::size_t p = 0; p < alpha.pixels.size(); ++p) {
      for (int c = 0; c < 3; ++c) radiance.pixels[p * 3 + c] = all.pixels[p * std::size_t(all.channels) + c];
      alpha.pixels[p] = all.pixels[p * std::size_t(all.channels) + 3];
    }
    const fs::path png = png_path(o);
    if (o.transparent) {
      // PNG's alpha is straight (PNG 1.2, §12.8): the display transform reads the colour before it was
      // premultiplied, and the PNG stores it with the alpha beside it.
      files.stage(png, encode_image(png,
                                    with_alpha(to_display(unpremultiplied(radiance, alpha), o.exposure, color, o.display, o.view),
                                               alpha, true),
                                    PixelFormat::uint8));
    } else {
      files.stage(png, encode_image(png, to_display(radiance, o.exposure, color, o.display, o.view), PixelFormat::uint8));
    }
  }
  files.stage(o.exr, encode_exr(o.exr, all, layers.names, formats, layers.frame));
  files.commit();
}

}  // namespace svbrdf
