#pragma once
// Float images in memory: linear values, interleaved channels, rows from the top (as stored in
// files and as glTF's uv (0,0) = top-left means them). Every file read and write goes through
// OpenImageIO.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace svbrdf {

struct Image {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<float> pixels;  // width * height * channels, row-major from the top row

  Image() = default;
  Image(int w, int h, int c) : width(w), height(h), channels(c), pixels(std::size_t(w) * h * c, 0.0f) {}

  float& at(int x, int y, int c) { return pixels[(std::size_t(y) * width + x) * channels + c]; }
  float at(int x, int y, int c) const { return pixels[(std::size_t(y) * width + x) * channels + c]; }
};

// Reads any format OpenImageIO reads into floats (values as stored: no color conversion).
// Throws svbrdf::Error naming the file when it is missing, truncated or corrupt.
Image read_image(const std::filesystem::path& path);

enum class PixelFormat { uint8, uint16, half, float32 };

// Pixels held in memory as a file would store them (`format`: 8- or 16-bit integers, half or float;
// width · height · channels values, interleaved, rows from the top) → the floats read_image gives for
// a file of those values: integers scaled by OpenImageIO's conversion to [0, 1], floats as they are.
// Throws svbrdf::Error naming `where` for a size check_image_size refuses.
Image image_from_stored(const void* data, PixelFormat format, int width, int height, int channels, const std::string& where);

// The channels of an image file named `names`, in that order: e.g. {"N.X", "N.Y", "N.Z"}, a layer of
// a render's EXR. Throws svbrdf::Error naming the file and the channel when one is missing.
Image read_image_channels(const std::filesystem::path& path, const std::vector<std::string>& names);

// read_image that also reports how the file stores its values (other integer types report uint16
// or float32, whichever holds them exactly; other float types float32).
Image read_image(const std::filesystem::path& path, PixelFormat* stored_format);

// An image file opened for reading: every check read_image makes before it decodes a pixel is made
// (the file exists, a PNG's chunks and CRCs, an OpenEXR header, the size), then the pixels are read
// whole, as read_image gives them, or, where the file stores rows of 8- or 16-bit unsigned codes, band
// by band as stored. A decoder that turns codes into its own values through tables (a 4096² material's
// texels) then needs neither the image's floats nor the whole image in memory at once.
class ImageFile {
 public:
  // Throws svbrdf::Error naming the file as read_image does.
  explicit ImageFile(const std::filesystem::path& path);
  ~ImageFile();
  ImageFile(ImageFile&&) noexcept;
  ImageFile& operator=(ImageFile&&) noexcept;

  int width() const { return width_; }
  int height() const { return height_; }
  int channels() const { return channels_; }
  PixelFormat stored_format() const { return stored_; }
  // 8 or 16 where read_codes reads the file: rows of one unsigned integer type for every channel
  // (PNG, JPEG, a TIFF of strips); 0 for any other (floats, tiles, signed or per-channel types).
  int code_bits() const { return code_bits_; }
  // Rows [y0, y1) as the file stores them: width · channels codes a row, interleaved, std::uint8_t
  // or std::uint16_t as code_bits() says, native byte order; the values read_image scales to [0, 1].
  // Bands in order from the top (a PNG decodes forward). Throws svbrdf::Error naming the file for a
  // truncated or corrupt image, with read_image's words.
  void read_codes(int y0, int y1, void* codes);
  // Every pixel as read_image gives it (instead of read_codes).
  Image read();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int width_ = 0, height_ = 0, channels_ = 0, code_bits_ = 0;
  PixelFormat stored_ = PixelFormat::float32;
};

// Writes through OpenImageIO, choosing the format by extension, atomically (temporary + rename).
// No color-space metadata is written (glTF viewers must ignore it and the Khronos validator warns
// about it); an integer format stores round(clamp(v, 0, 1) · max). A failed write (a full disk) is
// Error::Kind::environment and leaves no file (base/atomic_file.h).
void write_image(const std::filesystem::path& path, const Image& image, PixelFormat format);

// The file write_image writes, as bytes in memory: the format chosen by `path`'s extension. For
// outputs written together (base/atomic_file.h, StagedFiles).
std::vector<std::byte> encode_image(const std::filesystem::path& path, const Image& image, PixelFormat format);

// An OpenEXR file of named channels, each stored in a format of its own, as bytes in memory:
// `names` and `formats` give one per channel of `image`. Layers are named as OpenEXR's "Interpreting
// OpenEXR Images" names them ("albedo.R": channel R of layer albedo); "A" is the alpha of R, G and B,
// which are premultiplied by it as OpenEXR means them (written as given), and "Z" is depth.
std::vector<std::byte> encode_exr(const std::filesystem::path& path, const Image& image, const std::vector<std::string>& names,
                                  const std::vector<PixelFormat>& formats);

// Where an image lies in the frame it is part of: OpenEXR's data window (the pixels stored, from
// column x, row y) inside its display window (the frame, frame_width × frame_height from (0, 0)),
// as "Interpreting OpenEXR Images" defines the two. A crop of a render stores only its own pixels,
// and viewers, compositors and the merge of tiles place it in its frame by these.
struct FrameWindow {
  int x = 0, y = 0, frame_width = 0, frame_height = 0;
};

// encode_exr for an image that is the part of a larger frame `window` says.
std::vector<std::byte> encode_exr(const std::filesystem::path& path, const Image& image, const std::vector<std::string>& names,
                                  const std::vector<PixelFormat>& formats, const FrameWindow& window);

// An OpenEXR file whole: its channels as floats (the data window's pixels), their names and stored
// formats in the file's order, and where the data window lies in the display window.
struct ExrImage {
  Image image;
  std::vector<std::string> names;
  std::vector<PixelFormat> formats;
  FrameWindow window;
};
// Throws svbrdf::Error naming the file when it is missing, not an OpenEXR file, truncated or corrupt,
// or its display window does not start at (0, 0).
ExrImage read_exr(const std::filesystem::path& path);

// Largest image the project reads or makes: a side of 32768 texels, 2^28 texels in all (1 GiB per
// float channel). Anything larger, or an empty image, is refused as bad input.
inline constexpr int kMaxImageSide = 32768;
// Throws svbrdf::Error naming `where` unless 1 ≤ width, height ≤ kMaxImageSide and the image, decoded
// as `channels` floats a texel, fits --max-texels and the memory budget (base/resource_limits.h). Read
// from the file's header, before any pixel is decoded.
void check_image_size(const std::string& where, long long width, long long height, int channels = 4);

// Decodes an encoded image (PNG, JPEG, OpenEXR, HDR, TIFF...) held in memory through OpenImageIO
// (an IOMemReader proxy): images inside a .glb buffer or a data: URI. The bytes' signature decides
// the format; `mime_type` ("image/png", "image/jpeg", as glTF gives it, or a file name whose
// extension names the format) is the fallback. `name` is what error messages call it (e.g.
// "scene.glb: images[3]"). Values as stored, like read_image.
Image read_image_from_memory(std::span<const std::byte> bytes, std::string_view mime_type, const std::string& name);

// A parsed data: URI (RFC 2397) with base64 or percent-encoded payload.
struct DataUri {
  std::string mime_type;  // e.g. "image/png"; "text/plain;charset=US-ASCII" semantics when absent
  std::vector<std::byte> bytes;
};
bool is_data_uri(std::string_view uri);
// Throws svbrdf::Error naming `where` for a malformed URI or payload.
DataUri decode_data_uri(std::string_view uri, const std::string& where);
// Base64 (RFC 4648) without line breaks, for writing data: URIs.
std::string encode_base64(std::span<const std::byte> bytes);

}  // namespace svbrdf
