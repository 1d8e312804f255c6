#include "apps/direction_text.h"

#include <cmath>
#include <cstdlib>

#include "base/error.h"

namespace svbrdf {
namespace {

glm::vec3 unit(const glm::dvec3& v, const std::string& where, const char* name) {
  const double len = glm::length(v);
  if (!(std::abs(len - 1.0) <= 1e-3))
    throw input_error(where, std::string(name) + " is not a unit vector (length " + std::to_string(len) + ")");
  return glm::vec3(v / len);
}

// Six finite numbers and nothing else on the line; `form` names them in the message.
void read_six(const std::string& line, const std::string& where, const char* form, double (&v)[6]) {
  const std::string expected = std::string("expected six numbers '") + form + "', got '" + line + "'";
  const char* p = line.c_str();
  for (int i = 0; i < 6; ++i) {
    char* end = nullptr;
    v[i] = std::strtod(p, &end);
    if (end == p) throw input_error(where, expected);
    if (!std::isfinite(v[i])) throw input_error(where, "number " + std::to_string(i + 1) + " is not finite");
    p = end;
  }
  for (; *p; ++p)
    if (*p != ' ' && *p != '\t' && *p != '\r') throw input_error(where, expected);
}

bool skipped(const std::string& line) {
  const std::size_t first = line.find_first_not_of(" \t\r");
  return first == std::string::npos || line[first] == '#';
}

}  // namespace

bool parse_direction_line(const std::string& line, long line_number, glm::vec3& wi, glm::vec3& wo,
                          const std::string& source) {
  if (skipped(line)) return false;
  const std::string where = source + " line " + std::to_string(line_number);
  double v[6];
  read_six(line, where, "wi.x wi.y wi.z wo.x wo.y wo.z", v);
  wi = unit({v[0], v[1], v[2]}, where, "wi");
  wo = unit({v[3], v[4], v[5]}, where, "wo");
  return true;
}

bool parse_sample_line(const std::string& line, long line_number, glm::vec3& wo, glm::vec3& u,
                       const std::string& source) {
  if (skipped(line)) return false;
  const std::string where = source + " line " + std::to_string(line_number);
  double v[6];
  read_six(line, where, "wo.x wo.y wo.z u1 u2 u3", v);
  wo = unit({v[0], v[1], v[2]}, where, "wo");
  for (int i = 0; i < 3; ++i) {
    // In [0, 1) as a float: a number just below 1 rounds to 1, which a sampler never receives. Checked
    // before the conversion too, which is undefined for a double beyond float's range.
    const double x = v[3 + i];
    if (!(x >= 0.0 && x < 1.0) || !(static_cast<float>(x) < 1.0f))
      throw input_error(where, "number " + std::to_string(4 + i) + " is not in [0, 1)");
    u[i] = static_cast<float>(x);
  }
  return true;
}

glm::vec3 parse_direction(const std::string& text, const std::string& where) {
  double v[3];
  const char* p = text.c_str();
  for (int i = 0; i < 3; ++i) {
    char* end = nullptr;
    v[i] = std::strtod(p, &end);
    if (end == p || !std::isfinite(v[i])) throw input_error(where, "'" + text + "' is not x,y,z");
    p = end;
    if (i < 2) {
      if (*p != ',') throw input_error(where, "'" + text + "' is not x,y,z");
      ++p;
    }
  }
  if (*p != '\0') throw input_error(where, "'" + text + "' is not x,y,z");
  return unit({v[0], v[1], v[2]}, where, "the direction");
}

}  // namespace svbrdf
