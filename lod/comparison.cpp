#include "lod/comparison.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>

#include "base/error.h"
#include "render/camera.h"
#include "gltf/scene_reader.h"
#include "mip/texture_filter.h"
#include "render/lights.h"
#include "render/render_setup.h"
#include "render/renderer.h"

namespace svbrdf {

namespace fs = std::filesystem;

const LodShot::FilterResult* LodShot::find(const std::string& filter) const {
  for (const FilterResult& f : filters)
    if (f.filter == filter) return &f;
  return nullptr;
}

namespace {

// The renderer's filter of that name (svbrdf-render --filter), if it has one.
std::optional<TextureFilter> renderer_filter(const std::string& name) { return parse_filter(name); }

// One glTF file, prepared once (textures, BVH and whatever the renderer builds per scene), then
// rendered under any light from any of its cameras: the light and the environment are the world's
// members, replaced per light as svbrdf-render's --sun and --env would set them.
class ShotRenderer {
 public:
  ShotRenderer(const fs::path& gltf, int size, float footprint_scale, const ColorConfig& color)
      : size_(size), footprint_scale_(footprint_scale) {
    Scene scene = load_gltf(gltf);
    cameras_ = scene.cameras;
    SceneSetup setup;
    setup.width = size, setup.height = size;
    setup.env = "0,0,0";
    prepared_ = std::make_unique<PreparedScene>(std::move(scene), setup, color);
  }

  const CameraDesc& camera(const std::string& name) const {
    for (const CameraDesc& d : cameras_)
      if (d.name == name) return d;
    throw input_error(prepared_->scene().file.string(), "no camera named \"" + name + "\"");
  }

  // The world under `light`: the scene's own punctual lights (none in the LOD scenes) plus the sun,
  // and the environment.
  RenderWorld world(const LodLightSpec& light) const {
    RenderWorld w = prepared_->world();
    if (!light.sun.empty()) {
      float e = 0, a = 0, irradiance = 0;
      char extra = 0;
      if (std::sscanf(light.sun.c_str(), "%f,%f,%f%c", &e, &a, &irradiance, &extra) != 3)
        throw input_error("LOD light " + light.name, "bad sun \"" + light.sun + "\"");
      w.lights.push_back(sun_light(e, a, irradiance));
    }
    if (const auto c = parse_color(light.env)) {
      w.environment = Environment::uniform(*c);
    } else {
      w.environment = Environment::from_image(read_image(light.env), light.env);
    }
    return w;
  }

  // Radiance and depth of one render.
  std::pair<Image, Image> render_image(const RenderWorld& lit, const std::string& camera_name, TextureFilter filter,
                                       int spp, std::uint64_t seed, int max_depth, int threads) const {
    const Camera cam(camera(camera_name), size_, size_);
    RenderWorld world = lit;
    world.camera = &cam;
    RenderOptions options;
    options.spp = spp;
    options.seed = seed;
    options.threads = threads;
    options.integrator.max_depth = max_depth;
    options.integrator.filter = filter;
    options.integrator.footprints = filter != TextureFilter::level0;
    options.integrator.footprint_scale = footprint_scale_;
    const Film film = render(world, options);
    return {film.radiance(), film.depth()};
  }

 private:
  int size_ = 0;
  float footprint_scale_ = 0.0f;
  std::vector<CameraDesc> cameras_;
  std::unique_ptr<PreparedScene> prepared_;
};

bool selected(const std::vector<std::string>& list, const std::string& name) {
  return list.empty() || std::find(list.begin(), list.end(), name) != list.end();
}

void check_names(const std::vector<std::string>& asked, const std::vector<std::string>& known, const std::string& what) {
  for (const std::string& a : asked)
    if (std::find(known.begin(), known.end(), a) == known.end()) {
      std::string list;
      for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
      throw input_error(what + " " + a, "not in the LOD manifest (known: " + list + ")");
    }
}

bool identical(const Image& a, const Image& b) { return a.pixels == b.pixels; }

}  // namespace

LodResults run_lod_comparison(const LodManifest& m, const LodOptions& o, const ColorConfig& color) {
  const auto start = std::chrono::steady_clock::now();
  {
    std::vector<std::string> cases, lights, views;
    for (const LodCase& c : m.cases) {
      cases.push_back(c.name);
      for (const LodView& v : c.views) views.push_back(v.name);
    }
    for (const LodLightSpec& l : m.lights) lights.push_back(l.name);
    check_names(o.cases, cases, "case");
    check_names(o.lights, lights, "light");
    check_names(o.views, views, "view");
  }
  if (o.spp < 1) throw input_error("spp", "must be at least 1");
  if (o.parts < 1 || o.part < 0 || o.part >= o.parts)
    throw input_error("part " + std::to_string(o.part) + "/" + std::to_string(o.parts), "must be I/N with 0 <= I < N");
  LodResults results;
  results.options = o;
  results.image_size = m.image_size;
  const auto say = [&](const std::string& s) {
    if (o.progress) o.progress(s);
  };
  const auto wanted = [&](double k) {
    const bool listed = o.distances.empty() ||
                        std::any_of(o.distances.begin(), o.distances.end(), [&](double d) { return std::abs(k - d) <= 1e-9 * d; });
    return listed && k >= o.min_distance && k <= o.max_distance;
  };

  // Which filters the renderer offers (see the header): probed on the first selected case.
  std::vector<std::pair<std::string, TextureFilter>> filters;
  for (const std::string& name : o.filters) {
    const auto f = renderer_filter(name);
    if (!f || *f == TextureFilter::level0) {
      results.unavailable.push_back(name);
      continue;
    }
    filters.push_back({name, *f});
  }
  for (const LodCase& c : m.cases) {
    if (!selected(o.cases, c.name) || filters.empty()) continue;
    const LodView& v = c.views.front();
    const ShotRenderer probe(c.gltf, m.image_size, o.footprint_scale, color);
    const RenderWorld lit = probe.world(m.light(v.lights.front()));
    const auto level0 = probe.render_image(lit, v.cameras.back(), TextureFilter::level0, 4, o.filter_seed, c.max_depth, o.threads);
    std::vector<std::pair<std::string, TextureFilter>> kept;
    for (const auto& [name, f] : filters) {
      const auto img = probe.render_image(lit, v.cameras.back(), f, 4, o.filter_seed, c.max_depth, o.threads);
      if (identical(img.first, level0.first)) {
        say("filter " + name + ": the renderer renders it exactly as level0 (not implemented): skipped");
        results.unavailable.push_back(name);
      } else {
        kept.push_back({name, f});
      }
    }
    filters = kept;
    break;
  }
  for (const auto& f : filters) results.filters.push_back(f.first);

  for (const LodCase& c : m.cases) {
    if (!selected(o.cases, c.name)) continue;
    // Prepared on first use: a case whose shots are all filtered out costs nothing.
    std::unique_ptr<ShotRenderer> subject_owner, reference_owner;
    for (const LodView& v : c.views) {
      if (!selected(o.views, v.name)) continue;
      for (const std::string& light_name : v.lights) {
        if (!selected(o.lights, light_name)) continue;
        // This part's shots of the view and light: their indices k, k mod parts == part.
        std::vector<std::pair<std::size_t, int>> mine;
        for (std::size_t i = 0; i < v.cameras.size(); ++i) {
          if (!wanted(m.distances[i])) continue;
          const int k = results.total_shots++;
          if (k % o.parts == o.part) mine.push_back({i, k});
        }
        if (mine.empty()) continue;
        if (!subject_owner) {
          subject_owner = std::make_unique<ShotRenderer>(c.gltf, m.image_size, o.footprint_scale, color);
          if (c.reference != c.gltf) reference_owner = std::make_unique<ShotRenderer>(c.reference, m.image_size, o.footprint_scale, color);
        }
        const ShotRenderer& subject = *subject_owner;
        const ShotRenderer& reference = reference_owner ? *reference_owner : subject;
        const LodLightSpec& light = m.light(light_name);
        const RenderWorld subject_world = subject.world(light);
        const RenderWorld reference_world = reference_owner ? reference.world(light) : subject_world;
        for (const auto& [i, index] : mine) {
          const double k = m.distances[i];
          LodShot shot;
          shot.index = index;
          shot.case_name = c.name;
          shot.kind = c.kind;
          shot.view = v.name;
          shot.light = light_name;
          shot.camera = v.cameras[i];
          shot.multiple = k;
          const auto t0 = std::chrono::steady_clock::now();
          auto [truth, depth] = reference.render_image(reference_world, shot.camera, TextureFilter::level0, o.spp, o.seed, c.max_depth, o.threads);
          auto truth2 = reference.render_image(reference_world, shot.camera, TextureFilter::level0, o.spp, o.second_seed, c.max_depth, o.threads).first;
          shot.mask = object_mask(depth);
          shot.floor = compare_images(truth2, truth, shot.mask);
          shot.flux_sigma = flux_noise(truth, truth2, shot.mask);
          for (const auto& [name, f] : filters) {
            LodShot::FilterResult r;
            r.filter = name;
            Image img = subject.render_image(subject_world, shot.camera, f, o.spp, o.filter_seed, c.max_depth, o.threads).first;
            r.metrics = compare_images(img, truth, shot.mask);
            if (o.keep_images) r.image = std::move(img);
            shot.filters.push_back(std::move(r));
          }
          if (o.keep_images) shot.truth = std::move(truth), shot.truth2 = std::move(truth2);
          const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          char line[512];
          std::snprintf(line, sizeof line, "%s %s %s %gx: floor %.3g", c.name.c_str(), v.name.c_str(), light_name.c_str(), k,
                        shot.floor.rel_mse);
          std::string s = line;
          for (const auto& r : shot.filters) {
            std::snprintf(line, sizeof line, ", %s %.3g (flux %+.2f%%)", r.filter.c_str(), r.metrics.rel_mse,
                          100 * r.metrics.flux_bias);
            s += line;
          }
          std::snprintf(line, sizeof line, " [%.1f s]", dt);
          say(s + line);
          results.shots.push_back(std::move(shot));
        }
      }
    }
  }
  results.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return results;
}

}  // namespace svbrdf
