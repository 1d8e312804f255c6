#include "textures/color.h"

#include <OpenColorIO/OpenColorIO.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <mutex>
#include <optional>
#include <sstream>
#include <vector>

#include "base/error.h"
#include "textures/code_tables.h"
#include "textures/color_spaces.h"

namespace OCIO = OCIO_NAMESPACE;

namespace svbrdf {

// Defined in the generated unit that embeds textures/ocio/config.ocio (textures/CMakeLists.txt).
extern const char* const kBuiltinOcioConfig;

std::string_view builtin_ocio_config_text() { return kBuiltinOcioConfig; }

namespace {

// OCIO's default CPU optimization approximates pow with a fast SSE polynomial (relative error
// ~1e-5); the project checks the sRGB decode against IEC 61966-2-1 to 1e-6, so keep exact pow.
constexpr auto kOptimization =
    static_cast<OCIO::OptimizationFlags>(OCIO::OPTIMIZATION_DEFAULT & ~OCIO::OPTIMIZATION_FAST_LOG_EXP_POW);

OCIO::ConstCPUProcessorRcPtr cpu_processor(const OCIO::ConstConfigRcPtr& config, const char* from, const char* to) {
  return config->getProcessor(from, to)->getOptimizedCPUProcessor(OCIO::BIT_DEPTH_F32, OCIO::BIT_DEPTH_F32,
                                                                  kOptimization);
}

}  // namespace

struct ColorConfig::Impl {
  std::string source;
  OCIO::ConstConfigRcPtr config;
  ResolvedColorSpaces spaces;
  std::string display, view;
  OCIO::ConstCPUProcessorRcPtr srgb_to_linear, linear_to_srgb;
  // The sRGB decode's tables, made at the first decode (code_tables.h).
  mutable std::once_flag srgb_tables_made;
  mutable std::optional<CodeTables> srgb_tables;
  const CodeTables& srgb_to_linear_tables() const {
    std::call_once(srgb_tables_made, [&] { srgb_tables.emplace(srgb_to_linear); });
    return *srgb_tables;
  }

  Impl(std::string src, OCIO::ConstConfigRcPtr cfg) : source(std::move(src)), config(std::move(cfg)) {
    config->validate();
    spaces = resolve_color_spaces(config, source);
    display = config->getDefaultDisplay();
    view = config->getDefaultView(display.c_str());
    srgb_to_linear = cpu_processor(config, spaces.srgb_texture.c_str(), spaces.linear.c_str());
    linear_to_srgb = cpu_processor(config, spaces.linear.c_str(), spaces.srgb_texture.c_str());
  }
};

namespace {

std::shared_ptr<const ColorConfig::Impl> make_impl(const std::string& source, const OCIO::ConstConfigRcPtr& config) {
  return std::make_shared<const ColorConfig::Impl>(source, config);
}

// Gray and gray+alpha images become RGB(A): OCIO transforms need three color channels, and glTF
// reads a gray color texture as R = G = B.
void expand_gray(Image& image) {
  if (image.channels >= 3) return;
  const int in_c = image.channels, out_c = in_c == 1 ? 3 : 4;
  Image rgb(image.width, image.height, out_c);
  const std::size_t n = std::size_t(image.width) * image.height;
  for (std::size_t p = 0; p < n; ++p) {
    const float g = image.pixels[p * in_c];
    for (int c = 0; c < 3; ++c) rgb.pixels[p * out_c + c] = g;
    if (out_c == 4) rgb.pixels[p * out_c + 3] = image.pixels[p * in_c + 1];
  }
  image = std::move(rgb);
}

// Applies a CPU processor to channels 0..2 of every pixel, in parallel over bands of rows (the
// processor is immutable and thread-safe).
void apply_processor(const OCIO::ConstCPUProcessorRcPtr& cpu, Image& image) {
  expand_gray(image);
  if (image.width == 0 || image.height == 0) return;
  const int c = image.channels;
  const std::ptrdiff_t pixel_bytes = std::ptrdiff_t(sizeof(float)) * c;
  const std::ptrdiff_t row_bytes = pixel_bytes * image.width;
  const OCIO::ChannelOrdering order = c == 4 ? OCIO::CHANNEL_ORDERING_RGBA : OCIO::CHANNEL_ORDERING_RGB;
  const int rows_per_task = std::max(1, (1 << 16) / std::max(1, image.width));
  tbb::parallel_for(tbb::blocked_range<int>(0, image.height, rows_per_task), [&](const tbb::blocked_range<int>& r) {
    float* first = image.pixels.data() + std::size_t(r.begin()) * image.width * c;
    OCIO::PackedImageDesc desc(first, image.width, r.end() - r.begin(), order, OCIO::BIT_DEPTH_F32,
                               sizeof(float), pixel_bytes, row_bytes);
    cpu->apply(desc);
  });
}

// The same for packed RGB texels, in parallel over runs of them.
static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "packed RGB texels");
void apply_processor(const OCIO::ConstCPUProcessorRcPtr& cpu, std::span<glm::vec3> rgb) {
  constexpr std::size_t kRun = std::size_t(1) << 16;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rgb.size(), kRun), [&](const tbb::blocked_range<std::size_t>& r) {
    OCIO::PackedImageDesc desc(&rgb[r.begin()].x, long(r.size()), 1, OCIO::CHANNEL_ORDERING_RGB, OCIO::BIT_DEPTH_F32,
                               sizeof(float), 3 * sizeof(float), std::ptrdiff_t(3 * sizeof(float) * r.size()));
    cpu->apply(desc);
  });
}

// Channels 0..2 of every pixel through the transform's code tables, in parallel over runs of pixels
// (the tables are immutable); through the processor itself where there are none.
void apply_tables(const OCIO::ConstCPUProcessorRcPtr& cpu, const CodeTables& tables, Image& image) {
  if (tables.empty()) return apply_processor(cpu, image);
  expand_gray(image);
  const std::size_t c = std::size_t(image.channels), n = std::size_t(image.width) * image.height;
  constexpr std::size_t kRun = std::size_t(1) << 16;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kRun), [&](const tbb::blocked_range<std::size_t>& r) {
    tables.apply(image.pixels.data() + r.begin() * c, r.size(), c);
  });
}
void apply_tables(const OCIO::ConstCPUProcessorRcPtr& cpu, const CodeTables& tables, std::span<glm::vec3> rgb) {
  if (tables.empty()) return apply_processor(cpu, rgb);
  constexpr std::size_t kRun = std::size_t(1) << 16;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rgb.size(), kRun), [&](const tbb::blocked_range<std::size_t>& r) {
    tables.apply(&rgb[r.begin()].x, r.size(), 3);
  });
}

float apply_one(const OCIO::ConstCPUProcessorRcPtr& cpu, float v) {
  float rgb[3] = {v, v, v};
  cpu->applyRGB(rgb);
  return rgb[0];
}

}  // namespace

const ColorConfig& ColorConfig::builtin() {
  // Immutable once built; C++ guarantees one thread-safe initialization.
  static const ColorConfig config = [] {
    try {
      std::istringstream text{std::string(kBuiltinOcioConfig)};
      return ColorConfig(make_impl("built-in OCIO config", OCIO::Config::CreateFromStream(text)));
    } catch (const OCIO::Exception& e) {
      throw Error(std::string("the built-in OCIO config is invalid: ") + e.what(), Error::Kind::internal);
    }
  }();
  return config;
}

ColorConfig ColorConfig::from_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw input_error(path.string(), "no such OCIO config file");
  try {
    return ColorConfig(make_impl(path.string(), OCIO::Config::CreateFromFile(path.c_str())));
  } catch (const OCIO::Exception& e) {
    throw input_error(path.string(), std::string("invalid OCIO config: ") + e.what());
  }
}

ColorConfig ColorConfig::resolve(const std::optional<std::filesystem::path>& explicit_path) {
  if (explicit_path) return from_file(*explicit_path);
  if (const char* env = std::getenv("OCIO"); env && *env) {
    try {
      return from_file(env);
    } catch (const Error& e) {
      throw input_error("$OCIO", e.what());
    }
  }
  return builtin();
}

const std::string& ColorConfig::source() const { return impl_->source; }
const std::string& ColorConfig::linear_space() const { return impl_->spaces.linear; }
const std::string& ColorConfig::srgb_texture_space() const { return impl_->spaces.srgb_texture; }
const std::string& ColorConfig::data_space() const { return impl_->spaces.data; }
const std::string& ColorConfig::default_display() const { return impl_->display; }
const std::string& ColorConfig::default_view() const { return impl_->view; }

std::string ColorConfig::identity() const {
  std::ostringstream text;
  impl_->config->serialize(text);
  text << "\nlinear: " << impl_->spaces.linear << "\nsrgb texture: " << impl_->spaces.srgb_texture
       << "\nsrgb to linear: " << impl_->srgb_to_linear->getCacheID() << '\n';
  return text.str();
}

void ColorConfig::srgb_texture_to_linear(Image& image) const {
  apply_tables(impl_->srgb_to_linear, impl_->srgb_to_linear_tables(), image);
}
void ColorConfig::srgb_texture_to_linear(std::span<glm::vec3> rgb) const {
  apply_tables(impl_->srgb_to_linear, impl_->srgb_to_linear_tables(), rgb);
}
const CodeTables* ColorConfig::srgb_texture_to_linear_codes() const {
  const CodeTables& tables = impl_->srgb_to_linear_tables();
  return tables.empty() ? nullptr : &tables;
}
void ColorConfig::linear_to_srgb_texture(Image& image) const { apply_processor(impl_->linear_to_srgb, image); }

float ColorConfig::srgb_texture_to_linear(float v) const { return apply_one(impl_->srgb_to_linear, v); }
float ColorConfig::linear_to_srgb_texture(float v) const { return apply_one(impl_->linear_to_srgb, v); }

namespace {

// "a, b, c" for a message.
std::string listed(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "\"" : ", \"") + n + "\"";
  return out;
}

std::vector<std::string> displays_of(const OCIO::ConstConfigRcPtr& config) {
  std::vector<std::string> names;
  for (int i = 0; i < config->getNumDisplaysAll(); ++i) names.emplace_back(config->getDisplayAll(i));
  return names;
}

// A display's views, its own and the shared ones it lists.
std::vector<std::string> views_of(const OCIO::ConstConfigRcPtr& config, const std::string& display) {
  std::vector<std::string> names;
  for (const OCIO::ViewType type : {OCIO::VIEW_DISPLAY_DEFINED, OCIO::VIEW_SHARED})
    for (int i = 0; i < config->getNumViews(type, display.c_str()); ++i)
      names.emplace_back(config->getView(type, display.c_str(), i));
  return names;
}

// "the built-in OCIO config" or "the OCIO config FILE", for messages.
std::string config_name(const std::string& source) {
  return source.starts_with("built-in") ? "the " + source : "the OCIO config " + source;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace

std::pair<std::string, std::string> ColorConfig::display_view(const std::string& display, const std::string& view) const {
  const OCIO::ConstConfigRcPtr& config = impl_->config;
  const std::string d = display.empty() ? impl_->display : display;
  const std::vector<std::string> displays = displays_of(config);
  if (!contains(displays, d))
    throw input_error("--display " + d, "not a display of " + config_name(impl_->source) + " (its displays: " +
                                            listed(displays) + ")");
  if (view.empty()) {
    const char* default_view = config->getDefaultView(d.c_str());
    return {d, default_view ? default_view : ""};
  }
  const std::vector<std::string> views = views_of(config, d);
  if (!contains(views, view))
    throw input_error("--view " + view, "not a view of display \"" + d + "\" in " + config_name(impl_->source) +
                                            " (its views: " + listed(views) + ")");
  return {d, view};
}

void ColorConfig::linear_to_display(Image& image, const std::string& display, const std::string& view) const {
  const auto [d, v] = display_view(display, view);
  try {
    const auto cpu = impl_->config
                         ->getProcessor(impl_->spaces.linear.c_str(), d.c_str(), v.c_str(), OCIO::TRANSFORM_DIR_FORWARD)
                         ->getOptimizedCPUProcessor(OCIO::BIT_DEPTH_F32, OCIO::BIT_DEPTH_F32, kOptimization);
    apply_processor(cpu, image);
  } catch (const OCIO::Exception& e) {
    throw input_error(impl_->source, "display \"" + d + "\", view \"" + v + "\": " + e.what());
  }
}

std::string ColorConfig::file_color_space(const std::filesystem::path& file) const {
  const OCIO::ConstConfigRcPtr& config = impl_->config;
  // OCIO 1 configs have no file rules (OCIO emulates them by the default role: no rule of the config's own).
  if (config->getMajorVersion() < 2 || config->filepathOnlyMatchesDefaultRule(file.c_str())) return {};
  // A rule may name a role or an alias: the space's own name.
  const auto cs = config->getColorSpace(config->getColorSpaceFromFilepath(file.c_str()));
  return cs ? cs->getName() : std::string();
}

void ColorConfig::file_to_linear(Image& image, const std::filesystem::path& file) const {
  const std::string space = file_color_space(file);
  if (space.empty() || space == impl_->spaces.linear) return;
  if (const auto cs = impl_->config->getColorSpace(space.c_str()); cs && cs->isData()) return;
  convert(image, space, impl_->spaces.linear);
}

void ColorConfig::convert(Image& image, const std::string& from, const std::string& to) const {
  try {
    apply_processor(cpu_processor(impl_->config, from.c_str(), to.c_str()), image);
  } catch (const OCIO::Exception& e) {
    throw input_error(impl_->source, "\"" + from + "\" → \"" + to + "\": " + e.what());
  }
}

}  // namespace svbrdf
