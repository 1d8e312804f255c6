#pragma once
// The glTF sample models of ../shared/data/gltf-samples with what each contains.
#include <cstddef>
#include <filesystem>
#include "tests/common/test_paths.h"

namespace svbrdf::test {

inline std::filesystem::path samples_dir() {
  return std::filesystem::path(SVBRDF_SHARED_DIR) / "data" / "gltf-samples";
}

struct SampleCounts {
  const char* file;
  std::size_t meshes, primitives, materials, textures, images, triangles, instances, cameras, lights;
};

// Counted from the files' own JSON arrays with a few lines of Python (json.load, len() of
// meshes/materials/textures/images, Σ indices.count / 3, and a walk of the default scene's nodes
// for mesh/camera/light references), independently of the loader under test.
inline const SampleCounts kSamples[] = {
    {"AlphaBlendModeTest/glTF/AlphaBlendModeTest.gltf", 9, 9, 6, 4, 4, 61, 9, 0, 0},
    {"Avocado/glTF/Avocado.gltf", 1, 1, 1, 3, 3, 682, 1, 0, 0},
    {"BoxTextured/glTF-Binary/BoxTextured.glb", 1, 1, 1, 1, 1, 12, 1, 0, 0},
    {"BoxTextured/glTF/BoxTextured.gltf", 1, 1, 1, 1, 1, 12, 1, 0, 0},
    {"BoxTexturedNonPowerOfTwo/glTF-Binary/BoxTexturedNonPowerOfTwo.glb", 1, 1, 1, 1, 1, 12, 1, 0, 0},
    {"BoxTexturedNonPowerOfTwo/glTF/BoxTexturedNonPowerOfTwo.gltf", 1, 1, 1, 1, 1, 12, 1, 0, 0},
    {"Cameras/glTF/Cameras.gltf", 1, 1, 0, 0, 0, 2, 1, 2, 0},
    {"DamagedHelmet/glTF/DamagedHelmet.gltf", 1, 1, 1, 5, 5, 15452, 1, 0, 0},
    {"EmissiveStrengthTest/glTF-Binary/EmissiveStrengthTest.glb", 6, 6, 6, 1, 1, 90, 6, 0, 0},
    {"EmissiveStrengthTest/glTF/EmissiveStrengthTest.gltf", 6, 6, 6, 1, 1, 90, 6, 0, 0},
    {"LightsPunctualLamp/glTF/LightsPunctualLamp.gltf", 3, 3, 3, 7, 7, 6000, 3, 0, 5},
    {"MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb", 102, 123, 98, 0, 0, 1040409, 102, 0, 0},
    {"MetalRoughSpheresNoTextures/glTF/MetalRoughSpheresNoTextures.gltf", 102, 123, 98, 0, 0, 1040409, 102, 0, 0},
    {"MultiUVTest/glTF-Binary/MultiUVTest.glb", 1, 1, 1, 2, 2, 12, 1, 1, 0},
    {"MultiUVTest/glTF/MultiUVTest.gltf", 1, 1, 1, 2, 2, 12, 1, 1, 0},
    {"NegativeScaleTest/glTF-Binary/NegativeScaleTest.glb", 8, 8, 6, 2, 2, 3884, 11, 0, 0},
    {"NegativeScaleTest/glTF/NegativeScaleTest.gltf", 8, 8, 6, 2, 2, 3884, 11, 0, 0},
    {"NormalTangentMirrorTest/glTF/NormalTangentMirrorTest.gltf", 1, 1, 1, 3, 3, 5240, 1, 0, 0},
    {"NormalTangentTest/glTF/NormalTangentTest.gltf", 1, 1, 1, 3, 3, 7774, 1, 0, 0},
    {"OrientationTest/glTF-Binary/OrientationTest.glb", 13, 13, 7, 0, 0, 524, 13, 0, 0},
    {"OrientationTest/glTF/OrientationTest.gltf", 13, 13, 7, 0, 0, 524, 13, 0, 0},
    {"Suzanne/glTF/Suzanne.gltf", 1, 1, 1, 2, 2, 3936, 1, 0, 0},
    {"TextureCoordinateTest/glTF-Binary/TextureCoordinateTest.glb", 5, 5, 5, 1, 1, 10, 5, 0, 0},
    {"TextureCoordinateTest/glTF/TextureCoordinateTest.gltf", 5, 5, 5, 1, 1, 10, 5, 0, 0},
    {"TextureEncodingTest/glTF-Binary/TextureEncodingTest.glb", 14, 14, 14, 8, 8, 3844, 14, 0, 0},
    {"TextureEncodingTest/glTF/TextureEncodingTest.gltf", 14, 14, 14, 8, 8, 3844, 14, 0, 0},
    {"TextureLinearInterpolationTest/glTF-Binary/TextureLinearInterpolationTest.glb", 3, 3, 3, 2, 2, 642, 3, 0, 0},
    {"TextureLinearInterpolationTest/glTF/TextureLinearInterpolationTest.gltf", 3, 3, 3, 2, 2, 642, 3, 0, 0},
    {"TextureSettingsTest/glTF-Binary/TextureSettingsTest.glb", 10, 10, 10, 9, 3, 72, 10, 0, 0},
    {"TextureSettingsTest/glTF/TextureSettingsTest.gltf", 10, 10, 10, 9, 3, 72, 10, 0, 0},
    {"TextureTransformMultiTest/glTF/TextureTransformMultiTest.gltf", 29, 29, 29, 28, 4, 3956, 29, 0, 0},
    {"TextureTransformTest/glTF/TextureTransformTest.gltf", 9, 9, 9, 5, 5, 18, 12, 0, 0},
    {"ToyCar/glTF/ToyCar.gltf", 3, 3, 3, 8, 8, 108936, 3, 8, 0},
    {"TwoSidedPlane/glTF/TwoSidedPlane.gltf", 1, 1, 1, 3, 3, 2, 1, 0, 0},
    {"VertexColorTest/glTF-Binary/VertexColorTest.glb", 2, 2, 2, 2, 2, 36, 2, 0, 0},
    {"VertexColorTest/glTF/VertexColorTest.gltf", 2, 2, 2, 2, 2, 36, 2, 0, 0},
    {"WaterBottle/glTF/WaterBottle.gltf", 1, 1, 1, 4, 4, 4510, 1, 0, 0},
};

}  // namespace svbrdf::test
