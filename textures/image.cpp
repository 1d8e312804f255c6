#include "textures/image.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <mutex>
#include <optional>
#include <utility>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/resource_limits.h"
#include "textures/exr_header.h"

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

// OpenImageIO keeps per-thread error messages and prints any left unread at exit; every failure
// path reads them, and an empty one gets a generic reason.
std::string reason(std::string message, const char* fallback) {
  while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
  for (char& c : message)
    if (c == '\n') c = ' ';
  return message.empty() ? fallback : message;
}

PixelFormat from_oiio(OIIO::TypeDesc t) {
  switch (t.basetype) {
    case OIIO::TypeDesc::UINT8:
    case OIIO::TypeDesc::INT8: return PixelFormat::uint8;
    case OIIO::TypeDesc::UINT16:
    case OIIO::TypeDesc::INT16: return PixelFormat::uint16;
    case OIIO::TypeDesc::HALF: return PixelFormat::half;
    default: return PixelFormat::float32;
  }
}

// Values exactly as stored: PNG, TIFF and others keep straight (unassociated) alpha, and glTF
// means its base color that way; by default OpenImageIO would premultiply color by alpha on read
// and divide on write.
const OIIO::ImageSpec& straight_alpha_config() {
  static const OIIO::ImageSpec config = [] {
    OIIO::ImageSpec c;
    c.attribute("oiio:UnassociatedAlpha", 1);
    return c;
  }();
  return config;
}

// The checks of an opened input's subimage 0, MIP level 0 before any pixel is decoded.
void check_opened(const OIIO::ImageInput& in, const std::string& where, PixelFormat* stored_format) {
  const OIIO::ImageSpec& spec = in.spec();
  if (stored_format) *stored_format = from_oiio(spec.format);
  check_image_size(where, spec.width, spec.height, spec.nchannels);
  if (spec.nchannels < 1 || spec.nchannels > 64) throw input_error(where, "unsupported channel count " + std::to_string(spec.nchannels));
}

// A read's outcome: some decoders (libjpeg, libpng) report a premature end as a warning and fill the
// rest; OIIO passes that on as a pending error even when the read succeeds.
void check_read(bool read, OIIO::ImageInput& in, const std::string& where) {
  if (!read) throw input_error(where, "cannot decode image (truncated or corrupt?): " + reason(in.geterror(), "read failed"));
  if (in.has_error()) throw input_error(where, "cannot decode image (truncated or corrupt?): " + reason(in.geterror(), "decoder error"));
}

// Reads subimage 0, MIP level 0 of an opened and checked input into floats.
Image read_checked(OIIO::ImageInput& in, const std::string& where) {
  const OIIO::ImageSpec& spec = in.spec();
  Image img(spec.width, spec.height, spec.nchannels);
  check_read(in.read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, img.pixels.data()), in, where);
  return img;
}

// 8 or 16 where the input stores scanlines of one unsigned integer type in every channel, else 0.
int code_bits_of(const OIIO::ImageSpec& spec) {
  if (spec.tile_width != 0 || spec.depth > 1) return 0;
  for (const OIIO::TypeDesc& t : spec.channelformats)
    if (t != spec.format) return 0;
  return spec.format == OIIO::TypeDesc::UINT8 ? 8 : spec.format == OIIO::TypeDesc::UINT16 ? 16 : 0;
}

// The file extension OpenImageIO should try first for these bytes: by signature, else by MIME type.
std::string extension_for(std::span<const std::byte> bytes, std::string_view mime) {
  const auto starts = [&](std::initializer_list<unsigned char> sig) {
    if (bytes.size() < sig.size()) return false;
    std::size_t i = 0;
    for (unsigned char b : sig)
      if (std::to_integer<unsigned char>(bytes[i++]) != b) return false;
    return true;
  };
  if (starts({0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'})) return ".png";
  if (starts({0xff, 0xd8, 0xff})) return ".jpg";
  if (starts({0x76, 0x2f, 0x31, 0x01})) return ".exr";
  if (starts({'#', '?'})) return ".hdr";
  if (starts({'I', 'I', 0x2a, 0x00}) || starts({'M', 'M', 0x00, 0x2a})) return ".tif";
  // WebP (RFC 9649 §2.5): a RIFF container whose form type, at byte 8, is "WEBP".
  if (starts({'R', 'I', 'F', 'F'}) && bytes.size() >= 12 && std::to_integer<char>(bytes[8]) == 'W' &&
      std::to_integer<char>(bytes[9]) == 'E' && std::to_integer<char>(bytes[10]) == 'B' &&
      std::to_integer<char>(bytes[11]) == 'P')
    return ".webp";
  // A file name as the hint: its extension.
  if (const std::size_t dot = mime.rfind('.'); dot != std::string_view::npos && mime.substr(0, 6) != "image/") {
    std::string ext(mime.substr(dot));
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    for (const char* known : {".png", ".jpg", ".jpeg", ".exr", ".hdr", ".tif", ".tiff"})
      if (ext == known) return ext;
  }
  if (mime == "image/png") return ".png";
  if (mime == "image/jpeg") return ".jpg";
  if (mime == "image/x-exr" || mime == "image/aces") return ".exr";
  if (mime == "image/vnd.radiance") return ".hdr";
  if (mime == "image/tiff") return ".tif";
  if (mime == "image/webp") return ".webp";
  return "";
}

// CRC-32 of ISO 3309 / PNG (polynomial 0xedb88320, reflected), table-driven.
std::uint32_t crc32(const std::byte* data, std::size_t n) {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
      t[i] = c;
    }
    return t;
  }();
  std::uint32_t c = 0xffffffffu;
  for (std::size_t i = 0; i < n; ++i) c = table[(c ^ std::to_integer<std::uint32_t>(data[i])) & 0xffu] ^ (c >> 8);
  return ~c;
}

bool is_png(std::span<const std::byte> b) {
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (b.size() < 8) return false;
  for (int i = 0; i < 8; ++i)
    if (std::to_integer<unsigned char>(b[i]) != kSignature[i]) return false;
  return true;
}

// Walks a PNG's chunks (PNG spec §5.3: length, type, data, CRC) up to IEND before libpng sees it:
// libpng prints its own "libpng error" line to stderr for a truncated or damaged file, and the
// project's programs print exactly one line for bad input, ours.
void check_png_structure(std::span<const std::byte> b, const std::string& where) {
  const auto be32 = [&](std::size_t at) {
    return std::to_integer<std::uint32_t>(b[at]) << 24 | std::to_integer<std::uint32_t>(b[at + 1]) << 16 |
           std::to_integer<std::uint32_t>(b[at + 2]) << 8 | std::to_integer<std::uint32_t>(b[at + 3]);
  };
  std::size_t at = 8;
  for (int chunk = 0;; ++chunk) {
    if (b.size() - at < 12) throw input_error(where, "truncated PNG: the file ends inside chunk " + std::to_string(chunk) + " (no IEND)");
    const std::uint32_t length = be32(at);
    if (length > 0x7fffffffu || b.size() - at - 12 < length)
      throw input_error(where, "truncated PNG: chunk " + std::to_string(chunk) + " runs past the end of the file");
    if (crc32(b.data() + at + 4, length + 4) != be32(at + 8 + length))
      throw input_error(where, "corrupt PNG: CRC mismatch in chunk " + std::to_string(chunk));
    const bool iend = std::to_integer<char>(b[at + 4]) == 'I' && std::to_integer<char>(b[at + 5]) == 'E' &&
                      std::to_integer<char>(b[at + 6]) == 'N' && std::to_integer<char>(b[at + 7]) == 'D';
    at += 12 + length;
    if (iend) return;
  }
}

std::vector<std::byte> read_file_bytes(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw input_error(path.string(), "is not a regular file");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw input_error(path.string(), "cannot read file: " + ec.message());
  if (size > image_file_limit())
    throw input_error(path.string(), "is " + byte_size_text(size) + ", more than an image of at most " +
                                         std::to_string(resource_limits().max_texels) + " texels can be (--max-texels)");
  std::ifstream f(path, std::ios::binary);
  std::vector<std::byte> bytes;
  if (!f) throw input_error(path.string(), "cannot open file");
  bytes.resize(std::size_t(size));
  f.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size()));
  if (!f) throw input_error(path.string(), "cannot read file");
  return bytes;
}

// libpng's default error handler prints "libpng error: ..." to stderr before OpenImageIO reports the
// same text as its error, which the caller puts in its one line: the programs' contract is that one
// line. While any PNG is decoded, file descriptor 2 points at /dev/null: the first decode to start
// points it there and the last to finish points it back, so PNGs decode in parallel (OpenImageIO's
// error string keeps libpng's words, and the one line is printed after the decodes).
class QuietStderr {
 public:
  QuietStderr() {
    const std::lock_guard<std::mutex> lock(state().mutex);
    if (state().decoders++ > 0) return;
    std::fflush(stderr);
    state().saved = ::dup(2);
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (state().saved >= 0 && null >= 0) ::dup2(null, 2);
    if (null >= 0) ::close(null);
  }
  ~QuietStderr() {
    const std::lock_guard<std::mutex> lock(state().mutex);
    if (--state().decoders > 0 || state().saved < 0) return;
    ::dup2(state().saved, 2);
    ::close(state().saved);
    state().saved = -1;
  }
  QuietStderr(const QuietStderr&) = delete;
  QuietStderr& operator=(const QuietStderr&) = delete;

 private:
  struct State {
    std::mutex mutex;
    int decoders = 0;  // PNG decodes running
    int saved = -1;    // the real stderr while any runs
  };
  static State& state() {
    static State s;
    return s;
  }
};

// An opened input and what it reads from; members in the order they must be made (and are undone
// in reverse: the input before its bytes, stderr back last).
struct OpenedImage {
  std::string where;
  std::optional<QuietStderr> quiet;  // while a PNG is open
  std::vector<std::byte> bytes;      // a PNG file's, read whole for check_png_structure
  std::optional<OIIO::Filesystem::IOMemReader> proxy;
  std::unique_ptr<OIIO::ImageInput> in;

  // Opens encoded bytes held in memory (borrowed: they outlive the input); `where` names them.
  void open_memory(std::span<const std::byte> data, std::string_view mime_type) {
    if (is_png(data)) quiet.emplace();
    if (data.empty()) throw input_error(where, "image data is empty");
    if (is_png(data)) check_png_structure(data, where);
    check_exr_header(data, where);
    const std::string ext = extension_for(data, mime_type);
    if (ext.empty())
      throw input_error(where, "unsupported image type" + (mime_type.empty() ? std::string() : " \"" + std::string(mime_type) + "\""));
    proxy.emplace(data.data(), data.size());
    // OpenImageIO picks the decoder by the name's extension; the proxy supplies the bytes.
    // OpenImageIO 2.4 takes the proxy from the config when a config is given.
    OIIO::ImageSpec config = straight_alpha_config();
    OIIO::Filesystem::IOProxy* proxy_ptr = &*proxy;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy_ptr);
    in = OIIO::ImageInput::open("memory" + ext, &config, &*proxy);
    if (!in) throw input_error(where, "cannot decode image: " + reason(OIIO::geterror(), "unrecognized data"));
  }
};

Image decode_memory(std::span<const std::byte> bytes, std::string_view mime_type, const std::string& name,
                    PixelFormat* stored_format) {
  OpenedImage f;
  f.where = name;
  f.open_memory(bytes, mime_type);
  check_opened(*f.in, name, stored_format);
  return read_checked(*f.in, name);
}

int base64_value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+' || c == '-') return 62;  // '-' and '_': the URL-safe alphabet of RFC 4648 §5
  if (c == '/' || c == '_') return 63;
  return -1;
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

void check_image_size(const std::string& where, long long width, long long height, int channels) {
  if (width < 1 || height < 1)
    throw input_error(where, "image has no pixels (" + std::to_string(width) + "x" + std::to_string(height) + ")");
  if (width > kMaxImageSide || height > kMaxImageSide)
    throw input_error(where, "image size " + std::to_string(width) + "x" + std::to_string(height) +
                                 " is beyond the supported " + std::to_string(kMaxImageSide) + " per side");
  // Decoded as `channels` floats a texel: within --max-texels and the memory budget.
  svbrdf::check_image_size(std::uint64_t(width), std::uint64_t(height), std::uint64_t(std::max(channels, 1)) * sizeof(float),
                           where + ": image size");
}

Image read_image(const std::filesystem::path& path) { return read_image(path, nullptr); }

Image image_from_stored(const void* data, PixelFormat format, int width, int height, int channels, const std::string& where) {
  check_image_size(where, width, height, channels);
  if (channels < 1 || channels > 64) throw input_error(where, "unsupported channel count " + std::to_string(channels));
  Image img(width, height, channels);
  // The conversion read_checked's read_image applies to a file's stored values.
  if (!OIIO::convert_pixel_values(to_oiio(format), data, OIIO::TypeDesc::FLOAT, img.pixels.data(), int(img.pixels.size())))
    throw Error(where + ": cannot convert the pixel values", Error::Kind::internal);
  return img;
}

struct ImageFile::Impl : OpenedImage {};

Image read_image(const std::filesystem::path& path, PixelFormat* stored_format) {
  ImageFile file(path);
  if (stored_format) *stored_format = file.stored_format();
  return file.read();
}

ImageFile::ImageFile(const std::filesystem::path& path) : impl_(std::make_unique<Impl>()) {
  Impl& f = *impl_;
  f.where = path.string();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw input_error(f.where, "no such image file");
  if (std::filesystem::is_directory(path, ec)) throw input_error(f.where, "is a directory, not an image");
  // PNGs are checked whole before libpng sees them (check_png_structure), so decode from memory.
  if (char sig[8] = {}; std::ifstream(path, std::ios::binary).read(sig, 8) && is_png(std::as_bytes(std::span(sig)))) {
    f.bytes = read_file_bytes(path);
    f.open_memory(f.bytes, "");
  } else {
    check_exr_file_header(path, f.where);
    f.in = OIIO::ImageInput::open(f.where, &straight_alpha_config());
    if (!f.in) throw input_error(f.where, "cannot read image: " + reason(OIIO::geterror(), "unrecognized format"));
  }
  check_opened(*f.in, f.where, &stored_);
  const OIIO::ImageSpec& spec = f.in->spec();
  width_ = spec.width, height_ = spec.height, channels_ = spec.nchannels;
  code_bits_ = code_bits_of(spec);
}

ImageFile::~ImageFile() = default;
ImageFile::ImageFile(ImageFile&&) noexcept = default;
ImageFile& ImageFile::operator=(ImageFile&&) noexcept = default;

void ImageFile::read_codes(int y0, int y1, void* codes) {
  if (code_bits_ == 0 || y0 < 0 || y1 > height_ || y0 > y1)
    throw Error(impl_->where + ": rows " + std::to_string(y0) + ".." + std::to_string(y1) + " cannot be read as codes",
                Error::Kind::internal);
  OIIO::ImageInput& in = *impl_->in;
  const OIIO::ImageSpec& spec = in.spec();
  // The decoder's own rows, straight into `codes` (read_scanlines would copy them through a buffer of its own).
  check_read(in.read_native_scanlines(0, 0, spec.y + y0, spec.y + y1, 0, codes), in, impl_->where);
}

Image ImageFile::read() { return read_checked(*impl_->in, impl_->where); }

Image read_image_channels(const std::filesystem::path& path, const std::vector<std::string>& names) {
  const Image all = read_image(path);  // every check of a file read, and its channels in the order of its spec
  auto in = OIIO::ImageInput::open(path.string(), &straight_alpha_config());
  if (!in) throw input_error(path.string(), "cannot read image: " + reason(OIIO::geterror(), "unrecognized format"));
  const std::vector<std::string> have = in->spec().channelnames;
  in->close();
  Image out(all.width, all.height, int(names.size()));
  for (std::size_t k = 0; k < names.size(); ++k) {
    const auto at = std::find(have.begin(), have.end(), names[k]);
    if (at == have.end() || int(at - have.begin()) >= all.channels)
      throw input_error(path.string(), "has no channel \"" + names[k] + "\"");
    const std::size_t c = std::size_t(at - have.begin());
    for (std::size_t p = 0; p < std::size_t(all.width) * all.height; ++p)
      out.pixels[p * names.size() + k] = all.pixels[p * std::size_t(all.channels) + c];
  }
  return out;
}

ExrImage read_exr(const std::filesystem::path& path) {
  ExrImage out;
  out.image = read_image(path);  // every check of a file read
  auto in = OIIO::ImageInput::open(path.string(), &straight_alpha_config());
  if (!in) throw input_error(path.string(), "cannot read image: " + reason(OIIO::geterror(), "unrecognized format"));
  if (std::string(in->format_name()) != "openexr") throw input_error(path.string(), "is not an OpenEXR file");
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.full_x != 0 || spec.full_y != 0)
    throw input_error(path.string(), "its display window starts at (" + std::to_string(spec.full_x) + ", " +
                                         std::to_string(spec.full_y) + "), not at (0, 0)");
  out.names = spec.channelnames;
  for (int c = 0; c < spec.nchannels; ++c) out.formats.push_back(from_oiio(spec.channelformat(c)));
  out.window = {spec.x, spec.y, spec.full_width, spec.full_height};
  in->close();
  return out;
}

Image read_image_from_memory(std::span<const std::byte> bytes, std::string_view mime_type, const std::string& name) {
  return decode_memory(bytes, mime_type, name, nullptr);
}

namespace {

// `spec` written through OpenImageIO into memory, the format chosen by `path`'s extension.
std::vector<std::byte> encode_with_spec(const std::filesystem::path& path, const Image& image, OIIO::ImageSpec spec) {
  check_image_size(path.string(), image.width, image.height);
  auto out = OIIO::ImageOutput::create(path.string());
  if (!out) throw input_error(path.string(), "no image writer for this extension: " + reason(OIIO::geterror(), "unknown"));
  // Encoded into memory through an IOVecOutput proxy (OpenImageIO 2.4 takes it from the spec's
  // "oiio:ioproxy"): the PNG writer does not report a failed write to a file, so the bytes are
  // written by write_bytes_atomically, which checks every one.
  std::vector<unsigned char> encoded;
  OIIO::Filesystem::IOVecOutput proxy(encoded);
  OIIO::Filesystem::IOProxy* proxy_ptr = &proxy;
  spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy_ptr);
  if (!out->supports("ioproxy"))
    throw Error(path.string() + ": the image writer for this extension cannot encode to memory", Error::Kind::internal);
  if (!out->open(path.string(), spec) || !out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data()) || !out->close())
    throw Error(path.string() + ": cannot encode the image: " + reason(out->geterror(), "encoder failed"), Error::Kind::internal);
  std::vector<std::byte> bytes(encoded.size());
  std::memcpy(bytes.data(), encoded.data(), encoded.size());
  return bytes;
}

}  // namespace

std::vector<std::byte> encode_image(const std::filesystem::path& path, const Image& image, PixelFormat format) {
  OIIO::ImageSpec spec(image.width, image.height, image.channels, to_oiio(format));
  spec.attribute("oiio:UnassociatedAlpha", 1);  // our alpha is straight: store it as it is
  return encode_with_spec(path, image, std::move(spec));
}

std::vector<std::byte> encode_exr(const std::filesystem::path& path, const Image& image, const std::vector<std::string>& names,
                                  const std::vector<PixelFormat>& formats) {
  return encode_exr(path, image, names, formats, FrameWindow{0, 0, image.width, image.height});
}

std::vector<std::byte> encode_exr(const std::filesystem::path& path, const Image& image, const std::vector<std::string>& names,
                                  const std::vector<PixelFormat>& formats, const FrameWindow& window) {
  if (names.size() != std::size_t(image.channels) || formats.size() != names.size())
    throw Error(path.string() + ": " + std::to_string(names.size()) + " channel names and " + std::to_string(formats.size()) +
                    " formats for an image of " + std::to_string(image.channels) + " channels",
                Error::Kind::internal);
  OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT);
  spec.channelnames = names;
  spec.channelformats.clear();
  for (const PixelFormat f : formats) spec.channelformats.push_back(to_oiio(f));
  spec.alpha_channel = spec.z_channel = -1;
  for (int c = 0; c < image.channels; ++c) {
    if (names[std::size_t(c)] == "A") spec.alpha_channel = c;
    if (names[std::size_t(c)] == "Z") spec.z_channel = c;
  }
  spec.x = window.x;
  spec.y = window.y;
  spec.full_x = spec.full_y = 0;
  spec.full_width = window.frame_width;
  spec.full_height = window.frame_height;
  return encode_with_spec(path, image, std::move(spec));
}

void write_image(const std::filesystem::path& path, const Image& image, PixelFormat format) {
  const std::vector<std::byte> bytes = encode_image(path, image, format);
  write_bytes_atomically(path, bytes);
}

bool is_data_uri(std::string_view uri) { return uri.size() >= 5 && uri.substr(0, 5) == "data:"; }

DataUri decode_data_uri(std::string_view uri, const std::string& where) {
  if (!is_data_uri(uri)) throw input_error(where, "not a data: URI");
  const std::size_t comma = uri.find(',');
  if (comma == std::string_view::npos) throw input_error(where, "data: URI without ',' before its payload");
  std::string_view header = uri.substr(5, comma - 5);
  const std::string_view payload = uri.substr(comma + 1);
  bool base64 = false;
  if (header.size() >= 7 && header.substr(header.size() - 7) == ";base64") {
    base64 = true;
    header.remove_suffix(7);
  }
  DataUri out;
  out.mime_type = std::string(header.substr(0, header.find(';')));
  if (base64) {
    out.bytes.reserve(payload.size() / 4 * 3);
    unsigned acc = 0;
    int bits = 0;
    std::size_t padding = 0;
    for (std::size_t i = 0; i < payload.size(); ++i) {
      const char c = payload[i];
      if (c == '=') {
        ++padding;
        continue;
      }
      if (padding) throw input_error(where, "data: URI base64 has data after '=' padding");
      const int v = base64_value(c);
      if (v < 0) throw input_error(where, "data: URI has an invalid base64 character at offset " + std::to_string(comma + 1 + i));
      acc = (acc << 6) | unsigned(v);
      bits += 6;
      if (bits >= 8) {
        bits -= 8;
        out.bytes.push_back(std::byte((acc >> bits) & 0xffu));
      }
    }
    if (padding > 2 || bits >= 6) throw input_error(where, "data: URI base64 payload has a truncated length");
  } else {
    for (std::size_t i = 0; i < payload.size(); ++i) {
      if (payload[i] == '%') {
        const bool complete = i + 2 < payload.size();
        const int hi = complete ? hex_value(payload[i + 1]) : -1;
        const int lo = complete ? hex_value(payload[i + 2]) : -1;
        if (hi < 0 || lo < 0) throw input_error(where, "data: URI has a bad %-escape at offset " + std::to_string(comma + 1 + i));
        out.bytes.push_back(std::byte(hi * 16 + lo));
        i += 2;
      } else {
        out.bytes.push_back(std::byte(static_cast<unsigned char>(payload[i])));
      }
    }
  }
  return out;
}

std::string encode_base64(std::span<const std::byte> bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = std::to_integer<unsigned>(bytes[i]) << 16 | std::to_integer<unsigned>(bytes[i + 1]) << 8 |
                       std::to_integer<unsigned>(bytes[i + 2]);
    for (int s = 18; s >= 0; s -= 6) out.push_back(kAlphabet[(v >> s) & 63u]);
  }
  if (const std::size_t rest = bytes.size() - i) {
    unsigned v = std::to_integer<unsigned>(bytes[i]) << 16;
    if (rest == 2) v |= std::to_integer<unsigned>(bytes[i + 1]) << 8;
    out.push_back(kAlphabet[(v >> 18) & 63u]);
    out.push_back(kAlphabet[(v >> 12) & 63u]);
    out.push_back(rest == 2 ? kAlphabet[(v >> 6) & 63u] : '=');
    out.push_back('=');
  }
  return out;
}

}  // namespace svbrdf
