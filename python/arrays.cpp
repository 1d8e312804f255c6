#include "python/arrays.h"

#include "base/error.h"

namespace svbrdf::python {

namespace {

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

}  // namespace

void bad_argument(const std::string& where, const std::string& what) { throw input_error(where, what); }

Vectors::Vectors(const py::handle& object, const char* where) {
  array = FloatArray::ensure(object);  // null, the Python error cleared, when it is not numbers
  if (!array) bad_argument(where, "expected an array of numbers of shape (N, 3)");
  if (array.ndim() < 1 || array.shape(array.ndim() - 1) != 3)
    bad_argument(where, "expected an array of shape (N, 3), got " + shape_text(array));
  count = static_cast<std::size_t>(array.size() / 3);
  first = array.data();
  step = count == 1 ? 0 : 3;
  for (py::ssize_t d = 0; d + 1 < array.ndim(); ++d) shape.push_back(array.shape(d));
}

VectorPairs::VectorPairs(const py::handle& first, const char* first_name, const py::handle& second,
                         const char* second_name, const char* call)
    : a(first, first_name), b(second, second_name) {
  if (a.shape == b.shape) {
    count = a.count;
    shape = a.shape;
  } else if (a.array.ndim() == 1) {
    count = b.count;
    shape = b.shape;
  } else if (b.array.ndim() == 1) {
    count = a.count;
    shape = a.shape;
  } else {
    bad_argument(call, std::string(first_name) + " and " + second_name +
                           " must have the same shape, or one of them be a single vector of shape (3,)");
  }
}

}  // namespace svbrdf::python
