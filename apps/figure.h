#pragma once
// A plot of svbrdf-brdf (polar_plot.h, fresnel_plot.h) as a list of shapes in user units, y pointing
// down as SVG has it: lines, polylines, circles, arrows and text. Written as SVG 1.1 text or as a PNG
// rasterized here (figure_raster.cpp), one user unit to one pixel, chosen by the file's extension.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "textures/image.h"

namespace svbrdf {

// A number as a plot's label writes it: four significant digits.
std::string plot_number(double x);

class Figure {
 public:
  // Colors are "black", "white" or "#rrggbb"; a dash is SVG's stroke-dasharray ("7,5": on, off).
  struct Shape {
    enum class Kind { line, polyline, circle, polygon, text } kind = Kind::line;
    std::vector<glm::dvec2> points;  // line: two; circle and text: one (the center, the anchor)
    std::string color;
    double width = 1;                // stroke width; circle: also `radius` below
    std::string dash;
    double radius = 0;
    std::string text;
    double size = 14;                // font size (em) of a text
    std::string anchor = "start";    // start | middle | end
  };

  Figure(double width, double height);
  void line(glm::dvec2 a, glm::dvec2 b, const std::string& color, double width = 1, const std::string& dash = "");
  void polyline(const std::vector<glm::dvec2>& points, const std::string& color, double width = 1.5,
                const std::string& dash = "");
  void circle(glm::dvec2 center, double radius, const std::string& color, double width = 1, const std::string& dash = "");
  // A line from a to b with a filled arrow head at b.
  void arrow(glm::dvec2 a, glm::dvec2 b, const std::string& color, double width = 2);
  void text(glm::dvec2 at, const std::string& s, double size = 14, const std::string& color = "black",
            const std::string& anchor = "start");

  double width() const { return width_; }
  double height() const { return height_; }
  const std::vector<Shape>& shapes() const { return shapes_; }

  // The box a text shape covers in the PNG, in pixels: its top-left and bottom-right corners, as
  // OpenImageIO lays it out in the PNG's font at its anchor. Throws as raster() does where no font can
  // be found.
  static std::pair<glm::dvec2, glm::dvec2> text_box(const Shape& text);

  std::string svg() const;
  // RGB on white, ceil(width) × ceil(height) pixels, antialiased; text drawn by OpenImageIO with the
  // DejaVu Sans font (Debian's fonts-dejavu-core). Throws svbrdf::Error (environment) when no font
  // can be found.
  Image raster() const;
  // `.svg` or `.png`, written atomically (base/atomic_file.h); another extension is bad input naming
  // the file, a failed write an svbrdf::Error naming it.
  void write(const std::filesystem::path& path) const;

 private:
  double width_, height_;
  std::vector<Shape> shapes_;
};

}  // namespace svbrdf
