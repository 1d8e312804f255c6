#pragma once
// Builds a model of brdf-models.md from its name and `k=v` parameters (what `svbrdf-brdf` takes
// after `--param`), with validation: an unknown model or parameter, a malformed number, NaN or
// infinity, a value out of range, a parameter repeated or meaningless for the chosen options is an
// svbrdf::Error (bad input, exit 2) naming the model and the parameter.
#include <memory>
#include <string>
#include <vector>

#include "appearance/bsdf.h"

namespace svbrdf {

// Strict text → number: the whole text, finite; "r,g,b" or one number for gray. Throw
// svbrdf::Error naming `where`.
float parse_finite_number(const std::string& text, const std::string& where);
Rgb parse_rgb(const std::string& text, const std::string& where);

// The model names, in the order of brdf-models.md.
const std::vector<std::string>& model_names();
// One line per model: its parameters with their defaults and ranges (for --help).
std::string models_help();

// `params` are "key=value" strings; RGB values are "r,g,b" or one number for gray.
std::unique_ptr<Bsdf> make_model(const std::string& name, const std::vector<std::string>& params);

// The §27.14 combination: the model plus impulses, each "NAME[:SCALE]" with NAME one of mirror,
// dielectric, conductor-mirror (default parameters) and SCALE ∈ [0, 1] (default 1) its weight —
// `mirror:0.4` adds a mirror impulse of magnitude 0.4. Without impulses this is make_model.
std::unique_ptr<Bsdf> make_model(const std::string& name, const std::vector<std::string>& params,
                                 const std::vector<std::string>& impulses);

}  // namespace svbrdf
