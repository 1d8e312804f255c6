// The MIP cache's key (render/mip_cache_key.h) covers what enters a material's texels: here the clear
// coat's inputs (KHR_materials_clearcoat), the anisotropy's (KHR_materials_anisotropy) and the
// transmission's (KHR_materials_transmission), each of which the texels read
// (textures/material_loader.h), so a change of any one must give another key; a material without a
// coat, without an anisotropy strength or without a transmission factor does not read them.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "gltf/scene.h"
#include "render/mip_cache_key.h"
#include "render/texture_set.h"

namespace svbrdf {
namespace {

// A scene of `images` 4×4 RGB images, each its own texture, filled with distinct values.
Scene scene_with_images(int images) {
  Scene s;
  for (int k = 0; k < images; ++k) {
    ImageDesc im;
    im.where = "images[" + std::to_string(k) + "]";
    im.pixels = Image(4, 4, 3);
    for (std::size_t t = 0; t < im.pixels.pixels.size(); ++t) im.pixels.pixels[t] = float((t * 7 + k * 13) % 17) / 16.0f;
    s.images.push_back(std::move(im));
    TextureDesc tex;
    tex.image = k;
    tex.where = "textures[" + std::to_string(k) + "]";
    s.textures.push_back(tex);
  }
  return s;
}

TextureRef ref(int texture) {
  TextureRef r;
  r.texture = texture;
  return r;
}

// A coated material: base colour on texture 0, coat weight, roughness and normal on textures 1-3.
MaterialDesc coated() {
  MaterialDesc m;
  m.base_color_texture = ref(0);
  m.clearcoat = 0.8f;
  m.clearcoat_texture = ref(1);
  m.clearcoat_roughness = 0.3f;
  m.clearcoat_roughness_texture = ref(2);
  m.clearcoat_normal_texture = ref(3);
  m.clearcoat_normal_texture.scale = 0.7f;
  return m;
}

std::string key_of(const Scene& scene, const MaterialDesc& m) {
  const TextureSet textures(scene);
  return mip_cache_key(scene, textures, m, {4, 4}, "color");
}

TEST(MipCacheKey, EachClearcoatInputChangesTheKey) {
  const Scene scene = scene_with_images(5);  // texture 4: another image for any slot
  const std::string base = key_of(scene, coated());
  const std::vector<std::pair<std::string, std::function<void(MaterialDesc&)>>> changes{
      {"clearcoatFactor", [](MaterialDesc& m) { m.clearcoat = 0.5f; }},
      {"clearcoatTexture", [](MaterialDesc& m) { m.clearcoat_texture = ref(4); }},
      {"clearcoatTexture absent", [](MaterialDesc& m) { m.clearcoat_texture = TextureRef{}; }},
      {"clearcoatRoughnessFactor", [](MaterialDesc& m) { m.clearcoat_roughness = 0.6f; }},
      {"clearcoatRoughnessTexture", [](MaterialDesc& m) { m.clearcoat_roughness_texture = ref(4); }},
      {"clearcoatNormalTexture", [](MaterialDesc& m) { m.clearcoat_normal_texture.texture = 4; }},
      {"clearcoatNormalTexture.scale", [](MaterialDesc& m) { m.clearcoat_normal_texture.scale = 1.0f; }},
  };
  for (const auto& [name, change] : changes) {
    MaterialDesc m = coated();
    change(m);
    EXPECT_NE(key_of(scene, m), base) << name;
  }
  // The same inputs give the same key.
  EXPECT_EQ(key_of(scene, coated()), base);
}

TEST(MipCacheKey, AChangedClearcoatImageChangesTheKey) {
  Scene scene = scene_with_images(4);
  const std::string base = key_of(scene, coated());
  for (int image = 1; image <= 3; ++image) {
    Scene changed = scene;
    changed.images[static_cast<std::size_t>(image)].pixels.pixels[5] += 0.25f;
    EXPECT_NE(key_of(changed, coated()), base) << "images[" << image << "]";
  }
}

// Without a weight the coat's textures and roughness are not read (decode_material_texels), so they
// do not enter the key either: a material that carries them unused shares its build.
TEST(MipCacheKey, AnUnweightedCoatIsNotPartOfTheKey) {
  const Scene scene = scene_with_images(5);
  MaterialDesc plain;
  plain.base_color_texture = ref(0);
  MaterialDesc unused = coated();
  unused.clearcoat = 0.0f;
  EXPECT_EQ(key_of(scene, unused), key_of(scene, plain));
}

// An anisotropic material: base colour on texture 0, the anisotropy's strength and direction on texture 1.
MaterialDesc anisotropic() {
  MaterialDesc m;
  m.base_color_texture = ref(0);
  m.anisotropy_strength = 0.6f;
  m.anisotropy_rotation = 0.4f;
  m.anisotropy_texture = ref(1);
  return m;
}

TEST(MipCacheKey, EachAnisotropyInputChangesTheKey) {
  const Scene scene = scene_with_images(5);
  const std::string base = key_of(scene, anisotropic());
  const std::vector<std::pair<std::string, std::function<void(MaterialDesc&)>>> changes{
      {"anisotropyStrength", [](MaterialDesc& m) { m.anisotropy_strength = 0.3f; }},
      {"anisotropyRotation", [](MaterialDesc& m) { m.anisotropy_rotation = -1.0f; }},
      {"anisotropyTexture", [](MaterialDesc& m) { m.anisotropy_texture = ref(4); }},
      {"anisotropyTexture absent", [](MaterialDesc& m) { m.anisotropy_texture = TextureRef{}; }},
  };
  for (const auto& [name, change] : changes) {
    MaterialDesc m = anisotropic();
    change(m);
    EXPECT_NE(key_of(scene, m), base) << name;
  }
  EXPECT_EQ(key_of(scene, anisotropic()), base);
  Scene changed = scene;
  changed.images[1].pixels.pixels[5] += 0.25f;
  EXPECT_NE(key_of(changed, anisotropic()), base) << "images[1]";
  // Strength 0 is isotropic: the rotation and the texture are not read, and not part of the key.
  MaterialDesc plain;
  plain.base_color_texture = ref(0);
  MaterialDesc unused = anisotropic();
  unused.anisotropy_strength = 0.0f;
  EXPECT_EQ(key_of(scene, unused), key_of(scene, plain));
}

// A transmitting material: base colour on texture 0, the transmission on texture 1.
MaterialDesc transmitting() {
  MaterialDesc m;
  m.base_color_texture = ref(0);
  m.transmission = 0.6f;
  m.transmission_texture = ref(1);
  return m;
}

TEST(MipCacheKey, EachTransmissionInputChangesTheKey) {
  const Scene scene = scene_with_images(5);
  const std::string base = key_of(scene, transmitting());
  const std::vector<std::pair<std::string, std::function<void(MaterialDesc&)>>> changes{
      {"transmissionFactor", [](MaterialDesc& m) { m.transmission = 0.3f; }},
      {"transmissionTexture", [](MaterialDesc& m) { m.transmission_texture = ref(4); }},
      {"transmissionTexture absent", [](MaterialDesc& m) { m.transmission_texture = TextureRef{}; }},
  };
  for (const auto& [name, change] : changes) {
    MaterialDesc m = transmitting();
    change(m);
    EXPECT_NE(key_of(scene, m), base) << name;
  }
  EXPECT_EQ(key_of(scene, transmitting()), base);
  Scene changed = scene;
  changed.images[1].pixels.pixels[5] += 0.25f;
  EXPECT_NE(key_of(changed, transmitting()), base) << "images[1]";
  // The texture is data: its texels are read as stored even where another material shows the same
  // image as colour (and TextureSet holds a linearized copy of it), so the key stays.
  Scene shown = scene;
  shown.materials.push_back(MaterialDesc{});
  shown.materials.back().base_color_texture = ref(1);
  EXPECT_EQ(key_of(shown, transmitting()), base) << "images[1] shown as colour elsewhere";
  // Factor 0 transmits nothing: the texture is not read, and not part of the key.
  MaterialDesc plain;
  plain.base_color_texture = ref(0);
  MaterialDesc unused = transmitting();
  unused.transmission = 0.0f;
  EXPECT_EQ(key_of(scene, unused), key_of(scene, plain));
}

// The diffuse transmission's inputs (render/texel_inputs.h) are the key's as the transmission's are: each
// changes it, and a factor of 0 reads neither texture.
MaterialDesc diffusely_transmitting() {
  MaterialDesc m;
  m.base_color_texture = ref(0);
  m.diffuse_transmission = 0.6f;
  m.diffuse_transmission_texture = ref(1);
  m.diffuse_transmission_color = Rgb(0.9f, 0.5f, 0.2f);
  m.diffuse_transmission_color_texture = ref(2);
  return m;
}

TEST(MipCacheKey, EachDiffuseTransmissionInputChangesTheKey) {
  const Scene scene = scene_with_images(5);
  const std::string base = key_of(scene, diffusely_transmitting());
  const std::vector<std::pair<std::string, std::function<void(MaterialDesc&)>>> changes{
      {"diffuseTransmissionFactor", [](MaterialDesc& m) { m.diffuse_transmission = 0.3f; }},
      {"diffuseTransmissionTexture", [](MaterialDesc& m) { m.diffuse_transmission_texture = ref(4); }},
      {"diffuseTransmissionColorFactor", [](MaterialDesc& m) { m.diffuse_transmission_color.g = 0.6f; }},
      {"diffuseTransmissionColorTexture", [](MaterialDesc& m) { m.diffuse_transmission_color_texture = ref(3); }},
  };
  for (const auto& [name, change] : changes) {
    MaterialDesc m = diffusely_transmitting();
    change(m);
    EXPECT_NE(key_of(scene, m), base) << name;
  }
  EXPECT_EQ(key_of(scene, diffusely_transmitting()), base);
  MaterialDesc plain;
  plain.base_color_texture = ref(0);
  MaterialDesc unused = diffusely_transmitting();
  unused.diffuse_transmission = 0.0f;
  EXPECT_EQ(key_of(scene, unused), key_of(scene, plain));
}

}  // namespace
}  // namespace svbrdf
