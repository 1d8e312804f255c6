#pragma once
// numpy arrays at the module's boundary: arrays of directions (…, 3) read as float32 without a Python
// loop, and results made in the shape of the input.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace svbrdf::python {

namespace py = pybind11;

// float32, C order: other float and integer arrays are converted once on the way in.
using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

// Throws svbrdf::Error (bad input), which the module raises as svbrdf.InputError (module.cpp).
[[noreturn]] void bad_argument(const std::string& where, const std::string& what);

// An array of 3-vectors, shape (…, 3), or one 3-vector that pairs with every row of another.
struct Vectors {
  FloatArray array;
  std::size_t count = 0;
  std::vector<py::ssize_t> shape;  // the leading dimensions (… of (…, 3))

  Vectors(const py::handle& object, const char* where);
  glm::vec3 operator[](std::size_t k) const {
    const float* p = first + step * k;
    return {p[0], p[1], p[2]};
  }

  const float* first = nullptr;  // the first vector's x
  std::size_t step = 0;          // floats from one vector to the next: 3, or 0 for one vector paired with many
};

// Two arrays of vectors taken pairwise: the same leading shape, or one of them a single vector.
struct VectorPairs {
  Vectors a, b;
  std::size_t count = 0;
  std::vector<py::ssize_t> shape;
  VectorPairs(const py::handle& first, const char* first_name, const py::handle& second, const char* second_name,
              const char* call);
};

// work(k, a, b) for each pair k in order, a and b referring into the arrays themselves (three floats in
// a row are a glm::vec3: tightly packed, float-aligned). The loop holds plain pointers in locals and
// copies nothing: reloading the arrays' addresses, branching on their shapes or copying the vectors
// to pass them by reference at every pair costs as much as a cheap model's eval.
template <class Work>
void for_each_pair(const VectorPairs& p, Work&& work) {
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float) && alignof(glm::vec3) == alignof(float));
  const auto* a = reinterpret_cast<const glm::vec3*>(p.a.first);
  const auto* b = reinterpret_cast<const glm::vec3*>(p.b.first);
  const std::size_t step_a = p.a.step / 3, step_b = p.b.step / 3, count = p.count;
  for (std::size_t k = 0; k < count; ++k, a += step_a, b += step_b) work(k, *a, *b);
}

// An uninitialized array of `shape` with `last` more values per element (0: none).
template <class T>
py::array_t<T> make_array(std::vector<py::ssize_t> shape, py::ssize_t last) {
  if (last > 0) shape.push_back(last);
  return py::array_t<T>(shape);
}

}  // namespace svbrdf::python
