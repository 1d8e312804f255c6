#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "appearance/rng.h"
#include "render/embree_scene.h"

namespace svbrdf {
namespace {

// A unit quad in z = 0 facing +z (counter-clockwise seen from +z), centred on the origin.
Mesh quad_mesh(int material) {
  MeshPrimitive p;
  p.positions = {{-0.5f, -0.5f, 0}, {0.5f, -0.5f, 0}, {0.5f, 0.5f, 0}, {-0.5f, 0.5f, 0}};
  p.normals.assign(4, {0, 0, 1});
  p.texcoords[0] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  p.indices = {0, 1, 2, 0, 2, 3};
  p.material = material;
  p.where = "quad";
  Mesh m;
  m.primitives.push_back(p);
  return m;
}

struct Fixture {
  Scene scene;
  EmbreeDevice device;
  std::unique_ptr<TextureSet> textures;
  std::unique_ptr<EmbreeScene> bvh;
  void build() {
    textures = std::make_unique<TextureSet>(scene);
    bvh = std::make_unique<EmbreeScene>(device, scene, *textures);
  }
};

constexpr float kInf = std::numeric_limits<float>::infinity();

// Single-sided quads are seen from the front only, for every way a mesh can be placed: world space
// with a positive or a mirroring transform, and instanced (the same mesh twice) rotated or mirrored.
TEST(EmbreeScene, SingleSidedCullsBackFacesInEveryPlacement) {
  set_denormals_zero();
  for (int placement = 0; placement < 4; ++placement) {
    Fixture f;
    MaterialDesc mat;
    mat.double_sided = false;
    f.scene.materials.push_back(mat);
    f.scene.meshes.push_back(quad_mesh(0));
    const bool mirrored = placement % 2 == 1, instanced = placement >= 2;
    // Rotation by 90° about y turns the +z front toward +x; a mirror in x (scale −1) keeps the
    // front's winding meaning in object space, so the front then faces −x (glTF §3.7.2.1).
    glm::dmat4 xf = glm::rotate(glm::dmat4(1.0), glm::radians(90.0), glm::dvec3(0, 1, 0));
    if (mirrored) xf = glm::scale(glm::dmat4(1.0), glm::dvec3(-1, 1, 1)) * xf;
    f.scene.instances.push_back({0, 0, xf});
    if (instanced) f.scene.instances.push_back({0, 1, glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, 100))});
    f.build();
    const float front = mirrored ? -1.0f : 1.0f;  // the side (±x) the front faces
    const RayHit from_front = f.bvh->intersect({5 * front, 0, 0}, {-front, 0, 0}, 0, kInf, 1);
    const RayHit from_back = f.bvh->intersect({-5 * front, 0, 0}, {front, 0, 0}, 0, kInf, 1);
    EXPECT_TRUE(from_front.found()) << "placement " << placement;
    EXPECT_NEAR(from_front.t, 5.0f, 1e-5) << "placement " << placement;
    EXPECT_FALSE(from_back.found()) << "placement " << placement;
    EXPECT_FALSE(f.bvh->occluded({-5 * front, 0, 0}, {front, 0, 0}, 0, 10, 1)) << "placement " << placement;
    EXPECT_TRUE(f.bvh->occluded({5 * front, 0, 0}, {-front, 0, 0}, 0, 10, 1)) << "placement " << placement;
    if (instanced) {
      EXPECT_TRUE(f.bvh->intersect({0, 0, 105}, {0, 0, -1}, 0, kInf, 1).found());
    }
  }
}

TEST(EmbreeScene, DoubleSidedIsHitFromBothSides) {
  Fixture f;
  MaterialDesc mat;
  mat.double_sided = true;
  f.scene.materials.push_back(mat);
  f.scene.meshes.push_back(quad_mesh(0));
  f.scene.instances.push_back({0, 0, glm::dmat4(1.0)});
  f.build();
  EXPECT_TRUE(f.bvh->intersect({0, 0, 1}, {0, 0, -1}, 0, kInf, 1).found());
  EXPECT_TRUE(f.bvh->intersect({0, 0, -1}, {0, 0, 1}, 0, kInf, 1).found());
}

// Barycentrics come back in the primitive's own vertex order, whatever Embree was given.
TEST(EmbreeScene, BarycentricsInPrimitiveOrder) {
  for (bool mirrored : {false, true}) {
    Fixture f;
    MaterialDesc mat;
    mat.double_sided = true;
    f.scene.materials.push_back(mat);
    f.scene.meshes.push_back(quad_mesh(0));
    f.scene.instances.push_back({0, 0, glm::scale(glm::dmat4(1.0), glm::dvec3(mirrored ? -1 : 1, 1, 1))});
    f.build();
    // World point (0.3, −0.2) is object (±0.3, −0.2) in triangle 0 (v0 (−.5,−.5), v1 (.5,−.5), v2 (.5,.5)).
    const RayHit h = f.bvh->intersect({0.3f, -0.2f, 1}, {0, 0, -1}, 0, kInf, 1);
    ASSERT_TRUE(h.found());
    const glm::vec2 obj(mirrored ? -0.3f : 0.3f, -0.2f);
    const auto& p = h.geom->prim->positions;
    const auto* ix = &h.geom->prim->indices[3 * h.triangle];
    const glm::vec3 q = (1 - h.b1 - h.b2) * p[ix[0]] + h.b1 * p[ix[1]] + h.b2 * p[ix[2]];
    EXPECT_NEAR(q.x, obj.x, 1e-5) << mirrored;
    EXPECT_NEAR(q.y, obj.y, 1e-5) << mirrored;
  }
}

// alphaMode MASK: alpha below the cutoff is a hole for every ray; at or above it, a surface.
TEST(EmbreeScene, MaskCutoff) {
  for (float alpha : {0.3f, 0.6f}) {
    Fixture f;
    MaterialDesc mat;
    mat.alpha_mode = AlphaMode::mask;
    mat.alpha_cutoff = 0.5f;
    mat.base_alpha = alpha;
    f.scene.materials.push_back(mat);
    f.scene.meshes.push_back(quad_mesh(0));
    f.scene.instances.push_back({0, 0, glm::dmat4(1.0)});
    f.build();
    EXPECT_EQ(f.bvh->intersect({0, 0, 1}, {0, 0, -1}, 0, kInf, 1).found(), alpha >= 0.5f);
    EXPECT_EQ(f.bvh->occluded({0, 0, 1}, {0, 0, -1}, 0, 2, 1), alpha >= 0.5f);
  }
}

// alphaMode BLEND: the surface is hit with probability alpha over many seeds. (The ray avoids the
// quad's diagonal, where two triangles would each get their own chance.)
TEST(EmbreeScene, BlendIsStochasticOpacity) {
  Fixture f;
  MaterialDesc mat;
  mat.alpha_mode = AlphaMode::blend;
  mat.base_alpha = 0.25f;
  f.scene.materials.push_back(mat);
  f.scene.meshes.push_back(quad_mesh(0));
  f.scene.instances.push_back({0, 0, glm::dmat4(1.0)});
  f.build();
  const int n = 20000;
  int hits = 0;
  for (int s = 0; s < n; ++s) hits += f.bvh->intersect({0.2f, -0.1f, 1}, {0, 0, -1}, 0, kInf, mix64(s)).found();
  // Binomial(20000, 0.25): σ ≈ 61; 5σ.
  EXPECT_NEAR(hits, 0.25 * n, 5 * std::sqrt(n * 0.25 * 0.75));
}

}  // namespace
}  // namespace svbrdf
