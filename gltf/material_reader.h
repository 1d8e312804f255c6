#pragma once
// The appearance half of a glTF document: its images, textures with their samplers, and materials
// with every extension listed in supported_extensions(). The renderer's scene reader and the MIP
// build's material reader both read materials here, so both check a file the same way: a malformed
// value throws svbrdf::Error with one line naming the file and the JSON path, e.g.
// "scene.gltf: materials[2].pbrMetallicRoughness.roughnessFactor: is 3, outside [0, 1]".
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "gltf/document.h"
#include "gltf/scene.h"

namespace svbrdf::gltf {

struct Materials {
  std::vector<ImageDesc> images;  // described and checked; pixels empty until decode_image
  std::vector<TextureDesc> textures;
  std::vector<MaterialDesc> materials;
  // One line per material and extension of it that the project does not read, naming both.
  std::vector<std::string> warnings;
};

// Reads the images' descriptions, the textures and the materials of `doc`. Every image's bytes must
// be present (an image that cannot be read is an error, used or not).
Materials read_materials(const Document& doc);

// Decodes image i into `m.images[i].pixels` (OpenImageIO; values as stored) and releases its bytes
// in `doc` (take_image_bytes: an image file is read only now); true when it decoded. `found`, when
// given, is asked first, the image's encoded_digest set: when it returns true, its texels are had
// elsewhere (it set the size and channels) and the image is not decoded. A second call for the same
// image does nothing. Not thread-safe: OpenImageIO 2.4.7 crashes (decode_icc_profile) when PNGs with
// ICC profiles are opened concurrently.
bool decode_image(Document& doc, Materials& m, std::size_t i, const std::function<bool(ImageDesc&)>& found = {});

// The glTF extensions the project reads.
const std::vector<std::string>& supported_extensions();

}  // namespace svbrdf::gltf
