// The targets whose readers take bytes or text: encoded images, scene recipes, svbrdf-brdf's
// parameters.
#include <span>
#include <string>
#include <vector>

#include "apps/direction_text.h"
#include "appearance/registry.h"
#include "fuzz/fuzz_targets.h"
#include "fuzz/read_or_refuse.h"
#include "scenes/recipe.h"
#include "textures/color.h"
#include "textures/image.h"

namespace svbrdf::fuzz {

int image_input(const std::uint8_t* data, std::size_t size) {
  return read_or_refuse("image", [&] {
    // The signature decides the format; PNG is the fallback a glTF image without a MIME type gets.
    Image image = read_image_from_memory(std::as_bytes(std::span(data, size)), "image/png", "input");
    ColorConfig::builtin().srgb_texture_to_linear(image);
  });
}

int recipe_input(const std::uint8_t* data, std::size_t size) {
  return read_or_refuse("recipe", [&] {
    (void)parse_recipe(std::string(reinterpret_cast<const char*>(data), size), "input.json");
  });
}

// The input is lines: the first is the model's name; then "--param k=v", "--impulse NAME[:SCALE]",
// "--wo x,y,z", "--ior X", "--eta r,g,b", "--k r,g,b" as svbrdf-brdf takes them after the option, and
// any other line is a line of directions for `eval` and `pdf`. The model is built from the name, its
// parameters and impulses, then evaluated, sampled and asked its density at the directions read, as
// svbrdf-brdf's subcommands do.
int brdf_params_input(const std::uint8_t* data, std::size_t size) {
  return read_or_refuse("brdf_params", [&] {
    const std::string text(reinterpret_cast<const char*>(data), size);
    std::vector<std::string> lines;
    for (std::size_t at = 0; at <= text.size();) {
      const std::size_t end = std::min(text.find('\n', at), text.size());
      lines.push_back(text.substr(at, end - at));
      at = end + 1;
    }
    std::vector<std::string> params, impulses;
    std::vector<glm::vec3> wos;
    std::vector<std::pair<glm::vec3, glm::vec3>> pairs;
    const auto option = [](const std::string& line, const char* name, std::string& value) {
      const std::string prefix = std::string(name) + " ";
      if (line.compare(0, prefix.size(), prefix) != 0) return false;
      value = line.substr(prefix.size());
      return true;
    };
    for (std::size_t i = 1; i < lines.size(); ++i) {
      std::string v;
      if (option(lines[i], "--param", v)) params.push_back(v);
      else if (option(lines[i], "--impulse", v)) impulses.push_back(v);
      else if (option(lines[i], "--wo", v)) wos.push_back(parse_direction(v, "--wo"));
      else if (option(lines[i], "--ior", v)) (void)parse_finite_number(v, "--ior");
      else if (option(lines[i], "--eta", v)) (void)parse_rgb(v, "--eta");
      else if (option(lines[i], "--k", v)) (void)parse_rgb(v, "--k");
      else if (glm::vec3 wi, wo; parse_direction_line(lines[i], long(i), wi, wo)) pairs.emplace_back(wi, wo);
    }
    const auto bsdf = make_model(lines[0], params, impulses);
    for (const auto& [wi, wo] : pairs) {
      (void)bsdf->eval(wi, wo);
      (void)bsdf->pdf(wi, wo);
    }
    for (const glm::vec3& wo : wos) (void)bsdf->sample(wo, {0.25f, 0.5f, 0.75f});
  });
}

}  // namespace svbrdf::fuzz
