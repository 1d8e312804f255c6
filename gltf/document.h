#pragma once
// The one way a glTF 2.0 file (.gltf or .glb) is opened: its bytes read within the resource limits
// (base/resource_limits.h), its JSON scanned before tinygltf parses it (gltf/json_scan.h), every
// byte range the container and the buffer views state checked with overflow-safe arithmetic, and
// every file tinygltf reads beside it (buffers, images) checked to be a regular file of a size the
// document allows before one byte of it is read. Image bytes are kept encoded, for OpenImageIO to
// decode (tinygltf 2.7 reports success for an image it could not read: DEPENDENCIES.md pitfall 3).
// An image file beside the document is checked (a regular file of an allowed size) but read only
// when take_image_bytes asks for it: a scene's encoded images are then never all in memory at once.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <tiny_gltf.h>

namespace svbrdf::gltf {

// One image's encoded bytes (a data: URI or a buffer view) or its file beside the glTF, or why not.
struct ImageBytes {
  std::vector<unsigned char> bytes;
  std::filesystem::path file;  // checked, its bytes not yet read (take_image_bytes reads them)
  std::string error;  // set when the bytes could not be had (the message names the JSON path)
  bool loaded = false;
};

struct Document {
  std::filesystem::path path;
  tinygltf::Model model;
  std::vector<ImageBytes> images;  // by image index, as many as model.images
  // By animation, the index in the file's `channels` array of each channel tinygltf kept, so that a
  // message names the file's channel: tinygltf 2.7 leaves out, without an error, a channel with no
  // sampler or whose target has no node (one KHR_animation_pointer animates).
  std::vector<std::vector<int>> animation_channels;
};

// Reads `path`. Throws svbrdf::Error "PATH: [JSON path: ]what" (bad input) when the file cannot be
// read or violates the container's and the buffers' bounds.
Document read_document(const std::filesystem::path& path);

// Image i's encoded bytes, released from `doc`: those it holds, or its file read now (checked again
// as the document checked it). Throws svbrdf::Error "PATH: images[i]: why" when the file cannot be read.
std::vector<unsigned char> take_image_bytes(Document& doc, std::size_t i);

// Percent-decoding of a URI reference (RFC 3986 §2.1), as glTF §3.2 asks of relative paths and
// RFC 2397 of a data: URI that is not base64.
std::string uri_decode(const std::string& s);

// "images[3]"-style JSON path pieces.
std::string json_index(const char* array, int i);

// A number of an extension object (tinygltf keeps those as generic values) that names an index or a
// count, when it is one: a number, finite, whole and within [0, 2^31). tinygltf's GetNumberAsInt
// converts a double such as 1e20 to int, which is undefined behaviour.
std::optional<int> whole_index(const tinygltf::Value& v);

// Every number finite (a factor, a matrix, a translation).
bool finite_all(const std::vector<double>& v);

// A member of an object tinygltf keeps as a generic value: `fallback` when absent, NaN when present
// but not a number (so that in_range refuses it).
double number_or(const tinygltf::Value& object, const char* key, double fallback);

// x as a float when it is finite and within [lo, hi]; otherwise throws the input error
// "FILE: WHERE: is x, outside [lo, hi]".
float in_range(double x, double lo, double hi, const std::filesystem::path& file, const std::string& where);

}  // namespace svbrdf::gltf
