#pragma once
// The one exception type of the project (DESIGN.md, "Errors"): thrown at I/O and input
// boundaries, carrying what went wrong and where (a file, a glTF JSON path, a line number).
// Programs print what() as one line and exit 2 for bad input, 1 for an internal failure or one of
// the environment (a full disk, a folder the user may not write): the input was fine, so a
// script that retries or reports must not take it for the user's mistake.
#include <stdexcept>
#include <string>

namespace svbrdf {

class Error : public std::runtime_error {
 public:
  enum class Kind { bad_input, internal, environment };

  explicit Error(const std::string& message, Kind kind = Kind::bad_input)
      : std::runtime_error(message), kind_(kind) {}

  Kind kind() const { return kind_; }
  int exit_code() const { return kind_ == Kind::bad_input ? 2 : 1; }

 private:
  Kind kind_;
};

// "where: what" — the shape of every message, e.g. "scene.gltf: meshes[2].primitives[0]: ...".
inline Error input_error(const std::string& where, const std::string& what) {
  return Error(where.empty() ? what : where + ": " + what, Error::Kind::bad_input);
}

// The same shape for a failure of the machine rather than the input: the disk is full, the folder
// is read-only, a write or fsync failed.
inline Error environment_error(const std::string& where, const std::string& what) {
  return Error(where.empty() ? what : where + ": " + what, Error::Kind::environment);
}

}  // namespace svbrdf
