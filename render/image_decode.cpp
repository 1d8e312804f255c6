#include "render/image_decode.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "base/error.h"

namespace svbrdf {

namespace {
// OpenImageIO picks its reader by the name's extension; an ioproxy has no name, so give it one.
std::string pseudo_name(const std::vector<unsigned char>& b, const std::string& hint) {
  auto starts = [&](std::initializer_list<unsigned char> sig) {
    if (b.size() < sig.size()) return false;
    std::size_t i = 0;
    for (unsigned char c : sig)
      if (b[i++] != c) return false;
    return true;
  };
  if (starts({0x89, 'P', 'N', 'G'})) return "image.png";
  if (starts({0xFF, 0xD8, 0xFF})) return "image.jpg";
  if (starts({0x76, 0x2F, 0x31, 0x01})) return "image.exr";
  if (starts({'#', '?'})) return "image.hdr";
  if (starts({'R', 'I', 'F', 'F'})) return "image.webp";
  if (starts({'I', 'I', 0x2A, 0}) || starts({'M', 'M', 0, 0x2A})) return "image.tif";
  if (hint == "image/png") return "image.png";
  if (hint == "image/jpeg") return "image.jpg";
  const auto dot = hint.rfind('.');
  return dot == std::string::npos ? "image.png" : "image" + hint.substr(dot);
}
}  // namespace

Image decode_image(const std::vector<unsigned char>& bytes, const std::string& format_hint, const std::string& where) {
  if (bytes.empty()) throw input_error(where, "image data is empty");
  OIIO::Filesystem::IOMemReader reader(bytes.data(), bytes.size());
  auto in = OIIO::ImageInput::open(pseudo_name(bytes, format_hint), nullptr, &reader);
  if (!in) throw input_error(where, "cannot decode image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 ||
      static_cast<long long>(spec.width) * spec.height > (1LL << 28))
    throw input_error(where, "image has an unusable size " + std::to_string(spec.width) + "x" +
                                 std::to_string(spec.height) + "x" + std::to_string(spec.nchannels));
  Image img(spec.width, spec.height, spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, img.pixels.data()))
    throw input_error(where, "cannot decode image: " + in->geterror());
  return img;
}

}  // namespace svbrdf
