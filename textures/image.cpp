#include "textures/image.h"

#include <OpenImageIO/imageio.h>

#include "base/atomic_file.h"
#include "base/error.h"

namespace svbrdf {

namespace {
OIIO::TypeDesc to_oiio(PixelFormat f) {
  switch (f) {
    case PixelFormat::uint8: return OIIO::TypeDesc::UINT8;
    case PixelFormat::uint16: return OIIO::TypeDesc::UINT16;
    case PixelFormat::half: return OIIO::TypeDesc::HALF;
    case PixelFormat::float32: return OIIO::TypeDesc::FLOAT;
  }
  return OIIO::TypeDesc::FLOAT;
}
}  // namespace

Image read_image(const std::filesystem::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) throw input_error(path.string(), "cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  Image img(spec.width, spec.height, spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, img.pixels.data()))
    throw input_error(path.string(), "cannot decode image: " + in->geterror());
  return img;
}

void write_image(const std::filesystem::path& path, const Image& image, PixelFormat format) {
  write_atomically(path, [&](const std::filesystem::path& tmp) {
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out) throw input_error(path.string(), "no image writer for this extension: " + OIIO::geterror());
    OIIO::ImageSpec spec(image.width, image.height, image.channels, to_oiio(format));
    if (!out->open(tmp.string(), spec) ||
        !out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data()) || !out->close())
      throw input_error(path.string(), "cannot write image: " + out->geterror());
  });
}

}  // namespace svbrdf
