#pragma once
// Scenes built in code for the renderer's closed-form tests: quads, a sphere, orthographic cameras.
#include <cmath>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "render/render_setup.h"
#include "render/renderer.h"

namespace svbrdf::test {

// A square of side `size` in the plane z = 0, front face +z, uv (0,0) at (−s/2, +s/2) (the image's
// top-left seen from +z with +y up), placed by `to_world`.
inline void add_quad(Scene& s, int material, const glm::dmat4& to_world, float size = 2.0f) {
  const float h = 0.5f * size;
  MeshPrimitive p;
  p.positions = {{-h, -h, 0}, {h, -h, 0}, {h, h, 0}, {-h, h, 0}};
  p.normals.assign(4, {0, 0, 1});
  p.texcoords[0] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  p.tangents.assign(4, {1, 0, 0, 1});
  p.indices = {0, 1, 2, 0, 2, 3};
  p.material = material;
  p.where = "test quad";
  Mesh m;
  m.primitives.push_back(std::move(p));
  s.meshes.push_back(std::move(m));
  s.instances.push_back({int(s.meshes.size()) - 1, int(s.instances.size()), to_world});
}

// A UV sphere of radius r at the origin, flat-shaded (shading normal = geometric normal, so a
// white furnace is exact: no energy lost between the two normals).
inline void add_sphere(Scene& s, int material, float r, int rings = 48, int segments = 96) {
  MeshPrimitive p;
  const float pi = 3.14159265358979f;
  auto vertex = [&](int i, int j) {
    const float th = pi * float(i) / float(rings), ph = 2.0f * pi * float(j) / float(segments);
    return glm::vec3(r * std::sin(th) * std::cos(ph), r * std::cos(th), -r * std::sin(th) * std::sin(ph));
  };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const glm::vec3 a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1), d = vertex(i, j + 1);
      const glm::vec3 tris[2][3] = {{a, b, c}, {a, c, d}};
      for (const auto& t : tris) {
        const glm::vec3 n = glm::cross(t[1] - t[0], t[2] - t[0]);
        if (glm::length(n) < 1e-12f) continue;
        const glm::vec3 nn = glm::normalize(n);
        for (int k = 0; k < 3; ++k) {
          p.indices.push_back(std::uint32_t(p.positions.size()));
          p.positions.push_back(t[k]);
          p.normals.push_back(nn);
        }
      }
    }
  p.material = material;
  p.where = "test sphere";
  Mesh m;
  m.primitives.push_back(std::move(p));
  s.meshes.push_back(std::move(m));
  s.instances.push_back({int(s.meshes.size()) - 1, int(s.instances.size()), glm::dmat4(1.0)});
}

// An orthographic camera at `eye` looking toward `target`, with half height ymag.
inline CameraDesc ortho_camera(const glm::vec3& eye, const glm::vec3& target, float ymag, const glm::vec3& up = {0, 1, 0}) {
  CameraDesc c;
  c.name = "ortho";
  c.type = CameraDesc::Type::orthographic;
  c.xmag = c.ymag = ymag;
  const glm::vec3 f = glm::normalize(target - eye), r = glm::normalize(glm::cross(f, up)), u = glm::cross(r, f);
  glm::dmat4 m(1.0);
  m[0] = glm::dvec4(glm::dvec3(r), 0);
  m[1] = glm::dvec4(glm::dvec3(u), 0);
  m[2] = glm::dvec4(glm::dvec3(-f), 0);
  m[3] = glm::dvec4(glm::dvec3(eye), 1);
  c.to_world = m;
  return c;
}

inline CameraDesc perspective_camera(const glm::vec3& eye, const glm::vec3& target, float yfov_deg) {
  CameraDesc c = ortho_camera(eye, target, 1.0f);
  c.name = "persp";
  c.type = CameraDesc::Type::perspective;
  c.yfov = glm::radians(yfov_deg);
  return c;
}

// An image and a texture that reads it with the default sampler (repeat, as glTF's default);
// returns the texture's index for a TextureRef.
inline int add_image_texture(Scene& s, Image pixels) {
  ImageDesc im;
  im.pixels = std::move(pixels);
  im.where = "images[" + std::to_string(s.images.size()) + "]";
  s.images.push_back(std::move(im));
  TextureDesc t;
  t.image = int(s.images.size()) - 1;
  s.textures.push_back(t);
  return int(s.textures.size()) - 1;
}

// A pure Lambertian material: glTF's specular layer off (KHR_materials_specular factor 0).
inline MaterialDesc lambertian(const Rgb& rho) {
  MaterialDesc m;
  m.base_color = rho;
  m.metallic = 0.0f;
  m.roughness = 1.0f;
  m.specular = 0.0f;
  return m;
}

inline Film render_scene(Scene scene, const SceneSetup& setup, int spp, IntegratorSettings integ = {},
                         int threads = 0, std::uint64_t seed = 7) {
  const PreparedScene prepared(std::move(scene), setup);
  RenderOptions o;
  o.spp = spp;
  o.threads = threads;
  o.seed = seed;
  o.integrator = integ;
  return render(prepared.world(), o);
}

}  // namespace svbrdf::test
