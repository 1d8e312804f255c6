#include "gltf/material_reader.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <sstream>

#include <tiny_gltf.h>

#include "base/error.h"
#include "textures/image.h"

namespace svbrdf::gltf {

namespace {

class MaterialReader {
 public:
  explicit MaterialReader(const Document& doc) : doc_(doc), model_(doc.model) {}

  Materials run() {
    read_images();
    read_textures();
    read_materials();
    return std::move(out_);
  }

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw input_error(doc_.path.string() + (where.empty() ? "" : ": " + where), what);
  }

  void read_images() {
    const std::size_t n = model_.images.size();
    out_.images.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const tinygltf::Image& im = model_.images[i];
      ImageDesc& d = out_.images[i];
      d.name = im.name;
      d.uri = im.uri;
      d.mime_type = im.mimeType;
      d.where = json_index("images", int(i));
      if (i >= doc_.images.size()) fail(d.where, "has no image data");
      const ImageBytes& ib = doc_.images[i];
      if (!ib.error.empty()) fail(d.where, ib.error);
      if (!ib.loaded || (ib.bytes.empty() && ib.file.empty()))
        fail(d.where, im.uri.empty() ? "has no image data" : "cannot read the image file '" + im.uri + "'");
    }
  }

  void read_textures() {
    for (std::size_t i = 0; i < model_.textures.size(); ++i) {
      const tinygltf::Texture& t = model_.textures[i];
      TextureDesc d;
      d.where = json_index("textures", int(i));
      // EXT_texture_webp README: its source, a WebP image, is the texture's image for a reader that
      // supports the extension; the texture's own source, if any, is the fallback for one that does not.
      int source = t.source;
      std::string source_where = d.where + ".source";
      if (const auto webp = t.extensions.find("EXT_texture_webp"); webp != t.extensions.end()) {
        source_where = d.where + ".extensions.EXT_texture_webp.source";
        const auto& e = webp->second;
        if (!e.IsObject()) fail(d.where + ".extensions.EXT_texture_webp", "is not an object");
        if (e.Has("source")) {
          source = whole_index(e.Get("source")).value_or(-1);
          if (source < 0) fail(source_where, "is not an image index (a whole number from 0)");
        }
      }
      if (source >= 0) {
        if (static_cast<std::size_t>(source) >= model_.images.size())
          fail(source_where, "names " + json_index("images", source) + ", but the file has " +
                                 std::to_string(model_.images.size()) + " images");
        d.image = source;
      }
      if (t.sampler >= 0) {
        if (static_cast<std::size_t>(t.sampler) >= model_.samplers.size())
          fail(d.where + ".sampler", "names " + json_index("samplers", t.sampler) + ", but the file has " +
                                         std::to_string(model_.samplers.size()) + " samplers");
        const auto& s = model_.samplers[static_cast<std::size_t>(t.sampler)];
        const std::string sw = json_index("samplers", t.sampler);
        const std::string file = doc_.path.string() + ": ";
        d.sampler.wrap_s = wrap_mode_from_gltf(s.wrapS, file + sw + ".wrapS");
        d.sampler.wrap_t = wrap_mode_from_gltf(s.wrapT, file + sw + ".wrapT");
        if (s.magFilter >= 0) d.sampler.filter = filter_mode_from_gltf(s.magFilter, file + sw + ".magFilter");
      }
      out_.textures.push_back(d);
    }
  }

  // --- materials ---------------------------------------------------------------------------

  float checked(double x, double lo, double hi, const std::string& where) const {
    return in_range(x, lo, hi, doc_.path, where);
  }

  void apply_texture_transform(TextureRef& r, const tinygltf::Value& ext, const std::string& where) const {
    if (!ext.IsObject() || !ext.Has("KHR_texture_transform")) return;
    const tinygltf::Value& tt = ext.Get("KHR_texture_transform");
    const std::string w = where + ".extensions.KHR_texture_transform";
    auto vec2 = [&](const char* key, glm::vec2 fallback) {
      if (!tt.Has(key)) return fallback;
      const tinygltf::Value& a = tt.Get(key);
      if (!a.IsArray() || a.ArrayLen() != 2 || !a.Get(0).IsNumber() || !a.Get(1).IsNumber())
        fail(w + "." + key, "must be an array of two numbers");
      const glm::vec2 v(a.Get(0).GetNumberAsDouble(), a.Get(1).GetNumberAsDouble());
      if (!std::isfinite(v.x) || !std::isfinite(v.y)) fail(w + "." + key, "is not finite");
      return v;
    };
    const double rot = number_or(tt, "rotation", 0.0);
    if (!std::isfinite(rot)) fail(w + ".rotation", "is not a finite number");
    int override_set = -1;
    if (tt.Has("texCoord")) {
      const double tc = number_or(tt, "texCoord", 0);
      if (tc != 0 && tc != 1) fail(w + ".texCoord", "is " + std::to_string(tc) + "; TEXCOORD_0 and _1 are read");
      override_set = int(tc);
    }
    r.transform = TextureTransform::make(vec2("offset", glm::vec2(0)), float(rot), vec2("scale", glm::vec2(1)), override_set);
  }

  TextureRef texture_ref(int index, int tex_coord, const tinygltf::ExtensionMap& ext, const std::string& where) {
    TextureRef r;
    if (index < 0) return r;
    if (static_cast<std::size_t>(index) >= out_.textures.size())
      fail(where + ".index", "names " + json_index("textures", index) + ", but the file has " +
                                 std::to_string(out_.textures.size()) + " textures");
    // glTF 2.0 §5.29: a texture's source is optional, and without one (or an extension's) what it
    // shows is undefined: the material renders as if the texture were absent, and says so.
    if (out_.textures[static_cast<std::size_t>(index)].image < 0) {
      out_.warnings.push_back(where + ".index: " + json_index("textures", index) +
                              " has no image (no source); the material renders without it");
      return r;
    }
    if (tex_coord != 0 && tex_coord != 1)
      fail(where + ".texCoord", "is " + std::to_string(tex_coord) + "; TEXCOORD_0 and _1 are read");
    r.texture = index;
    r.tex_coord = tex_coord;
    tinygltf::Value::Object o(ext.begin(), ext.end());
    apply_texture_transform(r, tinygltf::Value(o), where);
    return r;
  }

  // A textureInfo inside an extension object (tinygltf leaves those as generic values).
  TextureRef texture_ref(const tinygltf::Value& ext_obj, const char* key, const std::string& where) {
    if (!ext_obj.IsObject() || !ext_obj.Has(key)) return {};
    const tinygltf::Value& ti = ext_obj.Get(key);
    const std::string w = where + "." + key;
    if (!ti.IsObject() || !ti.Has("index") || !ti.Get("index").IsNumber()) fail(w, "is not a textureInfo");
    const std::optional<int> index = whole_index(ti.Get("index"));
    if (!index) fail(w + ".index", "is not a texture index (a whole number from 0)");
    const std::optional<int> tc = ti.Has("texCoord") ? whole_index(ti.Get("texCoord")) : std::optional<int>(0);
    if (!tc) fail(w + ".texCoord", "is not a TEXCOORD set number (a whole number from 0)");
    tinygltf::ExtensionMap none;
    TextureRef r = texture_ref(*index, *tc, none, w);
    if (r.present() && ti.Has("extensions")) apply_texture_transform(r, ti.Get("extensions"), w);
    return r;
  }

  void read_materials() {
    for (std::size_t i = 0; i < model_.materials.size(); ++i) {
      const tinygltf::Material& m = model_.materials[i];
      MaterialDesc d;
      d.name = m.name;
      d.where = json_index("materials", int(i));
      const std::string w = d.where;
      const auto& pbr = m.pbrMetallicRoughness;
      const std::string wp = w + ".pbrMetallicRoughness";
      if (pbr.baseColorFactor.size() != 4 || !finite_all(pbr.baseColorFactor))
        fail(wp + ".baseColorFactor", "must be four finite numbers");
      for (int c = 0; c < 3; ++c)
        d.base_color[c] = checked(pbr.baseColorFactor[std::size_t(c)], 0, 1, wp + ".baseColorFactor");
      d.base_alpha = checked(pbr.baseColorFactor[3], 0, 1, wp + ".baseColorFactor");
      d.base_color_texture = texture_ref(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                         pbr.baseColorTexture.extensions, wp + ".baseColorTexture");
      d.metallic = checked(pbr.metallicFactor, 0, 1, wp + ".metallicFactor");
      d.roughness = checked(pbr.roughnessFactor, 0, 1, wp + ".roughnessFactor");
      d.metallic_roughness_texture =
          texture_ref(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                      pbr.metallicRoughnessTexture.extensions, wp + ".metallicRoughnessTexture");
      d.normal_texture = texture_ref(m.normalTexture.index, m.normalTexture.texCoord, m.normalTexture.extensions,
                                     w + ".normalTexture");
      if (!std::isfinite(m.normalTexture.scale)) fail(w + ".normalTexture.scale", "is not finite");
      d.normal_texture.scale = float(m.normalTexture.scale);
      d.occlusion_texture = texture_ref(m.occlusionTexture.index, m.occlusionTexture.texCoord,
                                        m.occlusionTexture.extensions, w + ".occlusionTexture");
      d.occlusion_texture.scale = checked(m.occlusionTexture.strength, 0, 1, w + ".occlusionTexture.strength");
      if (m.emissiveFactor.size() != 3 || !finite_all(m.emissiveFactor))
        fail(w + ".emissiveFactor", "must be three finite numbers");
      for (int c = 0; c < 3; ++c) d.emissive[c] = checked(m.emissiveFactor[std::size_t(c)], 0, 1, w + ".emissiveFactor");
      d.emissive_texture = texture_ref(m.emissiveTexture.index, m.emissiveTexture.texCoord,
                                       m.emissiveTexture.extensions, w + ".emissiveTexture");
      if (m.alphaMode == "OPAQUE") d.alpha_mode = AlphaMode::opaque;
      else if (m.alphaMode == "MASK") d.alpha_mode = AlphaMode::mask;
      else if (m.alphaMode == "BLEND") d.alpha_mode = AlphaMode::blend;
      else fail(w + ".alphaMode", "is '" + m.alphaMode + "'; glTF allows OPAQUE, MASK and BLEND");
      d.alpha_cutoff = checked(m.alphaCutoff, 0, 1e30, w + ".alphaCutoff");
      d.double_sided = m.doubleSided;
      read_material_extensions(m.extensions, d);
      out_.materials.push_back(std::move(d));
    }
  }

  // An extension's RGB factor `key` of `ext` (at JSON path where.key), each component in [0, hi].
  Rgb rgb_or(const tinygltf::Value& ext, const char* key, const Rgb& fallback, double hi, const std::string& where) const {
    if (!ext.Has(key)) return fallback;
    const std::string wk = where + "." + key;
    const auto& a = ext.Get(key);
    if (!a.IsArray() || a.ArrayLen() != 3) fail(wk, "must be three numbers");
    Rgb c;
    for (int i = 0; i < 3; ++i) c[i] = checked(a.Get(i).IsNumber() ? a.Get(i).GetNumberAsDouble() : std::nan(""), 0, hi, wk);
    return c;
  }

  void read_material_extensions(const tinygltf::ExtensionMap& ext, MaterialDesc& d) {
    const std::string w = d.where + ".extensions.";
    const auto& known = supported_extensions();
    for (const auto& [name, value] : ext)
      if (std::find(known.begin(), known.end(), name) == known.end())
        out_.warnings.push_back(d.where + (d.name.empty() ? "" : " '" + d.name + "'") + ": optional extension " + name +
                                " is not supported; the material renders without it");
    auto get = [&](const char* name) -> const tinygltf::Value* {
      auto it = ext.find(name);
      return it == ext.end() ? nullptr : &it->second;
    };
    if (const auto* e = get("KHR_materials_emissive_strength")) {
      const std::string we = w + "KHR_materials_emissive_strength.emissiveStrength";
      d.emissive_strength = checked(number_or(*e, "emissiveStrength", 1.0), 0, 1e30, we);
    }
    if (const auto* e = get("KHR_materials_ior")) {
      // KHR_materials_ior README and schema: "valid values for ior are numbers greater than or equal
      // to one", and zero, the specular-glossiness compatibility mode of an infinite index.
      const double ior = number_or(*e, "ior", 1.5);
      if (ior != 0.0) checked(ior, 1.0, std::numeric_limits<double>::max(), w + "KHR_materials_ior.ior");
      d.ior = ior == 0.0 ? kIorInfinity : float(std::min(ior, double(kIorInfinity)));
    }
    if (const auto* e = get("KHR_materials_specular")) {
      const std::string ws = w + "KHR_materials_specular";
      d.specular = checked(number_or(*e, "specularFactor", 1.0), 0, 1, ws + ".specularFactor");
      d.specular_texture = texture_ref(*e, "specularTexture", ws);
      d.specular_color = rgb_or(*e, "specularColorFactor", Rgb(1.0f), 1e30, ws);
      d.specular_color_texture = texture_ref(*e, "specularColorTexture", ws);
    }
    if (const auto* e = get("KHR_materials_transmission")) {
      const std::string wt = w + "KHR_materials_transmission";
      d.transmission = checked(number_or(*e, "transmissionFactor", 0.0), 0, 1, wt + ".transmissionFactor");
      d.transmission_texture = texture_ref(*e, "transmissionTexture", wt);
    }
    if (const auto* e = get("KHR_materials_diffuse_roughness")) {
      const std::string wr = w + "KHR_materials_diffuse_roughness";
      d.diffuse_roughness = checked(number_or(*e, "diffuseRoughnessFactor", 0.0), 0, 1, wr + ".diffuseRoughnessFactor");
      d.diffuse_roughness_texture = texture_ref(*e, "diffuseRoughnessTexture", wr);
    }
    if (get("KHR_materials_unlit")) d.unlit = true;
    if (const auto* e = get("KHR_materials_clearcoat")) {
      const std::string wc = w + "KHR_materials_clearcoat";
      d.clearcoat = checked(number_or(*e, "clearcoatFactor", 0.0), 0, 1, wc + ".clearcoatFactor");
      d.clearcoat_texture = texture_ref(*e, "clearcoatTexture", wc);
      d.clearcoat_roughness =
          checked(number_or(*e, "clearcoatRoughnessFactor", 0.0), 0, 1, wc + ".clearcoatRoughnessFactor");
      d.clearcoat_roughness_texture = texture_ref(*e, "clearcoatRoughnessTexture", wc);
      d.clearcoat_normal_texture = texture_ref(*e, "clearcoatNormalTexture", wc);
      if (d.clearcoat_normal_texture.present()) {
        const double scale = number_or(e->Get("clearcoatNormalTexture"), "scale", 1.0);
        if (!std::isfinite(scale)) fail(wc + ".clearcoatNormalTexture.scale", "is not finite");
        d.clearcoat_normal_texture.scale = float(scale);
      }
    }
    if (const auto* e = get("KHR_materials_diffuse_transmission")) {
      const std::string wd = w + "KHR_materials_diffuse_transmission";
      d.diffuse_transmission =
          checked(number_or(*e, "diffuseTransmissionFactor", 0.0), 0, 1, wd + ".diffuseTransmissionFactor");
      d.diffuse_transmission_texture = texture_ref(*e, "diffuseTransmissionTexture", wd);
      d.diffuse_transmission_color = rgb_or(*e, "diffuseTransmissionColorFactor", Rgb(1.0f), 1.0, wd);
      d.diffuse_transmission_color_texture = texture_ref(*e, "diffuseTransmissionColorTexture", wd);
    }
    if (const auto* e = get("KHR_materials_volume")) {
      const std::string wv = w + "KHR_materials_volume";
      d.thickness = checked(number_or(*e, "thicknessFactor", 0.0), 0, 1e30, wv + ".thicknessFactor");
      d.thickness_texture = texture_ref(*e, "thicknessTexture", wv);
      if (e->Has("attenuationDistance")) {
        const double ad = number_or(*e, "attenuationDistance", 0.0);
        if (!(ad > 0.0) || !std::isfinite(ad)) fail(wv + ".attenuationDistance", "must be a finite number > 0");
        d.attenuation_distance = float(ad);
      }
      d.attenuation_color = rgb_or(*e, "attenuationColor", Rgb(1.0f), 1.0, wv);
    }
    if (const auto* e = get("KHR_materials_dispersion"))
      d.dispersion = checked(number_or(*e, "dispersion", 0.0), 0, 1e3, w + "KHR_materials_dispersion.dispersion");
    if (d.ior == kIorInfinity) d.dispersion = 0.0f;  // KHR_materials_ior: no effect at an infinite index
    if (const auto* e = get("KHR_materials_sheen")) {
      const std::string ws = w + "KHR_materials_sheen";
      d.sheen_color = rgb_or(*e, "sheenColorFactor", Rgb(0.0f), 1.0, ws);
      d.sheen_color_texture = texture_ref(*e, "sheenColorTexture", ws);
      d.sheen_roughness = checked(number_or(*e, "sheenRoughnessFactor", 0.0), 0, 1, ws + ".sheenRoughnessFactor");
      d.sheen_roughness_texture = texture_ref(*e, "sheenRoughnessTexture", ws);
    }
    if (const auto* e = get("KHR_materials_iridescence")) {
      const std::string wi = w + "KHR_materials_iridescence";
      d.iridescence = checked(number_or(*e, "iridescenceFactor", 0.0), 0, 1, wi + ".iridescenceFactor");
      d.iridescence_texture = texture_ref(*e, "iridescenceTexture", wi);
      d.iridescence_ior = checked(number_or(*e, "iridescenceIor", 1.3), 1, 1e3, wi + ".iridescenceIor");
      d.iridescence_thickness_min =
          checked(number_or(*e, "iridescenceThicknessMinimum", 100.0), 0, 1e6, wi + ".iridescenceThicknessMinimum");
      d.iridescence_thickness_max =
          checked(number_or(*e, "iridescenceThicknessMaximum", 400.0), 0, 1e6, wi + ".iridescenceThicknessMaximum");
      d.iridescence_thickness_texture = texture_ref(*e, "iridescenceThicknessTexture", wi);
    }
    if (const auto* e = get("KHR_materials_anisotropy")) {
      const std::string wa = w + "KHR_materials_anisotropy";
      d.anisotropy_strength = checked(number_or(*e, "anisotropyStrength", 0.0), 0, 1, wa + ".anisotropyStrength");
      d.anisotropy_rotation = checked(number_or(*e, "anisotropyRotation", 0.0), -1e6, 1e6, wa + ".anisotropyRotation");
      d.anisotropy_texture = texture_ref(*e, "anisotropyTexture", wa);
    }
  }

  const Document& doc_;
  const tinygltf::Model& model_;
  Materials out_;
};

}  // namespace

Materials read_materials(const Document& doc) { return MaterialReader(doc).run(); }

bool decode_image(Document& doc, Materials& m, std::size_t i, const std::function<bool(ImageDesc&)>& found) {
  ImageDesc& d = m.images.at(i);
  if (d.pixels.width > 0) return false;
  const std::vector<unsigned char> b = take_image_bytes(doc, i);
  d.encoded_digest = sha256(std::as_bytes(std::span(b.data(), b.size())));
  if (found && found(d)) return false;
  try {
    d.pixels = read_image_from_memory(std::as_bytes(std::span(b.data(), b.size())), d.mime_type,
                                      d.uri.empty() ? d.where : d.where + " ('" + d.uri + "')");
  } catch (const Error& e) {
    throw input_error(doc.path.string(), e.what());
  }
  return true;
}

const std::vector<std::string>& supported_extensions() {
  static const std::vector<std::string> k = {
      "KHR_texture_transform",        "KHR_materials_emissive_strength", "KHR_materials_ior",
      "KHR_materials_specular",       "KHR_materials_transmission",      "KHR_materials_diffuse_roughness",
      "KHR_materials_unlit",          "KHR_lights_punctual",             "KHR_mesh_quantization",
      "KHR_draco_mesh_compression",   "EXT_meshopt_compression",         "KHR_materials_variants",
      "KHR_materials_clearcoat",      "KHR_materials_anisotropy",        "KHR_materials_sheen",
      "KHR_materials_iridescence",    "KHR_materials_volume",            "KHR_materials_diffuse_transmission",
      "KHR_materials_dispersion",     "EXT_texture_webp"};
  return k;
}

}  // namespace svbrdf::gltf
