#pragma once
// The MIP file: one material's level-0 parameters, parameter pyramid and BRDF pyramid in one
// OpenEXR file with one subimage (part) per level, so OpenImageIO's tools list it
// (`oiiotool --info -v FILE`, `iinfo -v FILE`). Written atomically; read back bit-identically.
//
// Subimage L (0 ≤ L < levels) has level L's resolution, the part name "levelL", and channels
//   param.R, param.G, param.B   mean linear base color                                   float
//   param.metallic              mean metallic                                            float
//   param.roughness             mean perceptual roughness (α = roughness², per texel)    float
//   param.N.X, param.N.Y, param.N.Z  mean of the unit shading normals in the tangent frame,
//                               unnormalized (its length < 1 says how much they spread); at
//                               level 0 the texel's unit normal                          float
// and, in every level of a material whose specular layer is not plain (KHR_materials_specular;
// textures/material_texels.h), 16 bytes:
//   param.specular              mean specular weight s                                   float
//   param.specular.R/G/B        mean specular colour (linear)                            float
// and, in every level of a material with a clear coat (KHR_materials_clearcoat), 20 bytes:
//   param.coat                  mean clearcoat weight                                    float
//   param.coat.roughness        mean clearcoat perceptual roughness                      float
//   param.coat.N.X/Y/Z          mean of the unit coat normals, unnormalized (level 0: the
//                               texel's coat normal)                                     float
// and, in every level of a material with a sheen (KHR_materials_sheen), 16 bytes, which the BRDF
// pyramid's texels read too (sheen_layer.h):
//   param.sheen.R/G/B           mean linear sheen colour                                 float
//   param.sheen.roughness       mean sheen perceptual roughness                          float
// and, in every level of an anisotropic material (KHR_materials_anisotropy), 12 bytes (level 0: the
// texel's own; above, param_pyramid.h anisotropy_from_below):
//   param.anisotropy            mean anisotropy strength                                 float
//   param.anisotropy.X/Y        its unit direction in the tangent frame                  float
// and, in every level of a material that transmits (KHR_materials_transmission, thin-walled), 4 bytes
// (level 0: the texel's own T; above, the mean of the covered texels'):
//   param.transmission          mean transmission T                                      float
// and, in every level of a material that transmits diffusely (KHR_materials_diffuse_transmission),
// 16 bytes (level 0: the texel's own; above, param_pyramid.h diffuse_transmission_mean):
//   param.diffuseTransmission   mean diffuse transmission share d                        float
//   param.diffuseTransmission.R/G/B  its share-weighted mean colour (linear)             float
// and, for L ≥ 1, for each lobe slot k = 0 .. S_L − 1 (lobe.h for the meaning), 26 bytes:
//   lobeK.weight                fraction of the texel's area, times the lobe's specular-flux
//                               factor (0: empty slot; slots are packed from 0)          half
//   lobeK.diffuse.R/G/B         mean diffuse albedo ρ = (1 − metallic)·base color        half
//   lobeK.F0.R/G/B              mean specular reflectance at normal incidence            half
//   lobeK.N.dir                 the direction of the lobe's mean unit normal, an octahedral
//                               code warped toward the pole (stored_normal.h: x in the low 16
//                               bits, y in the high, signed codes q; c = q/32767 and the
//                               octahedral coordinate is c·(1/16 + (15/16)·|c|))          uint
//   lobeK.N.deficit             1 − the mean normal's length (how much the normals spread) half
//   lobeK.alpha                 GGX α of the lobe about the normal's direction, α² its square (a
//                               roughness mixture's lower end, its atom; lobe.h)          half
//   lobeK.shape                 ln(α² upper end / α²) > 0 for a roughness mixture with a
//                               band, −(1 + that) < −1 for a two-point mixture, −μ for a
//                               GGX core with Beckmann share 1 − μ (−1: plain GGX)        half
//   lobeK.skirt                 a core's c ≥ 1 (the Beckmann share's α² is c·alpha2); a
//                               mixture's upper share β, as β ≤ ½ or β − 1 ∈ (−½, 0]; 1
//                               otherwise (stored_lobe.h, lobe_skirt_code)              half
// and, in a level where some lobe has ρ90 ≠ 0 or F90 ≠ 1 (the specular layer), 8 bytes more a slot:
//   lobeK.diffuse90.R/G/B       the diffuse factor at grazing incidence ρ90              half
//   lobeK.F90                   the specular Fresnel at grazing incidence F90           half
// and, in a level of a tintable file (svbrdf:tint 1) where some lobe has f0_tint ≠ 0, 6 bytes more:
//   lobeK.F0tint.R/G/B          the part of F0 a tint of the base color scales, the mean of
//                               metallic·base color (lobe.h, tinted)                     half
// and, in a level of a material with a clear coat, 2 bytes more a slot (coat_layer.h):
//   lobeK.coat                  the mean clearcoat weight of the lobe's texels            half
// and, in a level of a material with a sheen, 2 bytes more a slot (sheen_layer.h):
//   lobeK.sheen                 the mean max(sheen colour) of the lobe's texels, its sheen
//                               share                                                     half
// and, in a level where some lobe is stretched (lobe.h, "Stretched shapes"), 6 bytes more a slot
// (stored_lobe.h):
//   lobeK.stretch               ln r of the stretch (0: none)                             half
//   lobeK.stretch.dirHi/dirLo   the stretch direction's angle in [0, π) as a 20-bit code k
//                               (φ = k·π/2^20), its high and low 10 bits as integers      half
// and, in a level where some lobe transmits (a thin-walled KHR_materials_transmission; lobe.h,
// "Transmission"), 10 bytes more a slot:
//   lobeK.transmission.R/G/B    τ, the lobe's BTDF factor at w = 0                        half
//   lobeK.transmission.alpha    α_T, the GGX α of its transmission, its band's lower end
//                               (0: transmits nothing)                                    half
//   lobeK.transmission.alphaHi  its band's upper end (0: GGX)                             half
// and, in a level where some lobe's τ90 ≠ 0 (a transmitting material whose specular layer is not
// plain), 6 bytes more a slot:
//   lobeK.transmission90.R/G/B  τ90, the BTDF factor at w = 1                             half
// and, in a level where some lobe's transmission is stretched (its texels' anisotropy, without the
// normals' spread that the lobe's own stretch holds; lobe.h "Transmission"), 6 bytes more a slot:
//   lobeK.transmission.stretch, lobeK.transmission.stretch.dirHi/dirLo
//                               the transmission's stretch, coded as lobeK.stretch's      half
// and, in a level where some lobe transmits diffusely (KHR_materials_diffuse_transmission;
// diffuse_transmission.h), 6 bytes more a slot:
//   lobeK.diffuseTransmission.R/G/B    τd, the Lambertian BTDF's factor at w = 0           half
// and, in a level where some lobe's τd90 ≠ 0 (a diffusely transmitting material whose specular layer
// is not plain), 6 bytes more a slot:
//   lobeK.diffuseTransmission90.R/G/B  τd90, its factor at w = 1                          half
// and, for L ≥ kFirstCorrectedLevel (4), 24 bytes (radial_correction.h):
//   radial.R0 .. radial.R11     the texel's radial correction: the ratio of its true radial
//                               profile of reflected light to its lobes' (gated beyond 10°)
//                               at the 12 nodes of the grid svbrdf:radial_inner and
//                               svbrdf:radial_outer define                                half
// and, for L ≥ 1 of a material with a clear coat, for each coat lobe slot k = 0 .. C_L − 1 (coat_layer.h;
// F0 0.04, F90 1 and no diffuse term, which the extension fixes, are not stored), 14 bytes:
//   coatK.weight                the texel's mean clearcoat the lobe carries (0: empty)   half
//   coatK.N.dir, coatK.N.deficit, coatK.alpha, coatK.shape, coatK.skirt
//                               the coat lobe's mean coat normal and shape, as lobeK's   uint, half
// Level 0's BRDF pyramid is its parameters (one lobe per texel) and is not stored twice.
// Attributes on every subimage: svbrdf:mip_version (int, kMipFileVersion), svbrdf:level (int),
// svbrdf:max_lobes (int, the --lobes the file was built with), svbrdf:slots (int, S_L),
// svbrdf:coat_slots (int, C_L, on levels ≥ 1 of a material with a clear coat), svbrdf:ior
// (float, the material's KHR_materials_ior; absent: 1.5), svbrdf:tint (int 1: a pyramid built for
// tinted lookups, brdf_pyramid.h BrdfBuildOptions::tint; absent: 0), and, where any
// level has radial channels, svbrdf:radial_inner (float, radians: θ of the grid's node 1) and
// svbrdf:radial_outer (float, degrees: θ of its last node, RadialGrid::kOuterDeg).
// svbrdf:checksum (string, on every subimage): 32 hexadecimal digits, farmhash's Fingerprint128 (a
// fixed, portable hash, OpenImageIO's hash.h) of the level's header values that give its texels a
// meaning (its level, size, slots, lobes, radial grid, channels) and of its pixels as stored, channels
// in the order of their names (OpenEXR's); a file that has it is checked as it is read, and refused
// once read when a level differs (after any other refusal, which says more).
// svbrdf:cache_key (string, on subimage 0): the key of a MIP cache entry (render/mip_cache.h), when
// the file is one.
// This build reads version kMipFileVersion only. A file of any other version is refused with one line
// that names the file, its version and this build's, and how to rebuild it: another version's
// channels mean other things, and a current file is one `svbrdf-bake mip` away.
#include <filesystem>
#include <string>

#include "mip/mip_data.h"

namespace svbrdf {

inline constexpr int kMipFileVersion = 17;

// Throws svbrdf::Error naming the file when it cannot be written. A non-empty `cache_key` is stored as
// svbrdf:cache_key.
void write_mip_file(const std::filesystem::path& path, const MipData& mip, const std::string& cache_key = {});
// The same from the two pyramids alone (what a MipTexture holds; the file's level 0 is the parameter
// pyramid's).
void write_mip_file(const std::filesystem::path& path, const ParamPyramid& param, const BrdfPyramid& brdf,
                    const std::string& cache_key = {});

// Throws svbrdf::Error naming the file when it is missing, unreadable, not a MIP file, of another
// version than kMipFileVersion, or inconsistent (levels of the wrong size, missing channels, a level
// that does not match its svbrdf:checksum). A non-empty `cache_key` must equal the file's
// svbrdf:cache_key, checked before any pixel is read, and every level must carry its checksum.
MipData read_mip_file(const std::filesystem::path& path, const std::string& cache_key = {});

}  // namespace svbrdf
