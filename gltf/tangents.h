#pragma once
// Vertex normals and tangents for primitives whose file lacks them (glTF 2.0 §3.7.2.1): flat normals
// when NORMAL is missing, and MikkTSpace-compatible tangents when TANGENT is missing and a normal map
// is used. Written from the description of Mikkelsen 2008 ("Simulation of wrinkled surfaces
// revisited", MSc thesis) and the reference implementation's documented behaviour: per-triangle
// tangents along ∂p/∂u, projected into each vertex's tangent plane, weighted by the corner angle,
// summed over the triangles that share a vertex (same position, normal and uv) and the same uv
// orientation, with the bitangent sign from the uv orientation.
#include "gltf/scene.h"

namespace svbrdf {

// Replaces an indexed primitive with one whose three corners of each triangle are separate vertices
// carrying the face's normal (p1 − p0) × (p2 − p0), normalized (glTF: "flat normals"). Zero-area
// triangles get any unit normal; they are never hit.
void make_flat_normals(MeshPrimitive& prim);

// Fills prim.tangents from positions, normals and texcoords[tex_coord]; splits a vertex where its
// triangles disagree (a uv seam or mirrored uvs), so indices may change. glTF's v axis points down the
// image, MikkTSpace's up, so v is flipped for the computation; the resulting bitangent
// B = w·(N × T) points toward decreasing v — the "+Y up" of glTF's normal textures.
void generate_tangents(MeshPrimitive& prim, int tex_coord);

}  // namespace svbrdf
