// svbrdf.Material: a material's level-0 texels (textures/material_texels.h) from numpy arrays, image
// files or a glTF material, decoded as svbrdf-bake mip decodes its images (decode_material_texels):
// an integer array is what a PNG of those values holds (sRGB-encoded base color), a float array what
// an OpenEXR holds (linear).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <filesystem>
#include <optional>
#include <string>

#include "mip/gltf_material.h"
#include "python/arrays.h"
#include "python/bindings.h"
#include "textures/image.h"
#include "textures/material_loader.h"

namespace svbrdf::python {

namespace {

// One texture argument: a file (str or os.PathLike), or an array of shape (H, W) or (H, W, C) of
// uint8, uint16, float16 or float32 (float64 is taken as float32). `linear` says whether its values
// are stored as floats.
struct TextureArgument {
  std::optional<Image> image;
  std::string name;
  bool linear = false;
};

TextureArgument texture_argument(const py::object& value, const char* keyword) {
  TextureArgument t;
  if (value.is_none()) return t;
  if (py::isinstance<py::str>(value) || py::hasattr(value, "__fspath__")) {
    const std::filesystem::path path = py::module_::import("os").attr("fspath")(value).cast<std::string>();
    PixelFormat stored{};
    t.image = read_image(path, &stored);
    t.linear = stored == PixelFormat::half || stored == PixelFormat::float32;
    t.name = path.string();
    return t;
  }
  if (!py::isinstance<py::array>(value)) bad_argument(keyword, "expected a file name or a numpy array (H, W[, C])");
  py::array a = py::reinterpret_borrow<py::array>(value);
  t.name = std::string(keyword) + " array";
  if (a.ndim() != 2 && a.ndim() != 3) bad_argument(keyword, "expected an array of shape (H, W) or (H, W, C)");
  const py::dtype dtype = a.dtype();
  PixelFormat format;
  if (dtype.kind() == 'u' && dtype.itemsize() == 1) {
    format = PixelFormat::uint8;
  } else if (dtype.kind() == 'u' && dtype.itemsize() == 2) {
    format = PixelFormat::uint16;
  } else if (dtype.kind() == 'f' && dtype.itemsize() == 2) {
    format = PixelFormat::half;
  } else if (dtype.kind() == 'f') {
    format = PixelFormat::float32;
    a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
  } else {
    bad_argument(keyword, "expected uint8, uint16 or float values");
  }
  a = py::array::ensure(a, py::array::c_style);
  const auto dim = [&](int d) { return static_cast<long long>(a.shape(d)); };
  const long long channels = a.ndim() == 3 ? dim(2) : 1;
  check_image_size(t.name, dim(1), dim(0), static_cast<int>(std::min<long long>(channels, 64)));
  t.image = image_from_stored(a.data(), format, static_cast<int>(dim(1)), static_cast<int>(dim(0)),
                              static_cast<int>(channels), t.name);
  t.linear = format == PixelFormat::half || format == PixelFormat::float32;
  return t;
}

glm::vec3 rgb_argument(const py::handle& value, const char* keyword) {
  const Vectors v(value, keyword);
  if (v.count != 1 || v.array.ndim() != 1) bad_argument(keyword, "expected three numbers r, g, b");
  return v[0];
}

py::array_t<float> plane(const MaterialTexels& m, const std::vector<float>& values) {
  py::array_t<float> out({m.height, m.width});
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

py::array_t<float> planes(const MaterialTexels& m, const std::vector<glm::vec3>& values) {
  py::array_t<float> out({m.height, m.width, 3});
  float* p = out.mutable_data();
  for (const glm::vec3& v : values) *p++ = v.x, *p++ = v.y, *p++ = v.z;
  return out;
}

}  // namespace

MaterialTexels material_from_arguments(const py::object& base_color, const py::object& metallic_roughness,
                                       const py::object& normal, const py::object& base_color_factor,
                                       float metallic_factor, float roughness_factor, float normal_scale) {
  const TextureArgument base = texture_argument(base_color, "base_color"),
                        mr = texture_argument(metallic_roughness, "metallic_roughness"),
                        n = texture_argument(normal, "normal");
  MaterialImages in;
  if (base.image) {
    in.base_color = &*base.image;
    in.base_color_name = base.name;
    in.base_color_is_linear = base.linear;
  }
  if (mr.image) in.metallic_roughness = &*mr.image, in.metallic_roughness_name = mr.name;
  if (n.image) in.normal = &*n.image, in.normal_name = n.name;
  in.base_color_factor = glm::vec4(rgb_argument(base_color_factor, "base_color_factor"), 1.0f);
  in.metallic_factor = metallic_factor;
  in.roughness_factor = roughness_factor;
  in.normal_scale = normal_scale;
  py::gil_scoped_release unlocked;
  return decode_material_texels(in);
}

void bind_material(py::module_& m) {
  py::class_<MaterialTexels>(m, "Material", R"(A material's level-0 texels: linear base color, metallic,
perceptual roughness and the unit normal in the tangent frame, one per texel (brdf-mip.md, "The
material at level 0").

Material(base_color=None, metallic_roughness=None, normal=None, base_color_factor=(1, 1, 1),
metallic_factor=1, roughness_factor=1, normal_scale=1): each texture a file name or a numpy array
(H, W[, C]); integer arrays (uint8, uint16) are read as a PNG of those values is (the base color
sRGB-encoded), float arrays as an OpenEXR's (linear). Channels as glTF's: roughness in G, metallic
in B, the normal map's +Y up. Material.from_gltf(path, material) reads a glTF material.)")
      .def(py::init(&material_from_arguments), py::arg("base_color") = py::none(),
           py::arg("metallic_roughness") = py::none(), py::arg("normal") = py::none(),
           py::arg("base_color_factor") = py::make_tuple(1.0, 1.0, 1.0), py::arg("metallic_factor") = 1.0f,
           py::arg("roughness_factor") = 1.0f, py::arg("normal_scale") = 1.0f)
      .def_static(
          "from_gltf",
          [](const py::object& path, const std::string& material) {
            const std::string file = py::module_::import("os").attr("fspath")(path).cast<std::string>();
            py::gil_scoped_release unlocked;
            return load_gltf_material_texels(file, material);
          },
          py::arg("path"), py::arg("material"), "The level-0 texels of a glTF material, by name or index.")
      .def_readonly("width", &MaterialTexels::width)
      .def_readonly("height", &MaterialTexels::height)
      .def_property_readonly("base_color", [](const MaterialTexels& t) { return planes(t, t.base_color); },
                             "Linear base color, float32 (H, W, 3).")
      .def_property_readonly("metallic", [](const MaterialTexels& t) { return plane(t, t.metallic); })
      .def_property_readonly("roughness", [](const MaterialTexels& t) { return plane(t, t.roughness); },
                             "Perceptual roughness (alpha = roughness^2), float32 (H, W).")
      .def_property_readonly("normal", [](const MaterialTexels& t) { return planes(t, t.normal); },
                             "Unit normals in the tangent frame, float32 (H, W, 3).");
}

}  // namespace svbrdf::python
