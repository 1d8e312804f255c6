#include "render/mip_cache_key.h"

#include <OpenColorIO/OpenColorIO.h>
#include <OpenImageIO/oiioversion.h>

#include <cstdint>
#include <cstring>
#include <span>
#include <string_view>

#include "base/sha256.h"
#include "mip/mip.h"
#include "render/texel_inputs.h"

namespace svbrdf {

namespace {

// A field as its name's length and bytes, then its value's: framed, so that ("ab", "c") and ("a",
// "bc") hash differently.
class KeyWriter {
 public:
  void field(std::string_view name, std::span<const std::byte> value) {
    length(name.size());
    hash_.update(name);
    length(value.size());
    hash_.update(value);
  }
  void field(std::string_view name, std::string_view text) { field(name, std::as_bytes(std::span(text.data(), text.size()))); }
  template <typename T>
  void number(std::string_view name, T value) {
    field(name, std::as_bytes(std::span(&value, 1)));
  }
  std::string hex() { return to_hex(hash_.digest()); }

 private:
  void length(std::uint64_t n) { hash_.update(std::as_bytes(std::span(&n, 1))); }
  Sha256 hash_;
};

}  // namespace

Sha256Digest image_content(const ImageDesc& image) {
  if (image.encoded_digest) return *image.encoded_digest;
  Sha256 h;
  const int shape[3] = {image.pixels.width, image.pixels.height, image.pixels.channels};
  h.update(std::as_bytes(std::span(shape)));
  h.update(std::as_bytes(std::span(image.pixels.pixels)));
  return h.digest();
}

std::string mip_cache_key(const Scene& scene, const TextureSet& textures, const MaterialDesc& material, Extent grid,
                          const std::string& color_identity, bool tint, std::span<const double> grid_mappings) {
  KeyWriter key;
  key.field("key", "svbrdf MIP cache key 1");
  key.field("code", mip_code_identity());
  key.field("libraries", std::string("OpenImageIO ") + OIIO_VERSION_STRING + ", OpenColorIO " + OCIO_VERSION);
  key.field("build", mip_build_identity(tint));
  key.field("color", color_identity);
  key.number("grid.width", grid.width);
  key.number("grid.height", grid.height);
  if (!grid_mappings.empty()) key.field("grid.mappings", std::as_bytes(grid_mappings));
  for (const TexelInput& in : texel_inputs(material)) {
    if (!in.texture) {
      key.field(in.name, std::as_bytes(std::span(in.values)));
      continue;
    }
    const TextureRef& ref = *in.texture;
    key.number(in.name + ".present", ref.present());
    if (!ref.present()) continue;
    const ImageDesc& image = scene.images[static_cast<std::size_t>(scene.textures[static_cast<std::size_t>(ref.texture)].image)];
    const Sha256Digest content = image_content(image);
    key.field(in.name + ".image", std::as_bytes(std::span(content)));
    key.number(in.name + ".width", image.pixels.width);
    key.number(in.name + ".height", image.pixels.height);
    key.number(in.name + ".channels", image.pixels.channels);
    const Sampler& s = textures.sampler(ref);
    key.number(in.name + ".wrap_s", static_cast<int>(s.wrap_s));
    key.number(in.name + ".wrap_t", static_cast<int>(s.wrap_t));
    key.number(in.name + ".color", in.color && textures.linearized(ref));
  }
  return key.hex();
}

}  // namespace svbrdf
