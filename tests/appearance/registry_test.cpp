// The registry builds every model by name and rejects bad parameters with one clear svbrdf::Error
// (bad input) naming the model and the parameter.
#include <gtest/gtest.h>

#include "appearance/registry.h"
#include "base/error.h"
#include "test_models.h"

namespace svbrdf::testing {
namespace {

TEST(Registry, EveryModelBuildsWithItsDefaults) {
  for (const std::string& name : model_names()) {
    if (name == "measured") continue;  // needs file=
    const auto bsdf = make_model(name, {});
    ASSERT_NE(bsdf, nullptr) << name;
  }
  EXPECT_NE(make_model("measured", {"file=" + gltf_merl_path()}), nullptr);
  EXPECT_EQ(model_names().size(), 14u);
}

void expect_error(const std::string& model, const std::vector<std::string>& params, const std::string& fragment,
                  const std::vector<std::string>& impulses = {}) {
  try {
    make_model(model, params, impulses);
    ADD_FAILURE() << model << ": expected an error containing '" << fragment << "'";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), Error::Kind::bad_input) << e.what();
    EXPECT_EQ(e.exit_code(), 2);
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line: " << e.what();
  }
}

TEST(Registry, BadInputIsOneClearError) {
  expect_error("glossy", {}, "unknown model 'glossy'");
  expect_error("lambert", {"colour=0.5"}, "unknown parameter 'colour'");
  expect_error("lambert", {"albedo"}, "key=value");
  expect_error("lambert", {"albedo=nan"}, "not a finite number");
  expect_error("lambert", {"albedo=inf"}, "not a finite number");
  expect_error("lambert", {"albedo=-0.1"}, "out of range");
  expect_error("lambert", {"albedo=1.5"}, "out of range");
  expect_error("lambert", {"albedo=0.5x"}, "not a number");
  expect_error("lambert", {"albedo=0.1,0.2"}, "r,g,b");
  expect_error("lambert", {"albedo=0.1", "albedo=0.2"}, "more than once");
  expect_error("gltf", {"roughness=1.5"}, "'roughness'");
  expect_error("gltf", {"metallic=-1"}, "'metallic'");
  expect_error("microfacet", {"alpha=0"}, "'alpha'");
  expect_error("microfacet", {"alpha=-0.3"}, "'alpha'");
  expect_error("microfacet", {"distribution=phong"}, "ggx|beckmann");
  expect_error("microfacet", {"ior=1.33"}, "fresnel=dielectric");
  expect_error("microfacet", {"fresnel=conductor", "f0=0.5"}, "fresnel=schlick");
  expect_error("microfacet", {"metal_plastic=0.5", "kd=0.2"}, "metal_plastic");
  expect_error("microfacet", {"metal_plastic=2"}, "out of range");
  expect_error("microfacet", {"fresnel=conductor", "eta=0"}, "'eta'");
  expect_error("cook-torrance", {"distribution=ggx"}, "beckmann");
  expect_error("phong", {"n=20", "shininess=2"}, "not both");
  expect_error("phong", {"shininess=7"}, "out of range");
  expect_error("blinn-phong", {"s=-1"}, "out of range");
  expect_error("oren-nayar", {"sigma=-0.1"}, "out of range");
  expect_error("lafortune", {"lobe=1,2,3"}, "Cx,Cy,Cz,n");
  expect_error("lafortune", {"lobe=-1,-1,1,-5"}, "exponent");
  expect_error("lafortune", {"lobe=-1,-1,1,5,1,-1,1"}, "non-negative");
  expect_error("dielectric", {"ior=0"}, "'ior'");
  expect_error("measured", {}, "required");
  expect_error("measured", {"file=/nonexistent/table.binary"}, "/nonexistent/table.binary");
  expect_error("lambert", {}, "unknown impulse model", {"glass:0.3"});
  expect_error("lambert", {}, "out of range", {"mirror:1.5"});
  expect_error("lambert", {}, "not a number", {"mirror:x"});
  expect_error("lambert", {}, "at most one dielectric", {"dielectric", "dielectric:0.5"});
}

}  // namespace
}  // namespace svbrdf::testing
