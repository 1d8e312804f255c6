// svbrdf.render(scene, **options): svbrdf-render's options as keywords, parsed by the program's own
// option definitions (apps/render_command.h) and rendered through the same steps, so that a keyword
// is refused, and a scene rendered, exactly as on the command line. The image comes back as numpy
// arrays; files are written only when `out` names the EXR, as the program writes them.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <atomic>
#include <string>
#include <vector>

#include "apps/render_command.h"
#include "apps/render_frames.h"
#include "base/error.h"
#include "python/arrays.h"
#include "python/bindings.h"
#include "python/interruptible.h"
#include "textures/image.h"

namespace svbrdf::python {

namespace {

// A keyword's value as the command line writes it: a flag for True (nothing for False), a sequence
// as its items joined by commas (--sun 45,30; --env 1,1,1), anything else as Python writes it.
void append_option(std::vector<std::string>& args, const std::string& key, const py::handle& value) {
  std::string name = "--" + key;
  for (char& c : name)
    if (c == '_') c = '-';
  if (py::isinstance<py::bool_>(value)) {
    if (value.cast<bool>()) args.push_back(name);
    return;
  }
  std::string text;
  if (!py::isinstance<py::str>(value) && (py::isinstance<py::sequence>(value) || py::isinstance<py::array>(value))) {
    for (const py::handle item : value)
      text += (text.empty() ? "" : ",") + py::str(item).cast<std::string>();
  } else {
    text = py::str(value).cast<std::string>();
  }
  args.push_back(name);
  args.push_back(text);
}

py::array_t<float> image_array(const Image& image) {
  py::array_t<float> out({image.height, image.width, image.channels});
  std::copy(image.pixels.begin(), image.pixels.end(), out.mutable_data());
  return out;
}

// The EXR's R, G, B, A: the radiance premultiplied by alpha, as write_outputs stores it.
py::array_t<float> rgba_array(const Film& film) {
  const Image radiance = film.radiance(), alpha = film.alpha();
  py::array_t<float> out({film.height, film.width, 4});
  float* p = out.mutable_data();
  for (std::size_t k = 0; k < alpha.pixels.size(); ++k) {
    for (int c = 0; c < 3; ++c) *p++ = radiance.pixels[3 * k + c];
    *p++ = alpha.pixels[k];
  }
  return out;
}

py::object render_scene(const py::object& scene, const py::kwargs& kwargs) {
  std::vector<std::string> args{"svbrdf.render", py::module_::import("os").attr("fspath")(scene).cast<std::string>()};
  // Progress lines are for a terminal; a script asks for them with quiet=False.
  if (!kwargs.contains("quiet")) args.push_back("--quiet");
  for (const auto& [key, value] : kwargs) append_option(args, key.cast<std::string>(), value);

  CLI::App app{"svbrdf.render"};
  RenderCommand command;
  command.add_options(app);
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  try {
    app.parse(static_cast<int>(argv.size()), const_cast<char**>(argv.data()));
  } catch (const CLI::ParseError& e) {
    throw input_error("", e.what());
  }
  // One call returns one image: a frame of an animation (frames="12"), not a range of them.
  if (!command.frames.empty() && parse_frames(command.frames).count() > 1)
    throw input_error("frames=" + command.frames, "svbrdf.render returns one frame; render a range with svbrdf-render "
                                                  "--frames, or one frame a call");
  // A Ctrl-C stops the render as it stops the program's, and raises KeyboardInterrupt.
  RenderOutcome outcome;
  call_interruptibly([&](const std::atomic<bool>& cancel) {
    outcome = run_render(command, command.scene_file, "svbrdf.render", cancel);
  });
  if (!command.aovs) return rgba_array(outcome.film);
  py::dict out;
  out["rgba"] = rgba_array(outcome.film);
  out["albedo"] = image_array(outcome.film.albedo());
  out["normal"] = image_array(outcome.film.normal());
  out["depth"] = image_array(outcome.film.depth());
  out["mip_level"] = image_array(outcome.film.mip_level());
  return out;
}

}  // namespace

void bind_render(py::module_& m) {
  m.def("render", &render_scene, py::arg("scene"), R"(Path-traces a glTF 2.0 scene as svbrdf-render does.

Keywords are svbrdf-render's options without the dashes (spp=16, seed=3, res="64x48",
filter="param", sun=(45, 30), aov=True, ...); they are checked as the program checks them. Returns
the image as float32 (H, W, 4): the linear RGBA the program's EXR holds (bit for bit with float=True
there); with aov=True a dict of it ("rgba") and the layers albedo, normal, depth, mip_level. Nothing
is written unless out= names an EXR (then the EXR and PNG are written as the program writes them).
Quiet unless quiet=False. A Ctrl-C stops the render (once its first pass is done) and raises
KeyboardInterrupt; with out=, the files hold what had accumulated, as the program writes them.)");
  m.def("read_image", [](const py::object& path) {
          const std::string file = py::module_::import("os").attr("fspath")(path).cast<std::string>();
          Image image;
          {
            py::gil_scoped_release unlocked;
            image = read_image(file);
          }
          return image_array(image);
        }, py::arg("path"), "An image file as float32 (H, W, C), values as stored (OpenImageIO; an EXR's RGBA in that order).");
}

}  // namespace svbrdf::python
