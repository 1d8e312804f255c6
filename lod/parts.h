#pragma once
// The LOD comparison in parts (a farm's array tasks) and their assembly into the results of the whole.
//
// A part (LodOptions::part of parts) writes, into a folder the parts share:
//   lod-part-I-of-N.json                 its shots' numbers and the run it belongs to, written last
//   lod-part-I-of-N.shot-K.truth.exr     shot K's ground truth,
//   lod-part-I-of-N.shot-K.mask.exr      its object mask (one channel, 0 or 1),
//   lod-part-I-of-N.shot-K.FILTER.exr    each filter's render,
// the images in float (the report's PNGs are made from them as from the renders themselves) and
// every file atomically, so a part's JSON exists only when its images do. The numbers are JSON
// doubles, which read back as the doubles written (nlohmann writes the shortest text that does).
//
// The assembly reads every lod-part-*-of-*.json of the folder and gives the results of the single
// run: the shots of all parts in the comparison's order. It refuses, naming the file, a part missing,
// unreadable or cut short (JSON or image), a file that holds another part than its name says (a
// copy), a shot that two parts hold or that no part holds, and a part of another run (other options,
// manifest, part count).
#include <filesystem>
#include <string>

#include "lod/comparison.h"

namespace svbrdf {

// What the report needs besides the results, recorded by each part and checked equal across them.
struct LodPartRun {
  std::filesystem::path manifest;  // absolute
  std::string size_name;           // LodReportInfo::size_name
  std::string command;             // the comparison's command line, without the part's options
};

// The file name of part I of N's JSON.
std::string lod_part_name(int part, int parts);

// Writes results (of LodOptions::part of parts, with keep_images) into `dir`, which must exist.
void write_lod_part(const LodResults& results, const LodPartRun& run, const std::filesystem::path& dir);

// Reads every part in `dir`; throws svbrdf::Error (bad input, one line naming the file) as above.
LodResults read_lod_parts(const std::filesystem::path& dir, LodPartRun& run);

}  // namespace svbrdf
