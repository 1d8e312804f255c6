// svbrdf.build_mip / svbrdf.read_mip and svbrdf.Mip: both pyramids of a material (mip/mip_data.h) and
// the ways brdf-mip.md answers for a texel, as svbrdf-bake eval and compare answer: the reference
// `exact`, and the filters that store texels (param, toksvig, vmf, brdf); the spec's metrics.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <filesystem>
#include <optional>
#include <string>
#include <tuple>
#include <utility>

#include "mip/metrics.h"
#include "mip/mip_file.h"
#include "mip/texture_filter.h"
#include "python/arrays.h"
#include "python/bindings.h"

namespace svbrdf::python {

namespace {

std::string path_argument(const py::object& path) {
  return py::module_::import("os").attr("fspath")(path).cast<std::string>();
}

// exact (nullopt) or a filter that stores coarse texels; level0 stores none.
std::optional<TextureFilter> mode_argument(const std::string& mode) {
  const std::optional<TextureFilter> filter = parse_filter(mode);
  if (filter ? *filter == TextureFilter::level0 : mode != "exact")
    bad_argument("mode", "unknown mode '" + mode + "' (exact, param, toksvig, vmf, brdf)");
  return filter;
}

py::array_t<double> table_array(const BrdfTable& t) {
  py::array_t<double> out({static_cast<py::ssize_t>(t.size()), py::ssize_t(3)});
  double* p = out.mutable_data();
  for (const glm::dvec3& v : t) *p++ = v.x, *p++ = v.y, *p++ = v.z;
  return out;
}

BrdfTable table_argument(const py::handle& value, const char* keyword) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!a || a.ndim() != 2 || a.shape(0) != DirectionGrid::kPairs || a.shape(1) != 3)
    bad_argument(keyword, "expected a table of shape (" + std::to_string(DirectionGrid::kPairs) + ", 3)");
  BrdfTable t(DirectionGrid::kPairs);
  for (std::size_t k = 0; k < t.size(); ++k) t[k] = {a.at(k, 0), a.at(k, 1), a.at(k, 2)};
  return t;
}

MipData build(MaterialTexels material, int lobes, float tolerance) {
  if (lobes < 1 || lobes > kMaxLobes)
    bad_argument("lobes", std::to_string(lobes) + " is out of range (1.." + std::to_string(kMaxLobes) + ")");
  if (!(tolerance >= 0 && tolerance < 1)) bad_argument("tolerance", "must be in [0, 1)");
  BrdfBuildOptions options;
  options.reduction.max_lobes = lobes;
  options.reduction.tolerance = tolerance;
  py::gil_scoped_release unlocked;
  return build_mip(std::move(material), options);
}

py::array_t<double> eval(const MipData& mip, const std::string& mode, int level, std::pair<int, int> texel,
                         const py::handle& wi, const py::handle& wo) {
  const std::optional<TextureFilter> filter = mode_argument(mode);
  check_texel(mip, level, texel.first, texel.second);
  const VectorPairs p(wi, "wi", wo, "wo", "eval");
  py::array_t<double> out = make_array<double>(p.shape, 3);
  double* f = out.mutable_data();
  {
    py::gil_scoped_release unlocked;
    const ExactReference reference(mip.level0);
    for (std::size_t k = 0; k < p.count; ++k) {
      const glm::dvec3 a(p.a[k]), b(p.b[k]);
      const glm::dvec3 v = filter ? texel_eval(mip, *filter, level, texel.first, texel.second, a, b)
                                  : reference.eval(level, texel.first, texel.second, a, b);
      f[3 * k] = v.x, f[3 * k + 1] = v.y, f[3 * k + 2] = v.z;
    }
  }
  return out;
}

py::array_t<double> table(const MipData& mip, const std::string& mode, int level, std::pair<int, int> texel) {
  const std::optional<TextureFilter> filter = mode_argument(mode);
  check_texel(mip, level, texel.first, texel.second);
  BrdfTable t;
  {
    py::gil_scoped_release unlocked;
    t = filter ? texel_table(mip, *filter, level, texel.first, texel.second)
               : ExactReference(mip.level0).table(level, texel.first, texel.second);
  }
  return table_array(t);
}

py::list compare(const MipData& mip, std::optional<std::pair<int, int>> levels, int subset) {
  if (subset < 1) bad_argument("subset", "must be at least 1");
  CompareOptions c;
  c.subset = subset;
  c.first_level = std::min(1, mip.levels() - 1);
  c.last_level = mip.levels() - 1;
  if (levels) std::tie(c.first_level, c.last_level) = *levels;
  std::vector<LevelComparison> rows;
  {
    py::gil_scoped_release unlocked;
    rows = compare_levels(mip, c);
  }
  py::list out;
  for (const LevelComparison& l : rows) {
    py::dict modes;
    for (const ModeLevelStats& s : l.modes)
      modes[py::str(std::string(filter_name(s.mode)))] =
          py::dict(py::arg("e_rel_mean") = s.erel_mean, py::arg("e_rel_max") = s.erel_max,
                   py::arg("e_log") = s.elog_mean, py::arg("e_mean") = s.emean,
                   py::arg("bytes_per_texel") = s.bytes_per_texel);
    out.append(py::dict(py::arg("level") = l.level, py::arg("width") = l.extent.width,
                        py::arg("height") = l.extent.height, py::arg("measured") = l.measured,
                        py::arg("random_subset") = l.subset, py::arg("modes") = modes));
  }
  return out;
}

py::array_t<double> grid_directions() {
  const DirectionGrid& g = DirectionGrid::get();
  py::array_t<double> out({py::ssize_t(DirectionGrid::kDirections), py::ssize_t(3)});
  double* p = out.mutable_data();
  for (int d = 0; d < DirectionGrid::kDirections; ++d) *p++ = g.direction(d).x, *p++ = g.direction(d).y, *p++ = g.direction(d).z;
  return out;
}

}  // namespace

void bind_mip(py::module_& m) {
  py::class_<MipData>(m, "Mip", R"(Both pyramids of a material: the parameter pyramid (param, toksvig,
vmf) and the BRDF pyramid (brdf), with level 0 for the reference `exact` (brdf-mip.md). Made by
build_mip(material) or read_mip(path). Texels are (i, j): column i, row j from the top.)")
      .def_property_readonly("levels", &MipData::levels)
      .def("extent", [](const MipData& d, int level) {
            if (level < 0 || level >= d.levels())
              bad_argument("level", std::to_string(level) + " is out of range (0.." + std::to_string(d.levels() - 1) + ")");
            return std::make_pair(d.extent(level).width, d.extent(level).height);
          }, py::arg("level"), "(width, height) of a level.")
      .def_property_readonly("material", [](const MipData& d) { return d.level0; }, "Level 0 (a copy).")
      .def("eval", &eval, py::arg("mode"), py::arg("level"), py::arg("texel"), py::arg("wi"), py::arg("wo"),
           "F of texel (i, j) of `level` under mode exact | param | toksvig | vmf | brdf, for direction pairs "
           "(..., 3) in the geometric tangent frame: float64 (..., 3), as svbrdf-bake eval prints it.")
      .def("table", &table, py::arg("mode"), py::arg("level"), py::arg("texel"),
           "F of a texel over the metric's 4225 direction pairs (GRID_DIRECTIONS; pair p = i*65 + o): "
           "float64 (4225, 3).")
      .def("compare", &compare, py::arg("levels") = py::none(), py::arg("subset") = 256,
           "Per level, each filter's e_rel (mean, max), e_log and e_mean against exact, as svbrdf-bake "
           "compare --json: a list of dicts. `levels` = (first, last), default 1 to the last.")
      .def("write", [](const MipData& d, const py::object& path) {
            const std::string file = path_argument(path);
            py::gil_scoped_release unlocked;
            write_mip_file(file, d);
          }, py::arg("path"), "Writes the MIP file (OpenEXR) svbrdf-bake mip writes.");

  m.def("build_mip", &build, py::arg("material"), py::arg("lobes") = kDefaultLobes,
        py::arg("tolerance") = ReductionOptions{}.tolerance,
        "Builds both pyramids of a Material, as svbrdf-bake mip --lobes --tolerance does.");
  m.def("read_mip", [](const py::object& path) {
          const std::string file = path_argument(path);
          py::gil_scoped_release unlocked;
          return read_mip_file(file);
        }, py::arg("path"), "Reads a MIP file (svbrdf-bake mip's output).");
  m.def("e_rel", [](const py::handle& approx, const py::handle& exact) {
          return e_rel(table_argument(approx, "approx"), table_argument(exact, "exact"));
        }, py::arg("approx"), py::arg("exact"), "brdf-mip.md's e_rel of two tables (Mip.table), on L = F*wi.z.");
  m.def("e_log", [](const py::handle& approx, const py::handle& exact) {
          return e_log(table_argument(approx, "approx"), table_argument(exact, "exact"));
        }, py::arg("approx"), py::arg("exact"), "brdf-mip.md's e_log of two tables (Mip.table).");
  m.attr("GRID_DIRECTIONS") = grid_directions();
}

}  // namespace svbrdf::python
