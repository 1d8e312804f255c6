#include "mip/texture_filter.h"

namespace svbrdf {

namespace {
constexpr TextureFilter kFilters[] = {TextureFilter::level0, TextureFilter::param, TextureFilter::toksvig,
                                      TextureFilter::vmf, TextureFilter::brdf};
}  // namespace

std::string_view filter_name(TextureFilter f) {
  switch (f) {
    case TextureFilter::level0:
      return "level0";
    case TextureFilter::param:
      return "param";
    case TextureFilter::toksvig:
      return "toksvig";
    case TextureFilter::vmf:
      return "vmf";
    case TextureFilter::brdf:
      return "brdf";
  }
  return "?";
}

std::optional<TextureFilter> parse_filter(std::string_view name) {
  for (TextureFilter f : kFilters)
    if (filter_name(f) == name) return f;
  return std::nullopt;
}

std::vector<std::string> filter_names() {
  std::vector<std::string> names;
  for (TextureFilter f : kFilters) names.emplace_back(filter_name(f));
  return names;
}

}  // namespace svbrdf
