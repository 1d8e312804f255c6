#pragma once
// Asking the memory system for an object before it is read, for the inline lookups of mip's headers
// (brdf_pyramid.h). Not an interface of the MIP map: a user of the pyramid calls its prefetch().
namespace svbrdf {

// Both cache lines an object may straddle (a Lobe is 44 bytes, a RadialCorrection 48).
template <class T>
inline void prefetch_object(const T* object) {
  const char* p = reinterpret_cast<const char*>(object);
  __builtin_prefetch(p);
  __builtin_prefetch(p + sizeof(T) - 1);
}

}  // namespace svbrdf
