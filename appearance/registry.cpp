#include "appearance/registry.h"

#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>

#include "appearance/blinn_phong.h"
#include "appearance/conductor_mirror.h"
#include "appearance/cook_torrance.h"
#include "appearance/dielectric.h"
#include "appearance/gltf_bsdf.h"
#include "appearance/gltf_surface_bsdf.h"
#include "appearance/lafortune.h"
#include "appearance/lambert.h"
#include "appearance/measured.h"
#include "appearance/microfacet.h"
#include "appearance/mirror.h"
#include "appearance/mixture.h"
#include "appearance/oren_nayar.h"
#include "appearance/sheen.h"
#include "appearance/phong.h"
#include "base/error.h"

namespace svbrdf {
namespace {

constexpr float kInf = INFINITY;

std::string fmt(float x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t at = s.find(sep, start);
    out.push_back(s.substr(start, at == std::string::npos ? std::string::npos : at - start));
    if (at == std::string::npos) return out;
    start = at + 1;
  }
}

// Strict number: the whole text, finite.
float parse_number(const std::string& text, const std::string& where) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const double v = std::strtod(begin, &end);
  if (text.empty() || end == begin || *end != '\0')
    throw input_error(where, "'" + text + "' is not a number");
  if (!std::isfinite(v) || std::abs(v) > 3.0e38) throw input_error(where, "'" + text + "' is not a finite number");
  return static_cast<float>(v);
}

struct Range {
  float lo = -kInf, hi = kInf;
  bool lo_open = false;  // lo excluded
  bool contains(float v) const { return (lo_open ? v > lo : v >= lo) && v <= hi; }
  std::string text() const {
    return std::string(lo_open ? "(" : "[") + (lo == -kInf ? "-inf" : fmt(lo)) + ", " + (hi == kInf ? "inf" : fmt(hi)) + "]";
  }
};
const Range kUnit{0.0f, 1.0f};
const Range kNonNegative{0.0f, kInf};
const Range kPositive{0.0f, kInf, true};

// The parameters of one model: each read once with its default and range; finish() rejects the rest.
class ParamReader {
 public:
  ParamReader(std::string model, const std::vector<std::string>& params) : model_(std::move(model)) {
    for (const std::string& p : params) {
      const std::size_t eq = p.find('=');
      if (eq == std::string::npos || eq == 0)
        throw input_error("model '" + model_ + "'", "parameter '" + p + "' is not of the form key=value");
      values_[p.substr(0, eq)].push_back(p.substr(eq + 1));
    }
  }
  std::string where(const std::string& key) const { return "model '" + model_ + "': parameter '" + key + "'"; }
  bool has(const std::string& key) const { return values_.count(key) != 0; }

  float number(const std::string& key, float def, const Range& r) {
    const std::string* text = single(key);
    if (!text) return def;
    const float v = parse_number(*text, where(key));
    check(key, v, r);
    return v;
  }
  Rgb rgb(const std::string& key, const Rgb& def, const Range& r) {
    const std::string* text = single(key);
    if (!text) return def;
    const Rgb c = parse_rgb(*text, where(key));
    for (int i = 0; i < 3; ++i) check(key, c[i], r);
    return c;
  }
  std::string choice(const std::string& key, const std::string& def, const std::vector<std::string>& options) {
    const std::string* text = single(key);
    if (!text) return def;
    for (const std::string& o : options)
      if (*text == o) return o;
    std::string list;
    for (const std::string& o : options) list += (list.empty() ? "" : "|") + o;
    throw input_error(where(key), "'" + *text + "' is not one of " + list);
  }
  std::string text(const std::string& key) {
    const std::string* t = single(key);
    if (!t || t->empty()) throw input_error(where(key), "is required");
    return *t;
  }
  std::vector<std::string> repeated(const std::string& key) {
    used_.insert(key);
    auto it = values_.find(key);
    return it == values_.end() ? std::vector<std::string>{} : it->second;
  }
  // A parameter that the chosen options make meaningless is an error, not silently ignored.
  void forbid(const std::string& key, const std::string& why) {
    if (has(key)) throw input_error(where(key), why);
    used_.insert(key);
  }
  void finish() const {
    for (const auto& [key, v] : values_)
      if (!used_.count(key)) throw input_error("model '" + model_ + "'", "unknown parameter '" + key + "'");
  }

 private:
  const std::string* single(const std::string& key) {
    used_.insert(key);
    auto it = values_.find(key);
    if (it == values_.end()) return nullptr;
    if (it->second.size() > 1) throw input_error(where(key), "given more than once");
    return &it->second.front();
  }
  void check(const std::string& key, float v, const Range& r) const {
    if (!r.contains(v)) throw input_error(where(key), "value " + fmt(v) + " is out of range " + r.text());
  }
  std::string model_;
  std::map<std::string, std::vector<std::string>> values_;
  std::set<std::string> used_;
};

// `n` or `shininess` (§27.12: shininess = log10 of the exponent, 0 ... 6), not both.
float exponent(ParamReader& r, const std::string& key, float def) {
  if (r.has(key) && r.has("shininess"))
    throw input_error(r.where("shininess"), "give either '" + key + "' or 'shininess', not both");
  if (r.has("shininess")) return exponent_from_shininess(r.number("shininess", 0.0f, Range{0.0f, 6.0f}));
  return r.number(key, def, Range{0.0f, 1.0e6f});
}

MicrofacetParams microfacet_params(ParamReader& r, bool alias_cook_torrance) {
  MicrofacetParams p;
  if (alias_cook_torrance) {
    r.forbid("distribution", "cook-torrance fixes distribution=beckmann (use microfacet to choose)");
    r.forbid("masking", "cook-torrance fixes masking=vgroove (use microfacet to choose)");
    p = cook_torrance_params(p);
  } else {
    p.distribution = r.choice("distribution", "ggx", {"ggx", "beckmann"}) == "ggx" ? MicrofacetType::ggx
                                                                               : MicrofacetType::beckmann;
    p.masking = r.choice("masking", "smith", {"smith", "vgroove"}) == "smith" ? Masking::smith : Masking::vgroove;
  }
  // Below 1e-4 the float GGX/Beckmann peaks overflow.
  p.alpha = r.number("alpha", p.alpha, Range{1e-4f, 1e4f});
  if (r.has("metal_plastic")) {
    for (const char* k : {"kd", "f0", "fresnel", "ior", "eta", "k"})
      r.forbid(k, "metal_plastic sets kd, f0 and fresnel=schlick itself");
    const float t = r.number("metal_plastic", 0.0f, kUnit);
    const Rgb color = r.rgb("color", Rgb(0.8f), kUnit);
    return metal_plastic_params(p, t, color);
  }
  r.forbid("color", "applies only with metal_plastic");
  const std::string f = r.choice("fresnel", "schlick", {"schlick", "dielectric", "conductor", "none"});
  p.fresnel = f == "schlick" ? FresnelMode::schlick
              : f == "dielectric" ? FresnelMode::dielectric
              : f == "conductor" ? FresnelMode::conductor
                                 : FresnelMode::none;
  if (p.fresnel == FresnelMode::schlick) p.f0 = r.rgb("f0", p.f0, kUnit);
  else r.forbid("f0", "applies only with fresnel=schlick");
  if (p.fresnel == FresnelMode::dielectric) p.ior = r.number("ior", p.ior, kPositive);
  else r.forbid("ior", "applies only with fresnel=dielectric");
  if (p.fresnel == FresnelMode::conductor) {
    p.eta = r.rgb("eta", p.eta, kPositive);
    p.k = r.rgb("k", p.k, kNonNegative);
  } else {
    r.forbid("eta", "applies only with fresnel=conductor");
    r.forbid("k", "applies only with fresnel=conductor");
  }
  p.kd = r.rgb("kd", p.kd, kUnit);
  return p;
}

LafortuneLobe lafortune_lobe(const std::string& text, const std::string& where) {
  const std::vector<std::string> parts = split(text, ',');
  if (parts.size() != 4 && parts.size() != 7)
    throw input_error(where, "'" + text + "' is neither Cx,Cy,Cz,n nor Cx,Cy,Cz,n,r,g,b");
  LafortuneLobe l;
  float v[7];
  for (std::size_t i = 0; i < parts.size(); ++i) v[i] = parse_number(parts[i], where);
  l.c = {v[0], v[1], v[2]};
  l.n = v[3];
  if (!(l.n >= 0 && l.n <= 1e6f)) throw input_error(where, "exponent " + fmt(l.n) + " is out of range [0, 1e+06]");
  if (parts.size() == 7) {
    l.weight = {v[4], v[5], v[6]};
    if (!(v[4] >= 0 && v[5] >= 0 && v[6] >= 0)) throw input_error(where, "lobe weights must be non-negative");
  }
  return l;
}

std::unique_ptr<Bsdf> build(const std::string& name, ParamReader& r) {
  if (name == "lambert") return std::make_unique<Lambert>(r.rgb("albedo", Rgb(0.5f), kUnit));
  if (name == "phong") {
    const Rgb kd = r.rgb("kd", Rgb(0.5f), kUnit), ks = r.rgb("ks", Rgb(0.5f), kUnit);
    return std::make_unique<Phong>(kd, ks, exponent(r, "n", 20.0f));
  }
  if (name == "blinn-phong") {
    const Rgb kl = r.rgb("kl", Rgb(0.5f), kUnit), kg = r.rgb("kg", Rgb(0.5f), kUnit);
    return std::make_unique<BlinnPhong>(kl, kg, exponent(r, "s", 20.0f));
  }
  if (name == "lafortune") {
    const Rgb kd = r.rgb("kd", Rgb(0.5f), kUnit);
    std::vector<LafortuneLobe> lobes;
    for (const std::string& t : r.repeated("lobe")) lobes.push_back(lafortune_lobe(t, r.where("lobe")));
    if (lobes.size() > static_cast<std::size_t>(Lafortune::kMaxLobes))
      throw input_error(r.where("lobe"), "at most " + std::to_string(Lafortune::kMaxLobes) + " lobes");
    return std::make_unique<Lafortune>(kd, std::move(lobes));
  }
  if (name == "microfacet") return std::make_unique<Microfacet>(microfacet_params(r, false));
  if (name == "cook-torrance") return std::make_unique<Microfacet>(microfacet_params(r, true));
  if (name == "oren-nayar") {
    const Rgb albedo = r.rgb("albedo", Rgb(0.5f), kUnit);
    return std::make_unique<OrenNayar>(albedo, r.number("sigma", 0.3f, Range{0.0f, 1.5707964f}));
  }
  if (name == "gltf") {
    GltfParams p;
    p.base_color = r.rgb("base_color", p.base_color, kUnit);
    p.metallic = r.number("metallic", p.metallic, kUnit);
    p.roughness = r.number("roughness", p.roughness, kUnit);
    return std::make_unique<GltfBsdf>(p);
  }
  if (name == "sheen") {
    const Rgb color = r.rgb("color", Rgb(1.0f), kUnit);
    return std::make_unique<Sheen>(color, r.number("roughness", 0.5f, kUnit));
  }
  if (name == "gltf-surface") {
    // The renderer's glTF surface with its extension layers (gltf_surface_bsdf.h), in the shading frame.
    ShadingParams p;
    p.base_color = r.rgb("base_color", Rgb(0.8f), kUnit);
    p.metallic = r.number("metallic", 0.0f, kUnit);
    p.roughness = r.number("roughness", 0.5f, kUnit);
    p.ior = r.number("ior", 1.5f, Range{1.0f, 1e3f});
    p.specular = r.number("specular", 1.0f, kUnit);
    p.specular_color = r.rgb("specular_color", Rgb(1.0f), kNonNegative);
    p.diffuse_roughness = r.number("diffuse_roughness", 0.0f, kUnit);
    p.transmission = r.number("transmission", 0.0f, kUnit);
    // KHR_materials_volume: the transmission refracts by eta = n(beyond)/n(here); 0 keeps it thin-walled.
    p.eta = r.number("volume_eta", 0.0f, Range{0.0f, 1e3f});
    p.thin_walled = p.eta == 0.0f;
    if (p.thin_walled) p.eta = 1.5f;
    p.diffuse_transmission = r.number("diffuse_transmission", 0.0f, kUnit);
    p.diffuse_transmission_color = r.rgb("diffuse_transmission_color", Rgb(1.0f), kUnit);
    p.anisotropy = r.number("anisotropy", 0.0f, kUnit);
    const float rotation = r.number("anisotropy_rotation", 0.0f, Range{-1e3f, 1e3f});
    p.anisotropy_direction = glm::vec2(std::cos(rotation), std::sin(rotation));
    p.sheen_color = r.rgb("sheen_color", Rgb(0.0f), kUnit);
    p.sheen_roughness = r.number("sheen_roughness", 0.0f, kUnit);
    p.iridescence = r.number("iridescence", 0.0f, kUnit);
    p.iridescence_ior = r.number("iridescence_ior", 1.3f, Range{1.0f, 1e3f});
    p.iridescence_thickness = r.number("iridescence_thickness", 400.0f, Range{0.0f, 1e6f});
    p.clearcoat = r.number("clearcoat", 0.0f, kUnit);
    p.clearcoat_roughness = r.number("clearcoat_roughness", 0.0f, kUnit);
    return std::make_unique<SurfaceBsdf>(p);
  }
  if (name == "measured") return std::make_unique<Measured>(std::make_shared<MerlTable>(MerlTable::read(r.text("file"))));
  if (name == "mirror") return std::make_unique<Mirror>(r.rgb("rho", Rgb(1.0f), kUnit));
  if (name == "dielectric") return std::make_unique<Dielectric>(r.number("ior", 1.5f, kPositive));
  if (name == "conductor-mirror") {
    const Rgb eta = r.rgb("eta", Rgb(0.2f, 0.92f, 1.1f), kPositive);
    return std::make_unique<ConductorMirror>(eta, r.rgb("k", Rgb(3.9f, 2.45f, 2.14f), kNonNegative));
  }
  std::string list;
  for (const std::string& n : model_names()) list += (list.empty() ? "" : ", ") + n;
  throw input_error("", "unknown model '" + name + "' (models: " + list + ")");
}

}  // namespace

float parse_finite_number(const std::string& text, const std::string& where) { return parse_number(text, where); }

Rgb parse_rgb(const std::string& text, const std::string& where) {
  const std::vector<std::string> parts = split(text, ',');
  if (parts.size() != 1 && parts.size() != 3) throw input_error(where, "'" + text + "' is neither one number nor r,g,b");
  Rgb c;
  for (int i = 0; i < 3; ++i) c[i] = parse_number(parts[parts.size() == 1 ? 0 : static_cast<std::size_t>(i)], where);
  return c;
}

const std::vector<std::string>& model_names() {
  static const std::vector<std::string> names = {"lambert",     "phong",      "blinn-phong", "lafortune",
                                                 "microfacet",  "cook-torrance", "oren-nayar", "gltf",
                                                 "gltf-surface", "sheen",     "measured",   "mirror",
                                                 "dielectric",  "conductor-mirror"};
  return names;
}

std::string models_help() {
  return "lambert: albedo=0.5 [0,1]\n"
         "phong: kd=0.5 ks=0.5 [0,1], n=20 [0,1e6] or shininess=log10(n) [0,6]\n"
         "blinn-phong: kl=0.5 kg=0.5 [0,1], s=20 [0,1e6] or shininess=log10(s) [0,6]\n"
         "lafortune: kd=0.5 [0,1], lobe=Cx,Cy,Cz,n[,r,g,b] (repeatable, up to 8)\n"
         "microfacet: distribution=ggx|beckmann alpha=0.3 [1e-4,1e4] masking=smith|vgroove\n"
         "  fresnel=schlick|dielectric|conductor|none f0=0.04 ior=1.5 eta=0.2,0.92,1.1 k=3.9,2.45,2.14 kd=0\n"
         "  or metal_plastic=t [0,1] color=0.8 (kd=(1-t)color, f0=mix(0.04,color,t), schlick)\n"
         "cook-torrance: microfacet with distribution=beckmann masking=vgroove\n"
         "oren-nayar: albedo=0.5 [0,1] sigma=0.3 [0,pi/2] (radians)\n"
         "gltf: base_color=0.8 metallic=0 roughness=0.5 [0,1]\n"
         "sheen: color=1 roughness=0.5 [0,1] (KHR_materials_sheen's Charlie lobe alone)\n"
         "gltf-surface: gltf's parameters with the glTF extensions' layers: ior=1.5 [1,1e3] specular=1\n"
         "  specular_color=1 diffuse_roughness=0 transmission=0 diffuse_transmission=0 diffuse_transmission_color=1\n"
         "  volume_eta=0 (>0: the transmission refracts by n(beyond)/n(here)) anisotropy=0 anisotropy_rotation=0 (radians)\n"
         "  sheen_color=0 sheen_roughness=0 iridescence=0 [0,1] iridescence_ior=1.3 iridescence_thickness=400 (nm)\n"
         "  clearcoat=0 clearcoat_roughness=0 [0,1]\n"
         "measured: file=PATH (MERL binary layout)\n"
         "mirror: rho=1 [0,1]\n"
         "dielectric: ior=1.5 (>0)\n"
         "conductor-mirror: eta=0.2,0.92,1.1 k=3.9,2.45,2.14\n"
         "RGB values: r,g,b or one number for gray.\n";
}

std::unique_ptr<Bsdf> make_model(const std::string& name, const std::vector<std::string>& params) {
  ParamReader r(name, params);
  std::unique_ptr<Bsdf> model = build(name, r);
  r.finish();
  return model;
}

std::unique_ptr<Bsdf> make_model(const std::string& name, const std::vector<std::string>& params,
                                 const std::vector<std::string>& impulses) {
  std::unique_ptr<Bsdf> model = make_model(name, params);
  if (impulses.empty()) return model;
  auto mix = std::make_unique<OwningMixture>();
  int dielectrics = name == "dielectric" ? 1 : 0;
  mix->add(std::move(model), 1.0f);
  for (const std::string& spec : impulses) {
    const std::string where = "--impulse '" + spec + "'";
    const std::size_t colon = spec.find(':');
    const std::string kind = spec.substr(0, colon);
    float scale = 1.0f;
    if (colon != std::string::npos) {
      scale = parse_number(spec.substr(colon + 1), where);
      if (!(scale >= 0 && scale <= 1)) throw input_error(where, "scale " + fmt(scale) + " is out of range [0, 1]");
    }
    if (kind != "mirror" && kind != "dielectric" && kind != "conductor-mirror")
      throw input_error(where, "unknown impulse model '" + kind + "' (mirror, dielectric, conductor-mirror)");
    // At most two distinct impulse directions fit a query's Impulses: one refraction at most.
    if (kind == "dielectric" && ++dielectrics > 1) throw input_error(where, "at most one dielectric in a combination");
    if (mix->mixture().size() >= Mixture::kCapacity) throw input_error(where, "too many impulses");
    mix->add(make_model(kind, {}), scale);
  }
  return mix;
}

}  // namespace svbrdf
