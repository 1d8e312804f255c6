#pragma once
// A minimal SVG 1.1 document builder for the plots of svbrdf-brdf (polar_plot.h, fresnel_plot.h):
// lines, polylines, circles, arrows and text in user units, y pointing down as SVG has it.
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace svbrdf {

// A number as a plot's label writes it: four significant digits.
std::string plot_number(double x);

class Svg {
 public:
  Svg(double width, double height);
  void line(glm::dvec2 a, glm::dvec2 b, const std::string& color, double width = 1, const std::string& dash = "");
  void polyline(const std::vector<glm::dvec2>& points, const std::string& color, double width = 1.5,
                const std::string& dash = "");
  void circle(glm::dvec2 center, double radius, const std::string& color, double width = 1, const std::string& dash = "");
  // A line from a to b with a filled arrow head at b.
  void arrow(glm::dvec2 a, glm::dvec2 b, const std::string& color, double width = 2);
  void text(glm::dvec2 at, const std::string& s, double size = 14, const std::string& color = "black",
            const std::string& anchor = "start");
  std::string str() const;
  // Written atomically (base/atomic_file.h); throws svbrdf::Error naming the file on failure.
  void write(const std::filesystem::path& path) const;

 private:
  double width_, height_;
  std::string body_;
};


}  // namespace svbrdf
