#pragma once
// Reading a glTF 2.0 file (.gltf or .glb) into a Scene with tinygltf (Debian's shared library; images
// are handed to OpenImageIO, never to stb). Every index, accessor, buffer view and buffer is checked;
// a malformed file throws svbrdf::Error with one line naming the file and the JSON path of the
// offending object, e.g. "scene.gltf: meshes[2].primitives[0].attributes.POSITION: ...".
//
// What is read: the default scene's node hierarchy (matrix or TRS), triangle primitives (indexed or
// not; strips and fans become lists), POSITION, NORMAL, TANGENT, TEXCOORD_0/1, COLOR_0; cameras;
// KHR_lights_punctual; images, textures and materials through gltf/material_reader.h; compressed
// geometry (KHR_draco_mesh_compression, EXT_meshopt_compression) and material variants
// (KHR_materials_variants). Missing normals
// are generated flat, missing tangents (where a normal map needs them) MikkTSpace-compatible. An
// unsupported extension in extensionsRequired is an error; one only in extensionsUsed is a warning.
// Animations (gltf/animation.h) are read only when LoadOptions::camera_animation asks, and only
// those that move a camera's node or its ancestors: everything is drawn in its static pose, and a
// camera carries its motion for the frames of an animated render. Not read: morph targets, skins
// (meshes drawn in their bind pose, with a warning); occlusion textures are kept in the
// MaterialDesc but a path tracer computes occlusion itself.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "gltf/scene.h"

namespace svbrdf {

// Luminous efficacy used to turn KHR_lights_punctual's photometric intensities into radiometric ones:
// 683 lm/W, the peak of the photopic curve (CIE; the definition of the candela at 540 THz). Blender's
// exporter and importer divide and multiply by the same constant, so a Blender round trip is exact.
inline constexpr double kLumensPerWatt = 683.0;

// How a file's light intensities are read. KHR_lights_punctual defines them photometrically: a
// directional light in lux (lm/m²), a point or spot light in candela (lm/sr); they become W/m² and
// W/sr by dividing by kLumensPerWatt. `radiometric` is for files that wrote W/m² and W/sr instead.
enum class LightUnits { photometric, radiometric };

struct LoadOptions {
  LightUnits light_units = LightUnits::photometric;
  // KHR_materials_variants: the variant whose materials the primitives take; empty: each primitive's
  // own material. A name the file does not have is an input error listing the file's variants.
  std::string variant;
  // Read the animation channels that move each camera (CameraDesc::motion), checking them; a file's
  // other animations are not read. Off, animations are not read at all (a still render).
  bool camera_animation = false;
  // Called for each image a texture shows as soon as it is decoded, one at a time, before the next
  // is decoded; `color`: a color slot shows it (MaterialDesc::shows_as_color). The callee may take
  // the pixels away (out-of-core textures, render/texture_tiles.h), leaving the size and channels:
  // then the decoded images are never all in memory at once.
  std::function<void(std::size_t index, ImageDesc& image, bool color)> take_image;
  // Called for each image a texture shows before it is decoded, its encoded bytes' digest set
  // (ImageDesc::encoded_digest): when it returns true the callee has the texels elsewhere (out-of-core
  // textures found from an earlier load) and set the size and channels, and the image is neither
  // decoded nor given to take_image.
  std::function<bool(std::size_t index, ImageDesc& image, bool color)> find_image;
};

Scene load_gltf(const std::filesystem::path& path, const LoadOptions& options = {});

}  // namespace svbrdf
