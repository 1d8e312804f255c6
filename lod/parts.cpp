#include "lod/parts.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <regex>

#include "base/error.h"
#include "base/json.h"

namespace svbrdf {

namespace fs = std::filesystem;

namespace {

constexpr const char* kFormat = "svbrdf-lod-part";
constexpr int kVersion = 1;

// The run a part belongs to: everything that decides which shots there are and what they render,
// and what the report prints. Two parts belong to one comparison when these are equal.
Json run_json(const LodResults& r, const LodPartRun& run) {
  const LodOptions& o = r.options;
  return {{"manifest", run.manifest.string()},
          {"size_name", run.size_name},
          {"command", run.command},
          {"parts", o.parts},
          {"spp", o.spp},
          {"seeds", Json::array({o.seed, o.second_seed, o.filter_seed})},
          {"footprint_scale", double(o.footprint_scale)},
          {"filters_asked", o.filters},
          {"cases", o.cases},
          {"lights", o.lights},
          {"views", o.views},
          {"distances", o.distances},
          {"min_distance", o.min_distance},
          // JSON has no infinity: the default, no upper bound, is null.
          {"max_distance", std::isfinite(o.max_distance) ? Json(o.max_distance) : Json()},
          {"image_size", r.image_size},
          {"total_shots", r.total_shots},
          {"filters", r.filters},
          {"unavailable", r.unavailable}};
}

Json metrics_json(const LodMetrics& m) {
  return {{"rel_mse", m.rel_mse}, {"flux_bias", m.flux_bias}, {"peak_ratio", m.peak_ratio}};
}

LodMetrics read_metrics(const JsonNode& n) {
  n.only({"rel_mse", "flux_bias", "peak_ratio"});
  return {n["rel_mse"].number(), n["flux_bias"].number(), n["peak_ratio"].number()};
}

std::vector<std::string> strings(const JsonNode& n) {
  std::vector<std::string> out;
  for (const JsonNode& item : n.items()) out.push_back(item.string());
  return out;
}

// An image of the part, of the run's size and `channels` channels.
Image read_part_image(const fs::path& dir, const JsonNode& name, int size, int channels) {
  const std::string& file = name.string();
  if (file.empty() || fs::path(file).filename() != fs::path(file))
    name.fail("not a file name of the part's folder");
  const fs::path path = dir / file;
  Image im = read_image(path);
  if (im.width != size || im.height != size || im.channels != channels)
    throw input_error(path.string(), "is " + std::to_string(im.width) + "x" + std::to_string(im.height) +
                                         " with " + std::to_string(im.channels) +
                                         " channels, not the run's " + std::to_string(size) + "x" +
                                         std::to_string(size) + " with " + std::to_string(channels));
  return im;
}

// The member where two runs first differ, for the message.
std::string first_difference(const Json& a, const Json& b) {
  for (auto it = a.begin(); it != a.end(); ++it)
    if (!b.contains(it.key()) || b.at(it.key()) != it.value()) return it.key();
  return "its members";
}

}  // namespace

std::string lod_part_name(int part, int parts) {
  return "lod-part-" + std::to_string(part) + "-of-" + std::to_string(parts) + ".json";
}

void write_lod_part(const LodResults& r, const LodPartRun& run, const fs::path& dir) {
  const int part = r.options.part, parts = r.options.parts;
  const std::string stem = "lod-part-" + std::to_string(part) + "-of-" + std::to_string(parts);
  Json shots = Json::array();
  for (const LodShot& s : r.shots) {
    if (s.truth.pixels.empty())
      throw Error("write_lod_part: the shots' images were not kept", Error::Kind::internal);
    const std::string prefix = stem + ".shot-" + std::to_string(s.index) + ".";
    write_image(dir / (prefix + "truth.exr"), s.truth, PixelFormat::float32);
    Image mask(s.truth.width, s.truth.height, 1);
    for (std::size_t i = 0; i < s.mask.size(); ++i) mask.pixels[i] = s.mask[i] ? 1.0f : 0.0f;
    write_image(dir / (prefix + "mask.exr"), mask, PixelFormat::float32);
    Json filters = Json::array();
    for (const LodShot::FilterResult& f : s.filters) {
      write_image(dir / (prefix + f.filter + ".exr"), f.image, PixelFormat::float32);
      filters.push_back({{"filter", f.filter},
                         {"metrics", metrics_json(f.metrics)},
                         {"image", prefix + f.filter + ".exr"}});
    }
    shots.push_back({{"index", s.index},
                     {"case", s.case_name},
                     {"kind", s.kind},
                     {"view", s.view},
                     {"light", s.light},
                     {"camera", s.camera},
                     {"multiple", s.multiple},
                     {"floor", metrics_json(s.floor)},
                     {"flux_sigma", s.flux_sigma},
                     {"truth", prefix + "truth.exr"},
                     {"mask", prefix + "mask.exr"},
                     {"filters", std::move(filters)}});
  }
  const Json doc = {{"format", kFormat},        {"version", kVersion},     {"part", part},
                    {"parts", parts},           {"run", run_json(r, run)}, {"seconds", r.seconds},
                    {"shots", std::move(shots)}};
  write_json_file(dir / lod_part_name(part, parts), doc);  // last: the part is whole once it exists
}

LodResults read_lod_parts(const fs::path& dir, LodPartRun& run) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw input_error(dir.string(), "no such folder of LOD parts");
  // The parts by number; a folder holding parts of two part counts is refused below (foreign).
  const std::regex name_rule(R"(lod-part-(\d{1,9})-of-(\d{1,9})\.json)");
  std::map<std::pair<int, int>, fs::path> files;  // (N, I) → file
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    std::smatch m;
    const std::string name = e.path().filename().string();
    if (std::regex_match(name, m, name_rule))
      files[{std::stoi(m[2].str()), std::stoi(m[1].str())}] = e.path();
  }
  if (ec) throw input_error(dir.string(), "cannot list the folder: " + ec.message());
  if (files.empty()) throw input_error(dir.string(), "holds no LOD part (lod-part-I-of-N.json)");

  LodResults r;
  Json first_run;
  fs::path first_file;
  std::map<int, fs::path> holder;  // shot index → the part file that holds it
  for (const auto& [key, file] : files) {
    const auto [parts, part] = key;
    const JsonDocument doc = JsonDocument::read(file);
    const JsonNode root = doc.root();
    if (!root.is_object() || !root.has("format") || root["format"].value() != kFormat)
      throw input_error(file.string(), "not an svbrdf-lod-report part");
    if (root["version"].integer(0, 1 << 30) != kVersion)
      root["version"].fail("a part of another version of svbrdf-lod-report (this one reads version " +
                           std::to_string(kVersion) + ")");
    root.only({"format", "version", "part", "parts", "run", "seconds", "shots"});
    if (root["part"].integer(0, 1 << 30) != part || root["parts"].integer(1, 1 << 30) != parts)
      throw input_error(file.string(), "holds part " + std::to_string(root["part"].integer(0, 1 << 30)) +
                                           " of " + std::to_string(root["parts"].integer(1, 1 << 30)) +
                                           ", not the one its name says: a copy of another part");
    if (!root["run"].is_object()) root["run"].fail("not an object");
    const Json& run_value = root["run"].value();
    if (first_file.empty()) {
      first_run = run_value, first_file = file;
    } else if (run_value != first_run) {
      throw input_error(file.string(), "a part of another comparison than " + first_file.string() + " (its " +
                                           first_difference(first_run, run_value) + " differs)");
    }
    if (run_value.value("parts", -1) != parts)
      throw input_error(file.string(),
                        "its run is not in " + std::to_string(parts) + " parts, as its name says");
    const JsonNode rn = root["run"];
    const int size = rn["image_size"].integer(1, 1 << 16);
    r.image_size = size;
    r.seconds += root["seconds"].number(0.0, 1e300);
    for (const JsonNode& s : root["shots"].items()) {
      LodShot shot;
      shot.index = s["index"].integer(0, 1 << 30);
      if (shot.index % parts != part)
        s["index"].fail("shot " + std::to_string(shot.index) + " is not one of part " + std::to_string(part) +
                        " of " + std::to_string(parts) + " (shot k is part k mod N's)");
      if (const auto it = holder.find(shot.index); it != holder.end())
        throw input_error(file.string(), "holds shot " + std::to_string(shot.index) + ", which " +
                                             it->second.string() + " holds too");
      holder[shot.index] = file;
      shot.case_name = s["case"].string();
      shot.kind = s["kind"].string();
      shot.view = s["view"].string();
      shot.light = s["light"].string();
      shot.camera = s["camera"].string();
      shot.multiple = s["multiple"].number();
      shot.floor = read_metrics(s["floor"]);
      shot.flux_sigma = s["flux_sigma"].number();
      shot.truth = read_part_image(dir, s["truth"], size, 3);
      const Image mask = read_part_image(dir, s["mask"], size, 1);
      shot.mask.reserve(mask.pixels.size());
      for (const float v : mask.pixels) shot.mask.push_back(v != 0.0f ? 1 : 0);
      for (const JsonNode& f : s["filters"].items()) {
        LodShot::FilterResult fr;
        fr.filter = f["filter"].string();
        fr.metrics = read_metrics(f["metrics"]);
        fr.image = read_part_image(dir, f["image"], size, 3);
        shot.filters.push_back(std::move(fr));
      }
      r.shots.push_back(std::move(shot));
    }
  }
  // Every part of the first file's run, and every shot of the comparison.
  const int parts = files.begin()->first.first;
  for (int i = 0; i < parts; ++i)
    if (!files.count({parts, i}))
      throw input_error(
          (dir / lod_part_name(i, parts)).string(),
          "missing: part " + std::to_string(i) + " of " + std::to_string(parts) + " was not written");
  const JsonDocument first = JsonDocument::read(first_file);
  const JsonNode rn = first.root()["run"];
  r.total_shots = rn["total_shots"].integer(0, 1 << 30);
  for (int k = 0; k < r.total_shots; ++k)
    if (!holder.count(k))
      throw input_error((dir / lod_part_name(k % parts, parts)).string(),
                        "lacks shot " + std::to_string(k) + ", which part k mod N must render");
  if (int(holder.size()) != r.total_shots)
    throw input_error(holder.rbegin()->second.string(),
                      "holds shot " + std::to_string(holder.rbegin()->first) + ", beyond the run's " +
                          std::to_string(r.total_shots));
  std::sort(r.shots.begin(), r.shots.end(),
            [](const LodShot& a, const LodShot& b) { return a.index < b.index; });

  LodOptions& o = r.options;
  o.parts = parts;
  o.spp = rn["spp"].integer(1, 1 << 30);
  o.seed = rn["seeds"][0].unsigned_integer();
  o.second_seed = rn["seeds"][1].unsigned_integer();
  o.filter_seed = rn["seeds"][2].unsigned_integer();
  o.footprint_scale = float(rn["footprint_scale"].number());
  o.filters = strings(rn["filters_asked"]);
  o.cases = strings(rn["cases"]);
  o.lights = strings(rn["lights"]);
  o.views = strings(rn["views"]);
  r.filters = strings(rn["filters"]);
  r.unavailable = strings(rn["unavailable"]);
  run.manifest = rn["manifest"].string();
  run.size_name = rn["size_name"].string();
  run.command = rn["command"].string();
  return r;
}

}  // namespace svbrdf
