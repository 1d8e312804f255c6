#include "lod/report.h"

#include <algorithm>
#include <cmath>
#include <span>
#include <map>

#include <tbb/parallel_for.h>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/json.h"
#include "base/markup_escape.h"
#include "render/output.h"
#include "render/renderer.h"
#include "textures/image.h"

namespace svbrdf {

namespace fs = std::filesystem;

namespace {

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string sig(double v) { return fmt("%.3g", v); }

const char* filter_color(const std::string& f) {
  if (f == "param") return "#d62728";
  if (f == "toksvig") return "#ff7f0e";
  if (f == "vmf") return "#9467bd";
  if (f == "brdf") return "#1f77b4";
  return "#2ca02c";
}

// A scene of the report: the shots of one case, view and light, by increasing distance.
struct ReportScene {
  std::string case_name, view, light, id;
  std::vector<const LodShot*> shots;
};

std::vector<ReportScene> group(const LodResults& r) {
  std::vector<ReportScene> scenes;
  for (const LodShot& s : r.shots) {
    auto it = std::find_if(scenes.begin(), scenes.end(), [&](const ReportScene& g) {
      return g.case_name == s.case_name && g.view == s.view && g.light == s.light;
    });
    if (it == scenes.end()) {
      scenes.push_back({s.case_name, s.view, s.light, s.case_name + "_" + s.view + "_" + s.light, {}});
      it = scenes.end() - 1;
    }
    it->shots.push_back(&s);
  }
  for (ReportScene& g : scenes)
    std::sort(g.shots.begin(), g.shots.end(), [](const LodShot* a, const LodShot* b) { return a->multiple < b->multiple; });
  return scenes;
}

// Exposure (stops) that brings the scene's ground truths' 99.5th-percentile luminance to 0.8: one
// exposure for the whole scene, so its rows compare.
float scene_exposure(const ReportScene& g) {
  std::vector<double> lum;
  for (const LodShot* s : g.shots)
    for (int y = 0; y < s->truth.height; ++y)
      for (int x = 0; x < s->truth.width; ++x) lum.push_back(luminance(s->truth, x, y));
  if (lum.empty()) return 0.0f;
  const std::size_t k = std::min(lum.size() - 1, std::size_t(0.995 * double(lum.size())));
  std::nth_element(lum.begin(), lum.begin() + std::ptrdiff_t(k), lum.end());
  const double p = lum[k];
  return p > 0 ? float(std::log2(0.8 / p)) : 0.0f;
}

void write_png(const fs::path& path, const Image& display) { write_image(path, display, PixelFormat::uint8); }

std::string image_name(const ReportScene& g, const LodShot& s, const std::string& what) {
  return g.id + "_" + number_text(s.multiple) + "x_" + what + ".png";
}

constexpr double kErrorScale = 0.5;  // false-color full scale: |ΔY| / mean Y

// The charts' text is 11 px sans-serif (the page's style). An x label's width, bounded above by the
// advances of DejaVu Sans, the widest of the common sans faces: 0.636 em a digit, 0.838 em for "×".
constexpr double kFontPx = 11, kLabelGap = 6;
double x_label_width(double multiple) {
  return kFontPx * (0.636 * double(number_text(multiple).size()) + 0.838);
}

}  // namespace

std::string svg_chart(const std::string& title, const std::string& y_label, const std::vector<ChartSeries>& series,
                      bool log_y, int width, int height) {
  // The plot: [left, width − right] × [top, height − bottom]; the bottom margin holds the x labels
  // and two rows of legend. The right margin grows to hold half the last x label (below).
  const double left = 58, top = 22, bottom = 64;
  double right = 10;
  const double ph = height - top - bottom;
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const ChartSeries& s : series)
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (log_y && !(s.y[i] > 0)) continue;
      if (!std::isfinite(s.y[i])) continue;
      const double x = std::log2(s.x[i]), y = log_y ? std::log10(s.y[i]) : s.y[i];
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
  std::string out;
  out += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(width) + "\" height=\"" +
         std::to_string(height) + "\" viewBox=\"0 0 " + std::to_string(width) + " " + std::to_string(height) +
         "\" role=\"img\" aria-label=\"" + markup_escape(title) + "\">";
  out += "<text x=\"" + fmt("%.0f", left) + "\" y=\"14\" class=\"ct\">" + markup_escape(title) + "</text>";
  if (x0 > x1) {
    out += "<text x=\"" + fmt("%.0f", left) + "\" y=\"60\">no data</text></svg>";
    return out;
  }
  if (log_y) {
    y0 = std::floor(y0), y1 = std::ceil(y1);
    if (y1 - y0 < 1) y1 = y0 + 1;
  } else {
    y0 = std::min(y0, 0.0), y1 = std::max(y1, 0.0);
    const double pad = 0.1 * std::max(y1 - y0, 1e-6);
    y0 -= pad, y1 += pad;
  }
  if (x1 - x0 < 1e-9) x0 -= 1, x1 += 1;
  // x labels k× at powers of two, every `stride` of them (even, counted back from the last even power,
  // so the farthest distance is labelled) where their widths need it: 1× to 16384× in a 320-pixel
  // chart would otherwise overlap from 256× on.
  const int e_first = int(std::ceil(x0 - 1e-9)), e_last = int(std::floor(x1 + 1e-9));
  const int e_anchor = e_last - ((e_last % 2) + 2) % 2;
  double widest = 0;
  for (int e = e_first; e <= e_last; ++e) widest = std::max(widest, x_label_width(std::exp2(e)));
  right = std::max(right, 0.5 * x_label_width(std::exp2(e_anchor)) + 2);
  const double pw = width - left - right;
  int stride = 2;
  while (stride * pw / (x1 - x0) < widest + kLabelGap && stride < 64) stride += 2;
  const auto X = [&](double x) { return left + (std::log2(x) - x0) / (x1 - x0) * pw; };
  const auto Y = [&](double y) { return top + (1 - ((log_y ? std::log10(y) : y) - y0) / (y1 - y0)) * ph; };
  out += "<rect x=\"" + fmt("%.1f", left) + "\" y=\"" + fmt("%.1f", top) + "\" width=\"" + fmt("%.1f", pw) +
         "\" height=\"" + fmt("%.1f", ph) + "\" class=\"plot\"/>";
  // x ticks at every power of two present, labelled k×.
  for (int e = e_first; e <= e_last; ++e) {
    const double x = left + (e - x0) / (x1 - x0) * pw;
    out += "<line x1=\"" + fmt("%.1f", x) + "\" y1=\"" + fmt("%.1f", top + ph) + "\" x2=\"" + fmt("%.1f", x) + "\" y2=\"" +
           fmt("%.1f", top + ph + 4) + "\" class=\"ax\"/>";
    if ((((e_anchor - e) % stride) + stride) % stride == 0)
      out += "<text x=\"" + fmt("%.1f", x) + "\" y=\"" + fmt("%.1f", top + ph + 15) + "\" class=\"tx\">" +
             number_text(std::exp2(e)) + "×</text>";
  }
  // y ticks: decades, or five linear steps.
  const auto ytick = [&](double v, const std::string& label) {
    const double y = top + (1 - (v - y0) / (y1 - y0)) * ph;
    out += "<line x1=\"" + fmt("%.1f", left) + "\" y1=\"" + fmt("%.1f", y) + "\" x2=\"" + fmt("%.1f", left + pw) + "\" y2=\"" +
           fmt("%.1f", y) + "\" class=\"grid\"/>";
    out += "<text x=\"" + fmt("%.1f", left - 4) + "\" y=\"" + fmt("%.1f", y + 4) + "\" class=\"ty\">" + label + "</text>";
  };
  if (log_y) {
    for (int e = int(y0); e <= int(y1); ++e) ytick(e, "1e" + std::to_string(e));
  } else {
    // Ticks at a "nice" step (1, 2 or 5 × 10^k) giving about five of them.
    const double raw = (y1 - y0) / 5;
    const double mag = std::pow(10.0, std::floor(std::log10(raw)));
    const double step = raw / mag < 1.5 ? mag : raw / mag < 3.5 ? 2 * mag : raw / mag < 7.5 ? 5 * mag : 10 * mag;
    for (double v = std::ceil(y0 / step) * step; v <= y1 + 1e-9 * step; v += step) ytick(v, fmt("%.3g", std::abs(v) < 1e-9 * step ? 0.0 : v));
    if (y0 < 0 && y1 > 0) {
      const double y = top + (1 - (0 - y0) / (y1 - y0)) * ph;
      out += "<line x1=\"" + fmt("%.1f", left) + "\" y1=\"" + fmt("%.1f", y) + "\" x2=\"" + fmt("%.1f", left + pw) +
             "\" y2=\"" + fmt("%.1f", y) + "\" class=\"zero\"/>";
    }
  }
  out += "<text x=\"12\" y=\"" + fmt("%.1f", top + ph / 2) + "\" class=\"yl\" transform=\"rotate(-90 12 " +
         fmt("%.1f", top + ph / 2) + ")\">" + markup_escape(y_label) + "</text>";
  out += "<text x=\"" + fmt("%.1f", left + pw / 2) + "\" y=\"" + fmt("%.1f", top + ph + 28) +
         "\" class=\"tx\">distance (multiples of d₁)</text>";
  // Series and legend (wrapping onto a second row).
  double lx = left, ly = top + ph + 42;
  for (const ChartSeries& s : series) {
    std::string points;
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if ((log_y && !(s.y[i] > 0)) || !std::isfinite(s.y[i])) continue;
      points += fmt("%.1f", X(s.x[i])) + "," + fmt("%.1f", Y(s.y[i])) + " ";
      out += "<circle cx=\"" + fmt("%.1f", X(s.x[i])) + "\" cy=\"" + fmt("%.1f", Y(s.y[i])) + "\" r=\"2.5\" fill=\"" +
             s.color + "\"><title>" + markup_escape(s.name) + ": " + sig(s.y[i]) + " at " + number_text(s.x[i]) +
             "×</title></circle>";
    }
    out += "<polyline points=\"" + points + "\" fill=\"none\" stroke=\"" + s.color + "\" stroke-width=\"1.5\"" +
           (s.dashed ? " stroke-dasharray=\"4 3\"" : "") + "/>";
    const double item = 24 + 6.5 * double(s.name.size());
    if (lx + item > width && lx > left) lx = left, ly += 14;
    out += "<line x1=\"" + fmt("%.1f", lx) + "\" y1=\"" + fmt("%.1f", ly - 4) + "\" x2=\"" + fmt("%.1f", lx + 14) + "\" y2=\"" +
           fmt("%.1f", ly - 4) + "\" stroke=\"" + s.color + "\" stroke-width=\"2\"" +
           (s.dashed ? " stroke-dasharray=\"4 3\"" : "") + "/>";
    out += "<text x=\"" + fmt("%.1f", lx + 17) + "\" y=\"" + fmt("%.1f", ly) + "\" class=\"lg\">" + markup_escape(s.name) + "</text>";
    lx += item;
  }
  out += "</svg>";
  return out;
}

fs::path write_lod_report(const LodResults& r, const LodManifest& m, const fs::path& dir, const LodReportInfo& info,
                          const ColorConfig& color) {
  std::error_code ec;
  fs::create_directories(dir / "img", ec);
  if (ec) throw input_error(dir.string(), "cannot create the report directory: " + ec.message());
  const std::vector<ReportScene> scenes = group(r);

  // The images: display-referred PNGs, one exposure per scene; error images in false color.
  struct Job {
    fs::path path;
    const Image* image;
    const LodShot* shot;
    float exposure;
    bool error;
  };
  std::vector<Job> jobs;
  for (const ReportScene& g : scenes) {
    const float ev = scene_exposure(g);
    for (const LodShot* s : g.shots) {
      if (s->truth.pixels.empty()) continue;
      jobs.push_back({dir / "img" / image_name(g, *s, "truth"), &s->truth, s, ev, false});
      for (const auto& f : s->filters) {
        jobs.push_back({dir / "img" / image_name(g, *s, f.filter), &f.image, s, ev, false});
        jobs.push_back({dir / "img" / image_name(g, *s, "error-" + f.filter), &f.image, s, ev, true});
      }
    }
  }
  tbb::parallel_for(std::size_t(0), jobs.size(), [&](std::size_t i) {
    const Job& j = jobs[i];
    if (j.error) write_png(j.path, false_color_error(*j.image, j.shot->truth, j.shot->mask, kErrorScale));
    else write_png(j.path, to_display(*j.image, j.exposure, color));
  });

  std::string h;
  const auto add = [&h](const std::string& s) { h += s; };
  add("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n");
  add("<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n");
  add("<title>" + markup_escape(info.title) + "</title>\n<style>\n");
  add("body{font:14px/1.45 system-ui,sans-serif;margin:24px auto;max-width:1200px;padding:0 16px;color:#222}\n"
      "h1{font-size:22px}h2{font-size:17px;margin-top:36px;border-top:1px solid #ccc;padding-top:12px}\n"
      "table{border-collapse:collapse;margin:8px 0}td,th{border:1px solid #ddd;padding:2px 6px;text-align:right}\n"
      "th{background:#f4f4f4}td.l,th.l{text-align:left}\n"
      "table.strip td{padding:2px;text-align:center}table.strip img{width:96px;height:96px;image-rendering:pixelated;display:block}\n"
      ".good{background:#d9f2d9}.fair{background:#fff1cc}.bad{background:#f8d0d0}\n"
      ".charts{display:flex;flex-wrap:wrap;gap:8px}\n"
      "svg .plot{fill:#fff;stroke:#999}svg .grid{stroke:#eee}svg .zero{stroke:#999;stroke-dasharray:2 2}svg .ax{stroke:#999}\n"
      "svg text{font:11px system-ui,sans-serif;fill:#333}svg .ct{font-weight:600}svg .tx{text-anchor:middle}\n"
      "svg .ty{text-anchor:end}svg .yl{text-anchor:middle}code{background:#f4f4f4;padding:0 3px}\n"
      ".note{color:#555}\n");
  add("</style>\n</head>\n<body>\n");
  add("<h1>" + markup_escape(info.title) + "</h1>\n");

  // What was done.
  add("<p>Each material family lies on a quad seen head-on from k × d₁, where d₁ = s·H / (2·tan(φ/2)) is the distance at "
      "which one texel (side s) covers one pixel (image height H = " + std::to_string(m.image_size) + " pixels, field of "
      "view φ = " + number_text(m.yfov_deg) + "°): at k × d₁ a pixel covers k × k texels. The quad fills the "
      "frame at every distance, so every pixel is an object pixel. Glossy families are also seen in the mirror "
      "configuration of the 45° light. The tile roof (Exercise 27.11(c)) compares a flat proxy, whose normal map "
      "holds the roof's normals, against the real corrugated geometry, with one scattering event.</p>\n");
  add("<p>Renders: every image " + std::to_string(m.image_size) + "×" + std::to_string(m.image_size) + " at " +
      std::to_string(r.options.spp) + " samples per pixel, the renderer's box pixel filter. Ground truth: "
      "<code>--filter level0</code> (nearest texel at the exact uv, no MIP), seed " + std::to_string(r.options.seed) +
      "; noise floor: the same with seed " + std::to_string(r.options.second_seed) + "; filters with seed " +
      std::to_string(r.options.filter_seed) + ". Size: " + markup_escape(info.size_name) + ". " +
      fmt("%.0f", r.seconds) + " s.</p>\n");
  {
    // Which MIP levels the distances read: each camera sample filters its share of the pixel, so a
    // distance's level is not log₂ k (bench/results/mip.md, "LOD renders", the footprint scale).
    const double scale = resolve_footprint_scale(r.options.footprint_scale, r.options.spp);
    int size = 0;
    bool one_size = true;
    for (const LodCase& c : m.cases) {
      if (size != 0 && c.texture_size != size) one_size = false;
      size = c.texture_size;
    }
    const double coarsest = one_size && size > 0 ? std::floor(std::log2(double(size))) : INFINITY;
    std::string levels;
    for (std::size_t i = 0; i < m.distances.size(); ++i)
      levels += (i ? ", level " : "level ") + number_text(std::clamp(std::log2(m.distances[i] * scale), 0.0, coarsest)) +
                " at " + number_text(m.distances[i]) + "×";
    add("<p>Under the MIP filters each camera sample filters its own share of the pixel: its footprint is scaled by " +
        number_text(scale) + " (the renderer's default, 1/√spp, unless set), so at k × d₁ the lookups "
        "read MIP level log₂(k × " + number_text(scale) + "), clamped to the pyramid's levels" +
        (std::isfinite(coarsest) ? " (0 to " + number_text(coarsest) + " for the " + std::to_string(size) + "² textures)" : "") +
        ": " + levels + ".</p>\n");
  }
  if (!info.command.empty()) add("<p class=\"note\">Made by <code>" + markup_escape(info.command) + "</code>.</p>\n");
  add("<p>Metrics over the object's pixels (those whose depth is positive in the ground truth): relative MSE "
      "Σ(X−R)²/ΣR² over pixels and RGB channels; flux bias ΣX/ΣR − 1; peak ratio max Y(X) / max Y(R) (Y: luminance). "
      "The noise floor is the relative MSE between the two ground truths. False-color images show |Y(X) − Y(R)| / "
      "mean Y(R) from 0 (black) to " + number_text(kErrorScale) + " (yellow) <svg width=\"120\" height=\"10\">"
      "<defs><linearGradient id=\"cm\">");
  for (int i = 0; i <= 5; ++i) {
    float c[3];
    error_color(i / 5.0, c);
    add("<stop offset=\"" + fmt("%.1f", i / 5.0) + "\" stop-color=\"rgb(" + std::to_string(int(c[0] * 255)) + "," +
        std::to_string(int(c[1] * 255)) + "," + std::to_string(int(c[2] * 255)) + ")\"/>");
  }
  add("</linearGradient></defs><rect width=\"120\" height=\"10\" fill=\"url(#cm)\"/></svg>. Flux σ: the relative "
      "standard deviation of one ground truth's total flux, estimated from the two ground truths' per-pixel differences "
      "(a flux bias carries about √2·σ of noise). All numbers are also in <a href=\"results.json\">results.json</a>.</p>\n");
  add("<p>Filters: ");
  for (std::size_t i = 0; i < r.filters.size(); ++i) add((i ? ", " : "") + std::string("<code>") + markup_escape(r.filters[i]) + "</code>");
  if (r.filters.empty()) add("none");
  add(".");
  if (!r.unavailable.empty()) {
    add(" <strong>Not available in this renderer (not rendered):</strong> ");
    for (std::size_t i = 0; i < r.unavailable.size(); ++i) add((i ? ", " : "") + std::string("<code>") + markup_escape(r.unavailable[i]) + "</code>");
    add(".");
  }
  add("</p>\n");

  // Summary: each filter's relative MSE over the noise floor, per scene and distance.
  std::vector<double> distances;
  for (const LodShot& s : r.shots)
    if (std::find(distances.begin(), distances.end(), s.multiple) == distances.end()) distances.push_back(s.multiple);
  std::sort(distances.begin(), distances.end());
  for (const std::string& f : r.filters) {
    add("<h2 id=\"summary-" + markup_escape(f) + "\">Summary: relative MSE of <code>" + markup_escape(f) +
        "</code> over the noise floor (flux bias in brackets)</h2>\n<table>\n<tr><th class=\"l\">scene</th>");
    for (double k : distances) add("<th>" + number_text(k) + "×</th>");
    add("</tr>\n");
    for (const ReportScene& g : scenes) {
      add("<tr><td class=\"l\"><a href=\"#" + markup_escape(g.id) + "\">" + markup_escape(g.case_name + " / " + g.view + " / " + g.light) +
          "</a></td>");
      for (double k : distances) {
        const auto it = std::find_if(g.shots.begin(), g.shots.end(), [&](const LodShot* s) { return s->multiple == k; });
        const LodShot::FilterResult* fr = it == g.shots.end() ? nullptr : (*it)->find(f);
        if (!fr) {
          add("<td></td>");
          continue;
        }
        const double ratio = fr->metrics.rel_mse / std::max((*it)->floor.rel_mse, 1e-300);
        const char* cls = ratio <= 1.5 ? "good" : ratio <= 3 ? "fair" : "bad";
        add(std::string("<td class=\"") + cls + "\">" + sig(ratio) + " <small>(" + fmt("%+.1f", 100 * fr->metrics.flux_bias) +
            "%)</small></td>");
      }
      add("</tr>\n");
    }
    add("</table>\n");
  }

  // Per scene.
  for (const ReportScene& g : scenes) {
    add("<h2 id=\"" + markup_escape(g.id) + "\">" + markup_escape(g.case_name) + " — " + markup_escape(g.view) + " — " +
        markup_escape(g.light) + "</h2>\n<div class=\"charts\">\n");
    std::vector<ChartSeries> mse, flux, peak;
    ChartSeries floor{"noise floor", "#777", true, {}, {}};
    ChartSeries floor_flux{"noise floor", "#777", true, {}, {}}, floor_peak{"noise floor", "#777", true, {}, {}};
    for (const LodShot* s : g.shots) {
      floor.x.push_back(s->multiple), floor.y.push_back(s->floor.rel_mse);
      floor_flux.x.push_back(s->multiple), floor_flux.y.push_back(100 * s->floor.flux_bias);
      floor_peak.x.push_back(s->multiple), floor_peak.y.push_back(s->floor.peak_ratio);
    }
    for (const std::string& f : r.filters) {
      ChartSeries a{f, filter_color(f), false, {}, {}}, b = a, c = a;
      for (const LodShot* s : g.shots)
        if (const auto* fr = s->find(f)) {
          a.x.push_back(s->multiple), a.y.push_back(fr->metrics.rel_mse);
          b.x.push_back(s->multiple), b.y.push_back(100 * fr->metrics.flux_bias);
          c.x.push_back(s->multiple), c.y.push_back(fr->metrics.peak_ratio);
        }
      mse.push_back(a), flux.push_back(b), peak.push_back(c);
    }
    mse.push_back(floor), flux.push_back(floor_flux), peak.push_back(floor_peak);
    add(svg_chart("relative MSE", "relative MSE", mse, true) + "\n");
    add(svg_chart("flux bias", "flux bias (%)", flux, false) + "\n");
    add(svg_chart("peak ratio", "peak ratio", peak, true) + "\n</div>\n");

    if (!g.shots.empty() && !g.shots.front()->truth.pixels.empty()) {
      add("<table class=\"strip\">\n<tr><th>distance</th>");
      for (const std::string& f : r.filters) add("<th>" + markup_escape(f) + "</th>");
      add("<th>ground truth</th>");
      for (const std::string& f : r.filters) add("<th>error: " + markup_escape(f) + "</th>");
      add("</tr>\n");
      for (const LodShot* s : g.shots) {
        add("<tr><td>" + number_text(s->multiple) + "×</td>");
        const auto img = [&](const std::string& what, const std::string& alt) {
          add("<td><img src=\"img/" + markup_escape(image_name(g, *s, what)) + "\" alt=\"" + markup_escape(alt) + "\"></td>");
        };
        for (const auto& f : s->filters) img(f.filter, f.filter);
        img("truth", "ground truth");
        for (const auto& f : s->filters) img("error-" + f.filter, "error of " + f.filter);
        add("</tr>\n");
      }
      add("</table>\n");
    }

    add("<table>\n<tr><th>distance</th><th>camera</th><th>noise floor</th>");
    for (const std::string& f : r.filters)
      add("<th>" + markup_escape(f) + " rel. MSE</th><th>×floor</th><th>flux bias</th><th>peak ratio</th>");
    add("<th>floor flux</th><th>floor peak</th><th>flux σ</th></tr>\n");
    for (const LodShot* s : g.shots) {
      add("<tr><td>" + number_text(s->multiple) + "×</td><td class=\"l\">" + markup_escape(s->camera) + "</td><td>" +
          sig(s->floor.rel_mse) + "</td>");
      for (const std::string& f : r.filters) {
        const auto* fr = s->find(f);
        if (!fr) {
          add("<td></td><td></td><td></td><td></td>");
          continue;
        }
        add("<td>" + sig(fr->metrics.rel_mse) + "</td><td>" + sig(fr->metrics.rel_mse / std::max(s->floor.rel_mse, 1e-300)) +
            "</td><td>" + fmt("%+.2f%%", 100 * fr->metrics.flux_bias) + "</td><td>" + sig(fr->metrics.peak_ratio) + "</td>");
      }
      add("<td>" + fmt("%+.2f%%", 100 * s->floor.flux_bias) + "</td><td>" + sig(s->floor.peak_ratio) + "</td><td>" +
          fmt("%.2f%%", 100 * s->flux_sigma) + "</td></tr>\n");
    }
    add("</table>\n");
  }
  add("</body>\n</html>\n");

  // The numbers, machine-readable.
  {
    const auto metrics = [](const LodMetrics& mm) {
      return Json{{"rel_mse", mm.rel_mse}, {"flux_bias", mm.flux_bias}, {"peak_ratio", mm.peak_ratio}};
    };
    Json shots = Json::array();
    for (const LodShot& s : r.shots) {
      Json filters = Json::object();
      for (const auto& f : s.filters) filters[f.filter] = metrics(f.metrics);
      shots.push_back({{"case", s.case_name},
                       {"view", s.view},
                       {"light", s.light},
                       {"camera", s.camera},
                       {"multiple", s.multiple},
                       {"floor", metrics(s.floor)},
                       {"flux_sigma", s.flux_sigma},
                       {"filters", std::move(filters)}});
    }
    const Json doc = {{"spp", r.options.spp},
                      {"seeds", Json::array({r.options.seed, r.options.second_seed, r.options.filter_seed})},
                      {"footprint_scale", double(r.options.footprint_scale)},
                      {"image_size", r.image_size},
                      {"filters", r.filters},
                      {"unavailable", r.unavailable},
                      {"shots", std::move(shots)}};
    write_json_file(dir / "results.json", doc);
  }

  const fs::path index = dir / "index.html";
  write_bytes_atomically(index, std::as_bytes(std::span(h)));
  return index;
}

}  // namespace svbrdf
