#include "render/render_setup.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "base/error.h"
#include "base/resource_limits.h"
#include "render/renderer.h"
#include "textures/image.h"

namespace svbrdf {

namespace {

std::optional<std::vector<float>> parse_numbers(const std::string& text) {
  std::vector<float> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    try {
      std::size_t used = 0;
      const float x = std::stof(item, &used);
      if (used != item.size() || !std::isfinite(x)) return std::nullopt;
      v.push_back(x);
    } catch (...) {
      return std::nullopt;
    }
  }
  return v;
}

int pick_camera(const Scene& scene, const std::string& which) {
  if (which.empty()) return scene.cameras.empty() ? -1 : 0;
  if (std::all_of(which.begin(), which.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    const long i = std::stol(which);
    if (i < long(scene.cameras.size())) return int(i);
  } else {
    for (std::size_t i = 0; i < scene.cameras.size(); ++i)
      if (scene.cameras[i].name == which) return int(i);
  }
  std::string names;
  for (std::size_t i = 0; i < scene.cameras.size(); ++i)
    names += (i ? ", " : "") + std::to_string(i) + " '" + scene.cameras[i].name + "'";
  throw input_error("--camera " + which, scene.cameras.empty() ? "the scene has no cameras"
                                                                : "no such camera; the scene has " + names);
}

}  // namespace

std::optional<Rgb> parse_color(const std::string& text) {
  const auto v = parse_numbers(text);
  if (!v) return std::nullopt;
  if (v->size() == 1) return Rgb((*v)[0]);
  if (v->size() == 3) return Rgb((*v)[0], (*v)[1], (*v)[2]);
  return std::nullopt;
}

PreparedScene::PreparedScene(Scene scene, const SceneSetup& setup, const ColorConfig& color) : scene_(std::move(scene)) {
  {
    const SetupProgress::Stage stage(setup.progress, "preparing " + std::to_string(scene_.textures.size()) + " textures");
    textures_ = std::make_unique<TextureSet>(scene_, color, setup.texture_tiles);
    mips_ = std::make_unique<SceneMips>(scene_, *textures_);
  }
  if (setup.mip_cache) mips_->use_cache(setup.mip_cache, color.identity());
  if (setup.texture_tiles) mips_->use_tiles(setup.texture_tiles, color.identity());
  if (setup.filter) mips_->prepare(*setup.filter, setup.progress);
  {
    const SetupProgress::Stage stage(setup.progress, "building the BVH");
    bvh_ = std::make_unique<EmbreeScene>(device_, scene_, *textures_);
  }
  {
    const SetupProgress::Stage stage(setup.progress, "finding the emissive triangles");
    emitters_ = std::make_unique<Emitters>(scene_, *bvh_, *textures_);
  }

  const int ci = pick_camera(scene_, setup.camera);
  const CameraDesc desc = ci >= 0 ? scene_.cameras[std::size_t(ci)] : Camera::framing(bvh_->bounds_min(), bvh_->bounds_max());
  int width = setup.width, height = setup.height;
  if (width <= 0 || height <= 0) {
    float aspect = 16.0f / 9.0f;
    if (desc.type == CameraDesc::Type::perspective && desc.aspect_ratio > 0.0f) aspect = desc.aspect_ratio;
    if (desc.type == CameraDesc::Type::orthographic) aspect = desc.xmag / desc.ymag;
    // 360 rows and between 1 and 129,600 columns: a file's aspect ratio of 1e6 must not ask for a
    // frame of 360 × 3.6e8 pixels.
    aspect = std::clamp(aspect, 1.0f / 360.0f, 360.0f);
    height = 360;
    width = std::max(1, int(std::lround(height * aspect)));
  }
  check_image_size(std::uint64_t(width), std::uint64_t(height), Film::kBytesPerPixel, "the frame");
  if (ci >= 0 && setup.width > 0 && setup.height > 0) {
    const float file_aspect = desc.type == CameraDesc::Type::orthographic ? desc.xmag / desc.ymag : desc.aspect_ratio;
    const float frame_aspect = float(width) / float(height);
    if (file_aspect > 0.0f && std::abs(frame_aspect / file_aspect - 1.0f) > 1e-3f) {
      auto number = [](double x) {
        char b[32];
        std::snprintf(b, sizeof b, "%.4g", x);
        return std::string(b);
      };
      warnings_.push_back("the frame's aspect ratio " + number(frame_aspect) + " (" + std::to_string(width) + "x" +
                          std::to_string(height) + ") is not camera '" + desc.name + "''s " + number(file_aspect) +
                          ": its vertical field of view is kept and the horizontal one follows the frame");
    }
  }
  camera_desc_ = desc;
  aperture_ = setup.aperture;
  focus_distance_ = setup.focus_distance;
  camera_ = std::make_unique<Camera>(desc, width, height);
  set_lens();

  world_.scene = &scene_;
  world_.textures = textures_.get();
  world_.mips = mips_.get();
  world_.bvh = bvh_.get();
  world_.camera = camera_.get();
  world_.lights = scene_.lights;
  world_.emitters = emitters_.get();
  world_.scene_extent = bvh_->empty() ? 1.0f : glm::length(bvh_->bounds_max() - bvh_->bounds_min());

  if (!setup.sun.empty()) {
    const auto v = parse_numbers(setup.sun);
    if (!v || (v->size() != 2 && v->size() != 3) || (v->size() == 3 && (*v)[2] < 0.0f))
      throw input_error("--sun " + setup.sun, "expected elevation,azimuth[,irradiance] in degrees and W/m²");
    world_.lights.push_back(sun_light((*v)[0], (*v)[1], v->size() == 3 ? (*v)[2] : 1.0f));
  }

  if (setup.env.empty()) {
    // Without --env, a scene with nothing that emits gets a uniform white environment of radiance 1,
    // so it can be seen at all; one lit by its own lights or emissive surfaces gets none (glTF
    // carries no environment: a room lit by panels must not render as daylight).
    const bool lit = !world_.lights.empty() || !emitters_->empty();
    world_.environment = Environment::uniform(lit ? Rgb(0.0f) : Rgb(1.0f));
    if (!lit)
      environment_note_ = "a uniform white environment of radiance 1 (the scene has neither lights nor emissive "
                          "surfaces; --env sets another)";
    else if (world_.lights.empty())
      environment_note_ = "none: the scene is lit by its emissive surfaces alone (glTF carries no environment; "
                          "--env sets one)";
  } else if (const auto c = parse_color(setup.env)) {
    if (!(c->x >= 0.0f && c->y >= 0.0f && c->z >= 0.0f))
      throw input_error("--env " + setup.env, "a radiance cannot be negative");
    world_.environment = Environment::uniform(*c);
    if (!world_.environment.black()) environment_note_ = "a uniform environment of radiance " + setup.env;
  } else {
    // An HDR or EXR file is scene-linear; which space is the config's file rules' to say.
    Image sky = read_image(setup.env);
    color.file_to_linear(sky, setup.env);
    world_.environment = Environment::from_image(std::move(sky), setup.env);
    environment_note_ = "the equirectangular environment " + setup.env;
  }
}

void PreparedScene::set_lens() {
  if (aperture_ != 0.0f || focus_distance_ != 0.0f) {
    if (!(focus_distance_ >= 0.0f))  // a negative or NaN distance, not the autofocus's 0
      camera_->set_lens(aperture_, focus_distance_);
    camera_->set_lens(aperture_, focus_distance_ > 0.0f ? focus_distance_ : autofocus());
  }
}

void PreparedScene::pose_camera(const glm::dmat4& to_world) {
  CameraDesc posed = camera_desc_;
  posed.to_world = to_world;
  camera_ = std::make_unique<Camera>(posed, camera_->width(), camera_->height());
  world_.camera = camera_.get();
  set_lens();
}

float PreparedScene::autofocus() const {
  // What the ray through the frame's centre meets first, its distance along the view axis; a centre
  // that sees no surface focuses on the middle of the scene's bounds.
  const Camera& c = *camera_;
  const Ray r = c.ray(0.5f * float(c.width()), 0.5f * float(c.height()));
  const RayHit hit = bvh_->empty() ? RayHit{} : bvh_->intersect(r.origin, r.dir, r.tnear, r.tfar, 0);
  float d = hit.found() ? hit.t * glm::dot(r.dir, c.forward())
                        : glm::dot(0.5f * (bvh_->bounds_min() + bvh_->bounds_max()) - c.position(), c.forward());
  // The bounds behind the camera, or no geometry: a distance of 1.
  return d > 0.0f && std::isfinite(d) ? d : 1.0f;
}

}  // namespace svbrdf
