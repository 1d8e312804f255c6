#include "gltf/animation_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>

#include <glm/gtc/type_ptr.hpp>

#include "base/error.h"
#include "gltf/accessor.h"

namespace svbrdf::gltf {

namespace {

// The properties of a node an animation channel may move (§5.6.2 target.path), those read here.
enum class Property { translation, rotation, scale };

const char* property_name(Property p) {
  return p == Property::translation ? "translation" : p == Property::rotation ? "rotation" : "scale";
}

std::string number(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.9g", x);
  return b;
}

class MotionReader {
 public:
  MotionReader(const Document& doc, std::vector<std::string>* warnings)
      : model_(doc.model), doc_(doc), file_(doc.path.string() + ": "), warnings_(warnings) {}

  CameraMotion read(const std::vector<int>& chain) {
    CameraMotion motion;
    for (const int n : chain) motion.chain.push_back(static_pose(n));
    // Which channel animates each (node, property), for the checks below.
    std::map<std::pair<int, Property>, std::pair<std::size_t, std::string>> owner;
    for (std::size_t a = 0; a < model_.animations.size(); ++a) {
      const tinygltf::Animation& anim = model_.animations[a];
      for (std::size_t c = 0; c < anim.channels.size(); ++c) {
        const tinygltf::AnimationChannel& ch = anim.channels[c];
        const auto link = std::find(chain.begin(), chain.end(), ch.target_node);
        if (ch.target_node < 0 || link == chain.end()) continue;  // not a node of the chain
        NodeMotion& node = motion.chain[std::size_t(link - chain.begin())];
        const std::string wc = channel_name(a, c);
        Property property;
        if (ch.target_path == "translation") property = Property::translation;
        else if (ch.target_path == "rotation") property = Property::rotation;
        else if (ch.target_path == "scale") property = Property::scale;
        else if (ch.target_path == "weights") continue;  // a morph target's weights: no bearing on the camera
        else fail(wc + ".target.path", "is '" + ch.target_path + "'; expected translation, rotation, scale or weights");
        if (node.matrix)
          fail(wc + ".target.node", "names " + json_index("nodes", node.node) +
                                        ", which has a matrix: glTF animates a node's translation, rotation and scale, "
                                        "and a node an animation targets has none (glTF 2.0 §3.11)");
        if (ch.sampler < 0 || std::size_t(ch.sampler) >= anim.samplers.size())
          fail(wc + ".sampler", "names sampler " + std::to_string(ch.sampler) + ", but " + json_index("animations", int(a)) +
                                    " has " + std::to_string(anim.samplers.size()) + " samplers");
        const auto key = std::make_pair(node.node, property);
        if (const auto it = owner.find(key); it != owner.end()) {
          if (it->second.first == a)
            fail(wc + ".target", "animates the " + std::string(property_name(property)) + " of " +
                                     json_index("nodes", node.node) + ", as " + it->second.second +
                                     " does: within one animation each node's property has one channel (glTF 2.0 §3.11)");
          warnings_->push_back(file_ + wc + ": animates the " + property_name(property) + " of " +
                               json_index("nodes", node.node) + ", which " + it->second.second +
                               " animates already; the earlier animation is played");
          continue;
        }
        owner.emplace(key, std::make_pair(a, wc));
        AnimationSampler s = read_sampler(a, std::size_t(ch.sampler), property == Property::rotation);
        (property == Property::translation ? node.translation_sampler
         : property == Property::rotation  ? node.rotation_sampler
                                           : node.scale_sampler) = std::move(s);
        motion.channels.push_back(wc);
      }
    }
    return motion;
  }

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw input_error(file_ + where, what);
  }

  // "animations[a].channels[c]" with c the file's index of tinygltf's channel c.
  std::string channel_name(std::size_t a, std::size_t c) const {
    const bool mapped = a < doc_.animation_channels.size() && c < doc_.animation_channels[a].size();
    return json_index("animations", int(a)) + ".channels[" +
           std::to_string(mapped ? doc_.animation_channels[a][c] : int(c)) + "]";
  }

  // A node's own transform, as the scene reader composes it (it has checked the values).
  NodeMotion static_pose(int n) const {
    const tinygltf::Node& node = model_.nodes[std::size_t(n)];
    NodeMotion m;
    m.node = n;
    if (node.matrix.size() == 16) {
      m.matrix = glm::make_mat4(node.matrix.data());
      return m;
    }
    if (node.translation.size() == 3) m.translation = glm::make_vec3(node.translation.data());
    if (node.rotation.size() == 4) {
      const glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
      if (glm::length(q) > 0.0) m.rotation = glm::normalize(q);
    }
    if (node.scale.size() == 3) m.scale = glm::make_vec3(node.scale.data());
    return m;
  }

  AnimationSampler read_sampler(std::size_t a, std::size_t s, bool rotation) const {
    const tinygltf::AnimationSampler& smp = model_.animations[a].samplers[s];
    const std::string w = json_index("animations", int(a)) + ".samplers[" + std::to_string(s) + "]";
    AnimationSampler out;
    if (smp.interpolation == "LINEAR") out.interpolation = Interpolation::linear;
    else if (smp.interpolation == "STEP") out.interpolation = Interpolation::step;
    else if (smp.interpolation == "CUBICSPLINE") out.interpolation = Interpolation::cubic_spline;
    else fail(w + ".interpolation", "is '" + smp.interpolation + "'; expected LINEAR, STEP or CUBICSPLINE");

    // §5.5.1 input: "scalar type with floating-point components", times "time[0] >= 0.0, and
    // strictly increasing values".
    int comps = 0;
    out.times = read_floats(model_, smp.input, AccessorShape{{TINYGLTF_TYPE_SCALAR}, {TINYGLTF_COMPONENT_TYPE_FLOAT}},
                            file_ + w + ".input", &comps);
    if (!(out.times[0] >= 0.0f))
      fail(w + ".input", json_index("accessors", smp.input) + " begins at " + number(out.times[0]) +
                             " s; animation times are 0 or more");
    for (std::size_t k = 1; k < out.times.size(); ++k)
      if (!(out.times[k] > out.times[k - 1]))
        fail(w + ".input", json_index("accessors", smp.input) + " element " + std::to_string(k) + " is " +
                               number(out.times[k]) + " s, not after element " + std::to_string(k - 1) + "'s " +
                               number(out.times[k - 1]) + " s: key times increase strictly");

    // §3.11's table of animated properties: translation and scale float VEC3; rotation VEC4 of
    // float or normalized signed or unsigned bytes or shorts.
    const AccessorShape shape =
        rotation ? AccessorShape{{TINYGLTF_TYPE_VEC4},
                                 {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
                                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT}}
                 : AccessorShape{{TINYGLTF_TYPE_VEC3}, {TINYGLTF_COMPONENT_TYPE_FLOAT}};
    out.values = read_floats(model_, smp.output, shape, file_ + w + ".output", &out.components);
    const tinygltf::Accessor& output = model_.accessors[std::size_t(smp.output)];  // read_floats checked the index
    if (output.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !output.normalized)
      fail(w + ".output", json_index("accessors", smp.output) + " holds integers that are not normalized; a rotation's "
                                                                "integer components are normalized (glTF 2.0 §3.11)");
    const std::size_t keys = out.times.size(), elements = out.values.size() / std::size_t(out.components);
    const bool cubic = out.interpolation == Interpolation::cubic_spline;
    if (cubic && keys < 2)
      fail(w + ".input", json_index("accessors", smp.input) + " has one key; CUBICSPLINE needs at least two");
    if (elements != (cubic ? 3 : 1) * keys)
      fail(w + ".output", json_index("accessors", smp.output) + " has " + std::to_string(elements) + " elements for " +
                              std::to_string(keys) + " keys; " + smp.interpolation + " needs " +
                              (cubic ? "three per key (in-tangent, value, out-tangent)" : "one per key"));
    if (rotation)
      for (std::size_t e = cubic ? 1 : 0; e < elements; e += cubic ? 3 : 1) {
        const float* q = &out.values[4 * e];
        if (q[0] == 0.0f && q[1] == 0.0f && q[2] == 0.0f && q[3] == 0.0f)
          fail(w + ".output", json_index("accessors", smp.output) + " element " + std::to_string(e) +
                                  " is a zero quaternion, which is no rotation");
      }
    return out;
  }

  const tinygltf::Model& model_;
  const Document& doc_;
  std::string file_;
  std::vector<std::string>* warnings_;
};

}  // namespace

CameraMotion read_camera_motion(const Document& doc, const std::vector<int>& chain, std::vector<std::string>* warnings) {
  return MotionReader(doc, warnings).read(chain);
}

}  // namespace svbrdf::gltf
