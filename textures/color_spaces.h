#pragma once
// Which color spaces of an OpenColorIO config play the parts the project needs: linear Rec.709 (the
// working space, DESIGN.md "Conventions"), the IEC 61966-2-1 sRGB encoding glTF prescribes for color
// textures, and raw data. Found through the config's roles (OpenColorIO's role names: scene_linear,
// color_picking, texture_paint, matte_paint, default, data, and the interchange roles
// aces_interchange and cie_xyz_d65_interchange), each checked by what it does rather than what it is
// called:
//   - linear: the scene_linear role, when an interchange role shows it has Rec.709 primaries (an
//     ACES config's scene_linear is ACEScg: then the config's color space that the interchange role
//     shows is linear Rec.709); a config without an interchange role is taken at its word;
//   - sRGB texture: the first of the roles color_picking, texture_paint, matte_paint, default_byte,
//     default, then of all the config's color spaces, that decodes into the linear space channel by
//     channel by the IEC 61966-2-1 curve (configs give these roles to different spaces: Blender's
//     texture_paint is linear, ACES 1.x's color_picking is a display transform);
//   - data: the data role, else the first color space marked isdata.
// Names ("Linear Rec.709 (sRGB)", "Utility - sRGB - Texture", ...) are the fallback: for a config
// without roles, and for one whose roles name no space that passes (an OCIO v1 ACES config without
// interchange roles, whose scene_linear is ACEScg).
#include <OpenColorIO/OpenColorIO.h>

#include <string>

namespace svbrdf {

struct ResolvedColorSpaces {
  std::string linear;        // linear Rec.709
  std::string srgb_texture;  // the sRGB encoding of color textures
  std::string data;          // raw data; empty when the config has none
};

// Throws svbrdf::Error (bad input, naming `source`) when the config has no linear Rec.709 or no sRGB
// texture space.
ResolvedColorSpaces resolve_color_spaces(const OCIO_NAMESPACE::ConstConfigRcPtr& config, const std::string& source);

}  // namespace svbrdf
