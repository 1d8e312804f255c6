// svbrdf-brdf: a workbench for one BRDF model (../shared/spec/brdf-models.md, last section).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "appearance/albedo.h"
#include "apps/direction_text.h"
#include "apps/fresnel_plot.h"
#include "apps/polar_plot.h"
#include "appearance/registry.h"
#include "appearance/rng.h"
#include "base/cli_checks.h"
#include "base/error.h"
#include "apps/run_program.h"
#include "base/interrupt.h"
#include "base/message_line.h"
#include "base/math.h"

namespace {

using namespace svbrdf;

struct ModelArgs {
  std::string name;
  std::vector<std::string> params, impulses;
  std::unique_ptr<Bsdf> build() const { return make_model(name, params, impulses); }
};

void add_model_options(CLI::App* sub, ModelArgs& m) {
  sub->add_option("model", m.name, "model name (see --help of the main program)")->required();
  sub->add_option("--param", m.params, "a model parameter k=v (repeatable; RGB as r,g,b)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  sub->add_option("--impulse", m.impulses, "add an impulse model NAME[:SCALE], e.g. mirror:0.4 (repeatable)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

// eval / pdf: one output line per input line of six numbers.
void run_lines(const Bsdf& bsdf, bool density) {
  std::string line;
  long number = 0;
  glm::vec3 wi, wo;
  while (std::getline(std::cin, line)) {
    ++number;
    if (!parse_direction_line(line, number, wi, wo)) continue;
    if (density) {
      std::printf("%.9g\n", static_cast<double>(bsdf.pdf(wi, wo)));
    } else {
      const Rgb f = bsdf.eval(wi, wo);
      std::printf("%.9g %.9g %.9g\n", static_cast<double>(f.x), static_cast<double>(f.y), static_cast<double>(f.z));
    }
  }
  if (std::cin.bad()) throw Error("stdin: read error", Error::Kind::internal);
}

const char* kind_name(SampleKind k) {
  switch (k) {
    case SampleKind::finite: return "finite";
    case SampleKind::impulse: return "impulse";
    case SampleKind::absorbed: break;
  }
  return "absorbed";
}

void print_sample(const BsdfSample& s) {
  std::printf("%.9g %.9g %.9g %.9g %.9g %.9g %.9g %s\n", static_cast<double>(s.wi.x), static_cast<double>(s.wi.y),
              static_cast<double>(s.wi.z), static_cast<double>(s.pdf), static_cast<double>(s.weight.x),
              static_cast<double>(s.weight.y), static_cast<double>(s.weight.z), kind_name(s.kind));
}

// sample --stdin: one sample per stdin line "wo.x wo.y wo.z u1 u2 u3", so that a caller samples for
// the directions and at the numbers it chose (a stratification, another program's draws).
void sample_lines(const Bsdf& bsdf) {
  std::string line;
  long number = 0;
  glm::vec3 wo, u;
  while (std::getline(std::cin, line)) {
    ++number;
    if (parse_sample_line(line, number, wo, u)) print_sample(bsdf.sample(wo, u));
  }
  if (std::cin.bad()) throw Error("stdin: read error", Error::Kind::internal);
}

void check_angle(double deg, double hi, const std::string& option) {
  if (!(deg >= 0 && deg <= hi))
    throw input_error(option, "angle " + std::to_string(deg) + " is out of range [0, " + std::to_string(hi) + "]");
}

// Before the work: the plot is SVG or PNG, by the file's extension.
void check_plot_file(const std::string& out) {
  const auto ext = std::filesystem::path(out).extension().string();
  if (ext != ".svg" && ext != ".png") throw input_error("--out " + out, "a plot is written as .svg or .png");
}

}  // namespace

int main(int argc, char** argv) {
  // A Ctrl-C or SIGTERM: one line and exit 130 / 143, no temporary left (base/interrupt.h).
  svbrdf::install_interrupt_handlers("svbrdf-brdf");
  CLI::App app{"svbrdf-brdf: evaluate, sample and plot one BRDF model of CGPP chapter 27"};
  app.footer("Models and parameters:\n" + models_help());
  app.require_subcommand(1);

  ModelArgs m;
  CLI::App* eval = app.add_subcommand("eval", "f(wi, wo) per stdin line 'wi.x wi.y wi.z wo.x wo.y wo.z' -> 'r g b'");
  add_model_options(eval, m);
  CLI::App* pdf = app.add_subcommand("pdf", "the sampling density pdf(wi, wo) per stdin line");
  add_model_options(pdf, m);

  CLI::App* sample = app.add_subcommand("sample", "N samples 'wi.x wi.y wi.z pdf w.r w.g w.b kind' for one wo");
  add_model_options(sample, m);
  std::string wo_text;
  long long count = 1;
  std::uint64_t seed = 0;
  sample->add_option("--wo", wo_text, "the outgoing direction x,y,z (unit); required unless --stdin");
  sample->add_option("--count", count, "number of samples, 0 to 10^9")->check(cli::whole_in(0, 1000000000LL));
  sample->add_option("--seed", seed, "random seed")->check(cli::unsigned_whole);
  bool u_from_stdin = false;
  sample->add_flag("--stdin", u_from_stdin,
                   "instead of --count samples for --wo drawn from --seed: one sample per stdin line "
                   "'wo.x wo.y wo.z u1 u2 u3' (u in [0, 1))")
      ->excludes("--wo")
      ->excludes("--count")
      ->excludes("--seed");

  CLI::App* albedo = app.add_subcommand("albedo", "directional albedo of the finite part and the impulse total");
  add_model_options(albedo, m);
  double theta_o = 0;
  int strata = 512;
  albedo->add_option("--theta-o", theta_o, "angle of wo from the normal, degrees [0, 90]")->required()->check(cli::number_in(0, 90));
  albedo->add_option("--strata", strata, "estimate with strata^2 stratified samples, 1 to 4096")->check(cli::whole_in(1, 4096));

  CLI::App* plot = app.add_subcommand("plot", "polar plot (SVG or PNG): f black, sampling density blue, impulses arrows");
  add_model_options(plot, m);
  double theta_i = 30;
  std::string out;
  plot->add_option("--theta-i", theta_i, "angle of the light from the normal, degrees [0, 180]")->required()->check(cli::number_in(0, 180));
  plot->add_option("--out", out, "output file: .svg or .png")->required();

  CLI::App* fresnel = app.add_subcommand("fresnel", "exact Fresnel against Schlick over the angle of incidence (SVG or PNG)");
  std::string ior_text, eta_text, k_text;
  fresnel->add_option("--ior", ior_text, "relative index of a dielectric");
  fresnel->add_option("--eta", eta_text, "conductor: real part of the index (r,g,b or one number)");
  fresnel->add_option("--k", k_text, "conductor: imaginary part of the index (r,g,b or one number)");
  fresnel->add_option("--out", out, "output file: .svg or .png")->required();

  return run_program("svbrdf-brdf", app, argc, argv, [&] {
    if (eval->parsed() || pdf->parsed()) {
      const auto bsdf = m.build();
      run_lines(*bsdf, pdf->parsed());
    } else if (sample->parsed()) {
      if (u_from_stdin) {
        sample_lines(*m.build());
        return 0;
      }
      if (wo_text.empty()) throw input_error("sample", "--wo is required (or --stdin)");
      const glm::vec3 wo = parse_direction(wo_text, "--wo");
      const auto bsdf = m.build();
      Rng rng(mix64(seed), 0x5eed);
      for (long long i = 0; i < count; ++i) {
        const float ux = rng.next_float(), uy = rng.next_float(), uz = rng.next_float();
        print_sample(bsdf->sample(wo, {ux, uy, uz}));
      }
    } else if (albedo->parsed()) {
      check_angle(theta_o, 90, "--theta-o");
      const auto bsdf = m.build();
      const double t = radians_of(theta_o);
      const glm::vec3 wo(static_cast<float>(std::sin(t)), 0.0f, static_cast<float>(std::cos(t)));
      const Rgb a = directional_albedo(*bsdf, wo, strata), imp = impulse_total(*bsdf, wo);
      std::printf("finite %.9g %.9g %.9g\nimpulse %.9g %.9g %.9g\n", static_cast<double>(a.x), static_cast<double>(a.y),
                  static_cast<double>(a.z), static_cast<double>(imp.x), static_cast<double>(imp.y),
                  static_cast<double>(imp.z));
    } else if (plot->parsed()) {
      check_angle(theta_i, 180, "--theta-i");
      check_plot_file(out);
      const auto bsdf = m.build();
      std::string title = m.name;
      for (const std::string& p : m.params) title += " " + p;
      for (const std::string& p : m.impulses) title += " +" + p;
      polar_plot(polar_plot_data(*bsdf, static_cast<float>(theta_i)), title).write(out);
    } else if (fresnel->parsed()) {
      check_plot_file(out);
      FresnelCurves c;
      if (!ior_text.empty()) {
        if (!eta_text.empty() || !k_text.empty()) throw input_error("fresnel", "give --ior, or --eta and --k, not both");
        const float ior = parse_finite_number(ior_text, "--ior");
        if (!(ior > 0)) throw input_error("--ior", "must be positive");
        c = fresnel_curves_dielectric(ior);
      } else {
        if (eta_text.empty() || k_text.empty()) throw input_error("fresnel", "give --ior, or both --eta and --k");
        const Rgb eta = parse_rgb(eta_text, "--eta"), k = parse_rgb(k_text, "--k");
        if (!(glm::all(glm::greaterThan(eta, Rgb(0))) && glm::all(glm::greaterThanEqual(k, Rgb(0)))))
          throw input_error("fresnel", "--eta must be positive and --k non-negative");
        c = fresnel_curves_conductor(eta, k);
      }
      fresnel_plot(c).write(out);
      for (int ch = 0; ch < c.channels; ++ch)
        std::printf("max |exact - schlick| %.6g at %.4g deg\n", static_cast<double>(c.max_difference[static_cast<std::size_t>(ch)]),
                    static_cast<double>(c.max_at_deg[static_cast<std::size_t>(ch)]));
    }
    return 0;
  });
}
