#pragma once
// The text forms of directions that svbrdf-brdf reads (brdf-models.md, last section): an input line
// of six numbers "wi.x wi.y wi.z wo.x wo.y wo.z" (sample --stdin: "wo.x wo.y wo.z u1 u2 u3") and
// "x,y,z" for --wo. Directions must be unit length (within 1e-3; they are then renormalized): a wrong
// one is an error, not silently fixed.
#include <string>

#include <glm/glm.hpp>

namespace svbrdf {

// Returns false for a blank line or one starting with '#' (after leading blanks). Throws
// svbrdf::Error "<source> line N: ..." for anything else that is not six finite numbers forming two
// unit vectors.
bool parse_direction_line(const std::string& line, long line_number, glm::vec3& wi, glm::vec3& wo,
                          const std::string& source = "stdin");

// A line of svbrdf-brdf sample --stdin: "wo.x wo.y wo.z u1 u2 u3", a unit direction and three numbers in
// [0, 1) (as float32). Blank and '#' lines, and errors, as parse_direction_line.
bool parse_sample_line(const std::string& line, long line_number, glm::vec3& wo, glm::vec3& u,
                       const std::string& source = "stdin");

// "x,y,z" → a unit vector; throws svbrdf::Error naming `where`.
glm::vec3 parse_direction(const std::string& text, const std::string& where);

}  // namespace svbrdf
