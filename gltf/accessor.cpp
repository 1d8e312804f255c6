#include "gltf/accessor.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <limits>

#include "base/checked_number.h"
#include "base/error.h"
#include "base/resource_limits.h"

namespace svbrdf::gltf {

namespace {

int component_size(int ct) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

int type_components(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
  }
}

std::string type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "of a type glTF does not define";
  }
}

std::string acc_name(int i) { return "accessors[" + std::to_string(i) + "]"; }
std::string bv_name(int i) { return "bufferViews[" + std::to_string(i) + "]"; }

template <typename T>
T load(const unsigned char* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

// glTF 2.0 §3.11 "Animations"/"Meshes": normalized integer → float.
float component_value(const unsigned char* p, int ct, bool normalized) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return load<float>(p);
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const float c = load<std::int8_t>(p);
      return normalized ? std::max(c / 127.0f, -1.0f) : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const float c = load<std::uint8_t>(p);
      return normalized ? c / 255.0f : c;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const float c = load<std::int16_t>(p);
      return normalized ? std::max(c / 32767.0f, -1.0f) : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const float c = load<std::uint16_t>(p);
      return normalized ? c / 65535.0f : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      const auto c = load<std::uint32_t>(p);
      return normalized ? static_cast<float>(c / 4294967295.0) : static_cast<float>(c);
    }
    default: return 0.0f;
  }
}

std::uint32_t index_value(const unsigned char* p, int ct) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return load<std::uint8_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return load<std::uint16_t>(p);
    default: return load<std::uint32_t>(p);
  }
}

const tinygltf::Accessor& accessor_at(const tinygltf::Model& m, int index, const std::string& where) {
  if (index < 0 || static_cast<std::size_t>(index) >= m.accessors.size())
    throw input_error(where, "names " + acc_name(index) + ", but the file has " +
                                 std::to_string(m.accessors.size()) + " accessors");
  return m.accessors[static_cast<std::size_t>(index)];
}

// The bytes of buffer view `bv` from `offset` on, checked to hold `count` elements of `elem` bytes
// `stride` apart; returns the first element's address. `what` names the requester for messages.
const unsigned char* view_bytes(const tinygltf::Model& m, int bv, std::uint64_t offset, std::uint64_t count,
                                std::uint64_t stride, std::uint64_t elem, const std::string& where,
                                const std::string& what) {
  if (bv < 0 || static_cast<std::size_t>(bv) >= m.bufferViews.size())
    throw input_error(where, what + " names " + bv_name(bv) + ", but the file has " +
                                 std::to_string(m.bufferViews.size()) + " buffer views");
  const tinygltf::BufferView& view = m.bufferViews[static_cast<std::size_t>(bv)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= m.buffers.size())
    throw input_error(where, bv_name(bv) + " names buffers[" + std::to_string(view.buffer) +
                                 "], but the file has " + std::to_string(m.buffers.size()) + " buffers");
  const tinygltf::Buffer& buffer = m.buffers[static_cast<std::size_t>(view.buffer)];
  // Every sum below is checked: a byteOffset near 2^64 must not wrap the bound (glTF stores these as
  // JSON integers, which tinygltf reads into 64 bits).
  // A buffer with no bytes: one without a uri outside a .glb's first, or one whose uri is a URL
  // (gltf/tinygltf_stand_ins.h).
  if (buffer.data.empty() && view.byteLength > 0 && (buffer.uri.empty() || buffer.uri.find("://") != std::string::npos))
    throw input_error(where, bv_name(bv) + " reads buffers[" + std::to_string(view.buffer) + "], " +
                                 (buffer.uri.empty() ? std::string("which has no uri, so the file holds none of its bytes")
                                                     : "whose uri '" + buffer.uri + "' is not read: nothing is fetched from a network"));
  if (!range_inside(view.byteOffset, view.byteLength, buffer.data.size()))
    throw input_error(where, bv_name(bv) + " spans bytes [" + std::to_string(view.byteOffset) + ", +" +
                                 std::to_string(view.byteLength) + ") of buffers[" + std::to_string(view.buffer) +
                                 "], which has only " + std::to_string(buffer.data.size()) +
                                 " bytes (missing or short buffer)");
  if (count == 0) return buffer.data.data() + view.byteOffset;
  const auto span = checked_mul(count - 1, stride);
  const auto tail = span ? checked_add(*span, elem) : std::nullopt;
  if (!tail || !range_inside(offset, *tail, view.byteLength))
    throw input_error(where, what + " needs " + std::to_string(count) + " elements of " + std::to_string(elem) +
                                 " bytes, " + std::to_string(stride) + " apart, from byte " + std::to_string(offset) +
                                 " of " + bv_name(bv) + ", which has " + std::to_string(view.byteLength));
  return buffer.data.data() + view.byteOffset + offset;
}

// An accessor without a buffer view is zeros (§3.6.2.2), which cost the file nothing to state; it
// may be no larger than the file's buffers (or 1 MiB), the most its elements could have been given
// by data, so that a count of 10^9 in a file of a few hundred bytes is refused, not allocated.
void check_zeros(const tinygltf::Model& m, std::uint64_t count, std::uint64_t element_bytes, int index,
                 const std::string& where) {
  std::uint64_t have = 0;
  for (const auto& b : m.buffers) have += b.data.size();
  const std::uint64_t limit = std::max<std::uint64_t>(have, std::uint64_t(1) << 20);
  const auto bytes = checked_mul(count, element_bytes);
  if (!bytes || *bytes > limit)
    throw input_error(where, acc_name(index) + " has no bufferView, so its " + std::to_string(count) +
                                 " elements are zeros the file does not hold; more than its buffers' " +
                                 std::to_string(have) + " bytes (or 1 MiB) could have described");
}

void check_count(const tinygltf::Accessor& a, int index, const std::string& where) {
  if (a.count == 0) throw input_error(where, acc_name(index) + " has count 0");
  if (a.count > std::numeric_limits<std::uint32_t>::max())
    throw input_error(where, acc_name(index) + " has count " + std::to_string(a.count) + ", beyond 2^32");
}

// Applies the sparse substitution of §3.6.2.3 onto `out` (count × comps values).
void apply_sparse(const tinygltf::Model& m, const tinygltf::Accessor& a, int index, int comps,
                  std::vector<float>& out, const std::string& where) {
  const auto& sp = a.sparse;
  if (sp.count <= 0 || static_cast<std::size_t>(sp.count) > a.count)
    throw input_error(where, acc_name(index) + ".sparse.count is " + std::to_string(sp.count) +
                                 " for an accessor of " + std::to_string(a.count) + " elements");
  const int ict = sp.indices.componentType;
  if (ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    throw input_error(where, acc_name(index) + ".sparse.indices has component type " + std::to_string(ict));
  const int isz = component_size(ict);
  const auto n = static_cast<std::uint64_t>(sp.count);
  const unsigned char* ip = view_bytes(m, sp.indices.bufferView, static_cast<std::uint64_t>(sp.indices.byteOffset),
                                       n, isz, isz, where, acc_name(index) + ".sparse.indices");
  const int csz = component_size(a.componentType);
  const std::uint64_t elem = std::uint64_t(csz) * comps;
  const unsigned char* vp = view_bytes(m, sp.values.bufferView, static_cast<std::uint64_t>(sp.values.byteOffset),
                                       n, elem, elem, where, acc_name(index) + ".sparse.values");
  for (std::uint64_t k = 0; k < n; ++k) {
    const std::uint32_t target = index_value(ip + k * isz, ict);
    if (target >= a.count)
      throw input_error(where, acc_name(index) + ".sparse.indices[" + std::to_string(k) + "] is " +
                                   std::to_string(target) + ", past the accessor's " + std::to_string(a.count) +
                                   " elements");
    for (int c = 0; c < comps; ++c)
      out[std::size_t(target) * comps + c] = component_value(vp + k * elem + c * csz, a.componentType, a.normalized);
  }
}

// The bound `b` of accessor.min/max (stated in the stored values, glTF 2.0 §5.1: "normalized has no
// effect on array values") in the values read_floats returns.
double bound_as_read(double b, int ct, bool normalized) {
  if (!normalized) return b;
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return std::max(b / 127.0, -1.0);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return b / 255.0;
    case TINYGLTF_COMPONENT_TYPE_SHORT: return std::max(b / 32767.0, -1.0);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return b / 65535.0;
    default: return b;
  }
}

// The values an accessor holds, as a renderer would draw them: finite (glTF 2.0 §3.6.2.2: "values
// of FLOAT components MUST NOT be NaN or infinite") and within its min and max where it states them
// (§5.1: min and max bound every component, sparse substitution applied). The bounds get the room of
// a float's rounding: a writer may print them from the doubles it computed in.
void check_values(const tinygltf::Accessor& a, int index, int comps, const std::vector<float>& v,
                  const std::string& where) {
  const bool bounded = a.minValues.size() == std::size_t(comps) && a.maxValues.size() == std::size_t(comps);
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double x = v[i];
    const auto c = static_cast<std::size_t>(i % std::size_t(comps));
    if (!std::isfinite(x))
      throw input_error(where, acc_name(index) + " element " + std::to_string(i / std::size_t(comps)) +
                                   " is not finite (NaN or infinity)");
    if (!bounded) continue;
    const double lo = bound_as_read(a.minValues[c], a.componentType, a.normalized);
    const double hi = bound_as_read(a.maxValues[c], a.componentType, a.normalized);
    const double slack = 1e-6 * std::max({1.0, std::abs(lo), std::abs(hi)});
    if (x < lo - slack || x > hi + slack) {
      std::ostringstream m;
      m << acc_name(index) << " element " << i / std::size_t(comps) << " component " << c << " is " << x
        << ", outside the accessor's min " << lo << " and max " << hi;
      throw input_error(where, m.str());
    }
  }
}

}  // namespace

std::size_t element_count(const tinygltf::Model& model, int index, const std::string& where) {
  return accessor_at(model, index, where).count;
}

int accessor_components(const tinygltf::Model& m, int index, const AccessorShape& shape, const std::string& where) {
  const tinygltf::Accessor& a = accessor_at(m, index, where);
  if (std::find(shape.types.begin(), shape.types.end(), a.type) == shape.types.end()) {
    std::string allowed;
    for (int t : shape.types) allowed += (allowed.empty() ? "" : " or ") + type_name(t);
    throw input_error(where, acc_name(index) + " is " + type_name(a.type) + ", expected " + allowed);
  }
  if (component_size(a.componentType) == 0)
    throw input_error(where, acc_name(index) + " has component type " + std::to_string(a.componentType));
  if (!shape.component_types.empty() &&
      std::find(shape.component_types.begin(), shape.component_types.end(), a.componentType) ==
          shape.component_types.end())
    throw input_error(where, acc_name(index) + " has component type " + std::to_string(a.componentType) +
                                 ", which glTF does not allow here");
  check_count(a, index, where);
  return type_components(a.type);
}

std::vector<float> read_floats(const tinygltf::Model& m, int index, const AccessorShape& shape,
                               const std::string& where, int* components_out) {
  const int comps = accessor_components(m, index, shape, where);
  const tinygltf::Accessor& a = m.accessors[static_cast<std::size_t>(index)];
  const int csz = component_size(a.componentType);
  if (components_out) *components_out = comps;
  // glTF 2.0 §5.1 (accessor.normalized, accessor.byteOffset).
  if (a.normalized && (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                       a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
    throw input_error(where, acc_name(index) + " is normalized, which a FLOAT or UNSIGNED_INT accessor must not be");
  if (a.bufferView < 0 && a.byteOffset != 0)
    throw input_error(where, acc_name(index) + " has a byteOffset but no bufferView to offset into");
  // The bytes are checked present before the output is allocated, so a count of 10^9 in a small
  // file is refused rather than allocated; an accessor with no buffer view (zeros, §3.6.2.2) is held
  // to check_zeros.
  const unsigned char* p = nullptr;
  std::uint64_t stride = 0;
  if (a.bufferView >= 0) {
    const std::uint64_t elem = std::uint64_t(csz) * comps;
    stride = elem;
    const auto& views = m.bufferViews;
    if (static_cast<std::size_t>(a.bufferView) < views.size() && views[a.bufferView].byteStride != 0) {
      stride = views[a.bufferView].byteStride;
      if (stride < elem)
        throw input_error(where, bv_name(a.bufferView) + ".byteStride " + std::to_string(stride) +
                                     " is smaller than one element of " + acc_name(index) + " (" +
                                     std::to_string(elem) + " bytes)");
    }
    p = view_bytes(m, a.bufferView, a.byteOffset, a.count, stride, elem, where, acc_name(index));
  }
  if (!p) check_zeros(m, a.count, sizeof(float) * comps, index, where);
  check_allocation(a.count, sizeof(float) * comps, where, acc_name(index) + " elements");
  std::vector<float> out(a.count * comps, 0.0f);
  if (p) {
    for (std::size_t i = 0; i < a.count; ++i)
      for (int c = 0; c < comps; ++c)
        out[i * comps + c] = component_value(p + i * stride + std::uint64_t(c) * csz, a.componentType, a.normalized);
  }  // no buffer view: zeros, then the sparse values if any (glTF 2.0 §3.6.2.2)
  if (a.sparse.isSparse) apply_sparse(m, a, index, comps, out, where);
  check_values(a, index, comps, out, where);
  return out;
}

std::vector<std::uint32_t> read_indices(const tinygltf::Model& m, int index, const std::string& where) {
  const tinygltf::Accessor& a = accessor_at(m, index, where);
  if (a.type != TINYGLTF_TYPE_SCALAR)
    throw input_error(where, acc_name(index) + " is " + type_name(a.type) + ", expected SCALAR");
  const int ct = a.componentType;
  if (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    throw input_error(where, acc_name(index) + " has component type " + std::to_string(ct) +
                                 "; indices must be UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
  check_count(a, index, where);
  const int isz = component_size(ct);
  const unsigned char* p = nullptr;
  std::uint64_t stride = isz;
  if (a.bufferView >= 0) {
    // glTF 2.0 §3.6.2.4 (via bufferView.byteStride): "for indices, byteStride must not be defined".
    if (static_cast<std::size_t>(a.bufferView) < m.bufferViews.size() && m.bufferViews[a.bufferView].byteStride != 0)
      throw input_error(where, acc_name(index) + " reads " + bv_name(a.bufferView) +
                                   ", which has a byteStride; index data are tightly packed");
    p = view_bytes(m, a.bufferView, a.byteOffset, a.count, stride, isz, where, acc_name(index));
  }
  if (!p) check_zeros(m, a.count, sizeof(std::uint32_t), index, where);
  check_allocation(a.count, sizeof(std::uint32_t), where, acc_name(index) + " indices");
  std::vector<std::uint32_t> out(a.count, 0u);
  if (p) {
    for (std::size_t i = 0; i < a.count; ++i) out[i] = index_value(p + i * stride, ct);
  }  // no buffer view: zeros, then the sparse values if any (glTF 2.0 §3.6.2.2)
  if (a.sparse.isSparse) {
    const auto& sp = a.sparse;
    const int ict = sp.indices.componentType;
    const int sisz = component_size(ict);
    if (sp.count <= 0 || static_cast<std::size_t>(sp.count) > a.count || sisz == 0 ||
        ict == TINYGLTF_COMPONENT_TYPE_BYTE || ict == TINYGLTF_COMPONENT_TYPE_SHORT ||
        ict == TINYGLTF_COMPONENT_TYPE_FLOAT)
      throw input_error(where, acc_name(index) + ".sparse is malformed");
    const auto n = static_cast<std::uint64_t>(sp.count);
    const unsigned char* ip = view_bytes(m, sp.indices.bufferView, static_cast<std::uint64_t>(sp.indices.byteOffset),
                                         n, sisz, sisz, where, acc_name(index) + ".sparse.indices");
    const unsigned char* vp = view_bytes(m, sp.values.bufferView, static_cast<std::uint64_t>(sp.values.byteOffset),
                                         n, isz, isz, where, acc_name(index) + ".sparse.values");
    for (std::uint64_t k = 0; k < n; ++k) {
      const std::uint32_t target = index_value(ip + k * sisz, ict);
      if (target >= a.count)
        throw input_error(where, acc_name(index) + ".sparse.indices[" + std::to_string(k) + "] is past the accessor");
      out[target] = index_value(vp + k * isz, ct);
    }
  }
  // glTF 2.0 §3.7.2.1: indices "MUST NOT contain the maximum possible value for the component
  // type" (the primitive restart value of graphics APIs, which would break the strip or list).
  const std::uint32_t restart = ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 0xFFu
                                : ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 0xFFFFu
                                                                               : 0xFFFFFFFFu;
  if (const auto it = std::find(out.begin(), out.end(), restart); it != out.end())
    throw input_error(where, acc_name(index) + " element " + std::to_string(it - out.begin()) + " is " +
                                 std::to_string(restart) + ", the primitive restart value, which glTF forbids in indices");
  return out;
}

}  // namespace svbrdf::gltf
