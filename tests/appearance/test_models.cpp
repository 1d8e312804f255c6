#include "test_models.h"

#include <cmath>
#include <filesystem>
#include <unistd.h>

#include "appearance/gltf_bsdf.h"
#include "appearance/measured.h"
#include "appearance/registry.h"

namespace svbrdf::testing {

std::string ModelCase::label() const {
  std::string s = name;
  for (const std::string& p : params) s += " " + p;
  for (const std::string& p : impulses) s += " +" + p;
  return s;
}

std::unique_ptr<Bsdf> ModelCase::build() const { return make_model(name, params, impulses); }

glm::vec3 direction_deg(double theta, double phi) {
  const double t = theta * M_PI / 180.0, p = phi * M_PI / 180.0;
  return glm::vec3(glm::normalize(glm::dvec3(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t))));
}

const std::vector<ModelCase>& sampler_cases() {
  static const std::vector<ModelCase> cases = {
      {"lambert", {"albedo=0.7"}},
      {"lambert", {"albedo=0.2,0.5,0.9"}},
      {"oren-nayar", {"albedo=0.8", "sigma=0.5"}},
      {"phong", {"kd=0.3", "ks=0.6", "n=20"}},
      {"phong", {"kd=0", "ks=1", "n=200"}},
      {"phong", {"kd=0", "ks=0.8", "n=0"}},
      {"blinn-phong", {"kl=0.2", "kg=0.7", "s=50"}},
      {"blinn-phong", {"kl=0", "kg=1", "shininess=2.7"}},
      {"lafortune", {"kd=0.2", "lobe=-1,-1,1,30"}},
      {"lafortune", {"kd=0.1", "lobe=-0.8,-1.2,0.9,15,0.6,0.5,0.4", "lobe=0.5,0.5,0.7,5,0.3,0.3,0.3"}},
      {"microfacet", {"alpha=0.3"}},
      {"microfacet", {"alpha=0.05", "fresnel=conductor"}},
      {"microfacet", {"distribution=beckmann", "alpha=0.3", "fresnel=dielectric"}},
      {"microfacet", {"distribution=beckmann", "alpha=0.05", "fresnel=none"}},
      {"microfacet", {"alpha=0.8", "kd=0.5", "f0=0.9,0.6,0.3"}},
      {"microfacet", {"metal_plastic=0.5", "alpha=0.2"}},
      {"cook-torrance", {"alpha=0.2", "fresnel=dielectric", "ior=1.8"}},
      {"gltf", {"base_color=0.8", "roughness=0.5"}},
      {"gltf", {"base_color=0.9,0.6,0.3", "metallic=1", "roughness=0.2"}},
      {"gltf", {"base_color=0.5", "metallic=0.5", "roughness=0.1"}},
      {"sheen", {"color=1", "roughness=0"}},
      {"sheen", {"color=0.9,0.6,0.3", "roughness=0.7"}},
      {"gltf-surface", {"base_color=0.7,0.4,0.2", "metallic=0.3", "roughness=0.4", "anisotropy=0.6",
                        "anisotropy_rotation=0.5", "clearcoat=1", "clearcoat_roughness=0.1"}},
      {"measured", {"file=" + gltf_merl_path()}},
      {"lambert", {"albedo=0.2"}, {"mirror:0.4"}},
      {"gltf", {"roughness=0.3", "metallic=1"}, {"dielectric:0.5"}},
  };
  return cases;
}

const std::string& gltf_merl_path() {
  static const std::string path = [] {
    const auto p = std::filesystem::temp_directory_path() /
                   ("svbrdf_appearance_test_" + std::to_string(::getpid()) + ".binary");
    GltfParams g;
    g.base_color = Rgb(0.7f, 0.5f, 0.3f);
    g.roughness = 0.6f;
    MerlTable::tabulate(GltfBsdf(g)).write(p);
    static struct Remove {
      std::filesystem::path p;
      ~Remove() {
        std::error_code ec;
        std::filesystem::remove(p, ec);
      }
    } remove{p};
    return p.string();
  }();
  return path;
}

}  // namespace svbrdf::testing
