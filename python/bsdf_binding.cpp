// svbrdf.Bsdf: a model of brdf-models.md built by name and parameters as svbrdf-brdf builds it
// (appearance/registry.h make_model: the same validation and the same messages), evaluated, sampled
// and its density computed over numpy arrays of direction pairs in one call.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <string>
#include <vector>

#include "appearance/registry.h"
#include "python/arrays.h"
#include "python/bindings.h"

namespace svbrdf::python {

namespace {

// A keyword argument as make_model's "key=value" text: a string as it is, a number as Python writes it
// (the shortest text that reads back to the same value), a sequence as its numbers joined by commas
// ("r,g,b", as the command line writes a colour).
std::string param_text(const std::string& key, const py::handle& value) {
  std::string text;
  if (py::isinstance<py::str>(value)) {
    text = value.cast<std::string>();
  } else if (py::isinstance<py::sequence>(value) || py::isinstance<py::array>(value)) {
    for (const py::handle item : value) {
      if (!text.empty()) text += ",";
      text += py::str(item).cast<std::string>();
    }
  } else {
    text = py::str(value).cast<std::string>();
  }
  return key + "=" + text;
}

class PyBsdf {
 public:
  PyBsdf(const std::string& model, const py::kwargs& kwargs) : model_(model) {
    for (const auto& [key, value] : kwargs) {
      const std::string name = key.cast<std::string>();
      if (name == "impulses" && py::isinstance<py::str>(value)) {
        impulses_.push_back(value.cast<std::string>());
      } else if (name == "impulses") {
        for (const py::handle item : value) impulses_.push_back(py::str(item).cast<std::string>());
      } else {
        params_.push_back(param_text(name, value));
      }
    }
    bsdf_ = make_model(model_, params_, impulses_);
  }

  py::array_t<float> eval(const py::handle& wi, const py::handle& wo) const {
    const VectorPairs p(wi, "wi", wo, "wo", "eval");
    py::array_t<float> out = make_array<float>(p.shape, 3);
    float* f = out.mutable_data();
    {
      py::gil_scoped_release unlocked;
      const Bsdf& bsdf = *bsdf_;
      for_each_pair(p, [&](std::size_t k, const glm::vec3& wi, const glm::vec3& wo) {
        const Rgb v = bsdf.eval(wi, wo);
        f[3 * k] = v.x, f[3 * k + 1] = v.y, f[3 * k + 2] = v.z;
      });
    }
    return out;
  }

  py::array_t<float> pdf(const py::handle& wi, const py::handle& wo) const {
    const VectorPairs p(wi, "wi", wo, "wo", "pdf");
    py::array_t<float> out = make_array<float>(p.shape, 0);
    float* d = out.mutable_data();
    {
      py::gil_scoped_release unlocked;
      const Bsdf& bsdf = *bsdf_;
      for_each_pair(p, [&](std::size_t k, const glm::vec3& wi, const glm::vec3& wo) { d[k] = bsdf.pdf(wi, wo); });
    }
    return out;
  }

  // (wi, pdf, weight, kind): kind 0 finite, 1 impulse, 2 absorbed (SAMPLE_KINDS).
  py::tuple sample(const py::handle& wo, const py::handle& u) const {
    const VectorPairs p(wo, "wo", u, "u", "sample");
    py::array_t<float> wi = make_array<float>(p.shape, 3), pdf = make_array<float>(p.shape, 0),
                       weight = make_array<float>(p.shape, 3);
    py::array_t<std::uint8_t> kind = make_array<std::uint8_t>(p.shape, 0);
    float *w = wi.mutable_data(), *d = pdf.mutable_data(), *g = weight.mutable_data();
    std::uint8_t* k8 = kind.mutable_data();
    {
      py::gil_scoped_release unlocked;
      const Bsdf& bsdf = *bsdf_;
      for_each_pair(p, [&](std::size_t k, const glm::vec3& wo, const glm::vec3& u) {
        const BsdfSample s = bsdf.sample(wo, u);
        w[3 * k] = s.wi.x, w[3 * k + 1] = s.wi.y, w[3 * k + 2] = s.wi.z;
        d[k] = s.pdf;
        g[3 * k] = s.weight.x, g[3 * k + 1] = s.weight.y, g[3 * k + 2] = s.weight.z;
        k8[k] = s.kind == SampleKind::finite ? 0 : s.kind == SampleKind::impulse ? 1 : 2;
      });
    }
    return py::make_tuple(wi, pdf, weight, kind);
  }

  std::string repr() const {
    std::string text = "svbrdf.Bsdf('" + model_ + "'";
    for (const std::string& p : params_) text += ", " + p;
    for (const std::string& i : impulses_) text += ", +" + i;
    return text + ")";
  }

 private:
  std::string model_;
  std::vector<std::string> params_, impulses_;
  std::unique_ptr<Bsdf> bsdf_;
};

}  // namespace

void bind_bsdf(py::module_& m) {
  m.def("model_names", &model_names, "The BRDF models' names, in the order of brdf-models.md.");
  m.def("models_help", &models_help, "Each model's parameters with their defaults and ranges, one line a model.");
  m.attr("SAMPLE_KINDS") = py::make_tuple("finite", "impulse", "absorbed");
  py::class_<PyBsdf>(m, "Bsdf", R"(A BRDF model of brdf-models.md, as svbrdf-brdf builds it.

Bsdf(model, impulses=(), **params): `model` is one of model_names(); each keyword is a parameter
(a number, or r,g,b as a sequence or a string "r,g,b"); `impulses` lists "NAME[:SCALE]" as
svbrdf-brdf's --impulse. Directions are in the local shading frame (z = normal), both pointing away
from the surface: wi toward the light, wo toward the viewer.)")
      .def(py::init<const std::string&, const py::kwargs&>(), py::arg("model"))
      .def("eval", &PyBsdf::eval, py::arg("wi"), py::arg("wo"),
           "f(wi, wo), the finite part, for arrays of shape (..., 3) (or one (3,) vector against many): "
           "float32 of shape (..., 3).")
      .def("pdf", &PyBsdf::pdf, py::arg("wi"), py::arg("wo"),
           "The density with which sample() draws wi for wo (solid angle): float32 of shape (...).")
      .def("sample", &PyBsdf::sample, py::arg("wo"), py::arg("u"),
           "One sample per row of uniform numbers u in [0, 1)^3: (wi, pdf, weight, kind), kind indexing "
           "SAMPLE_KINDS.")
      .def("__repr__", &PyBsdf::repr);
}

}  // namespace svbrdf::python
