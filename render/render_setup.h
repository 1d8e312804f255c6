#pragma once
// From a loaded Scene and the command line's choices to everything a render needs: the textures,
// the Embree scene, the camera, the lights and the environment, kept alive together.
#include <memory>
#include <optional>
#include <string>

#include "render/camera.h"
#include "render/embree_device.h"
#include "render/embree_scene.h"
#include "render/emitters.h"
#include "render/integrator.h"
#include "render/material_mips.h"
#include "gltf/scene.h"
#include "render/texture_set.h"
#include "textures/color.h"
#include "base/setup_progress.h"

namespace svbrdf {

struct SceneSetup {
  std::string camera;  // index or name; empty: the scene's first camera, else a framing camera
  int width = 0, height = 0;  // 0: from the camera's aspect ratio at 360 rows, else 640×360
  // "--env": empty for the default (white radiance 1 when the scene has neither punctual lights nor
  // emissive surfaces, none otherwise); "r,g,b" or "v" for a uniform radiance; anything else names
  // an equirectangular image.
  std::string env;
  // "--sun elevation,azimuth[,irradiance]" in degrees and W/m²; empty for none.
  std::string sun;
  // The texture filter whose MIP data to build now (the materials in parallel); render() builds
  // what any other filter needs on first use.
  std::optional<TextureFilter> filter;
  // Where the set-up's stages report (base/setup_progress.h); null: nowhere.
  SetupProgress* progress = nullptr;
  // Where brdf MIP builds are read from and stored (render/mip_cache.h); null: built every time.
  MipCache* mip_cache = nullptr;
  // Where the scene's images went when they were loaded out of core (LoadOptions::take_image with
  // TextureSet::store), and where the materials' MIP data go (render/mip_tiles.h); null: the scene
  // holds its pixels and its MIP data.
  TextureTiles* texture_tiles = nullptr;
  // Depth of field (render/camera.h; glTF cameras carry no lens): the thin lens's radius in scene
  // units (0: the pinhole), and the distance along the view axis it focuses at (0: the distance along
  // the axis to the first surface the ray through the frame's centre meets, else to the centre of the
  // scene's bounds).
  float aperture = 0.0f;
  float focus_distance = 0.0f;
};

class PreparedScene {
 public:
  PreparedScene(Scene scene, const SceneSetup& setup, const ColorConfig& color = ColorConfig::builtin());
  const RenderWorld& world() const { return world_; }
  const Scene& scene() const { return scene_; }
  const Camera& camera() const { return *camera_; }
  // The distance SceneSetup::focus_distance 0 focuses at.
  float autofocus() const;
  // The camera as the file describes it: its static pose, and its motion when the file was read with
  // LoadOptions::camera_animation (null for the framing camera of a scene that has none).
  const CameraDesc& camera_desc() const { return camera_desc_; }
  // Places the camera at `to_world` (a pose of camera_desc().motion, checked by the caller with
  // camera_transform_fault), keeping the frame's size and the lens; an autofocus focuses anew.
  void pose_camera(const glm::dmat4& to_world);
  const EmbreeScene& bvh() const { return *bvh_; }
  // The environment the render uses, in words, when it is not the file's own (glTF carries none, so
  // whenever it is not black), e.g. "a uniform white environment of radiance 1 (...)"; and for a
  // scene lit by its emissive surfaces alone, that it has none. Empty otherwise.
  const std::string& environment_note() const { return environment_note_; }
  const Emitters& emitters() const { return *emitters_; }
  // What the set-up changed from the file's intent, one line each: a --res whose aspect ratio is not
  // the camera's (the vertical field of view is kept, the horizontal one follows the frame).
  const std::vector<std::string>& warnings() const { return warnings_; }
  // What a render under `filter` should warn about the MIP data, one line each (material_mips.h).
  std::vector<std::string> mip_warnings(TextureFilter filter) const { return mips_->warnings(filter); }
  // How many distinct MIP builds came from SceneSetup::mip_cache and how many were built.
  SceneMips::CacheCounts mip_cache_counts() const { return mips_->cache_counts(); }

 private:
  void set_lens();  // SceneSetup's aperture and focus distance on camera_
  Scene scene_;
  EmbreeDevice device_;
  std::unique_ptr<TextureSet> textures_;
  std::unique_ptr<SceneMips> mips_;
  std::unique_ptr<EmbreeScene> bvh_;
  std::unique_ptr<Camera> camera_;
  CameraDesc camera_desc_;
  float aperture_ = 0.0f, focus_distance_ = 0.0f;  // SceneSetup's
  std::unique_ptr<Emitters> emitters_;
  RenderWorld world_;
  std::string environment_note_;
  std::vector<std::string> warnings_;
};

// "r,g,b" or "v" as a color; nullopt when the text is not numbers.
std::optional<Rgb> parse_color(const std::string& text);

}  // namespace svbrdf
