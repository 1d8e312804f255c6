// The MIP file's svbrdf:checksum: every level's header carries the fingerprint of its pixels, written
// after the pixels over a placeholder of the same length, and a level whose checksum differs from
// its pixels' is refused.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "base/error.h"
#include "mip/mip_file.h"
#include "tests/common/run_command.h"
#include "tests/common/temp_dir.h"
#include "tests/mip/synthetic_materials.h"

namespace svbrdf {
namespace {

TEST(MipFileChecksum, EveryLevelCarriesItsPixelsChecksumAndAChangedOneIsRefused) {
  testing::TempDir dir;
  const auto path = dir / "tray.exr";
  write_mip_file(path, build_mip(synthetic::tray(16)));
  std::vector<std::string> checksums;
  {
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path.string());
    ASSERT_TRUE(in);
    for (int level = 0; in->seek_subimage(level, 0); ++level)
      checksums.push_back(in->spec().get_string_attribute("svbrdf:checksum"));
  }
  ASSERT_EQ(checksums.size(), 5u);
  for (std::size_t level = 0; level < checksums.size(); ++level) {
    const std::string& c = checksums[level];
    ASSERT_EQ(c.size(), 32u) << "level " << level;
    EXPECT_EQ(std::count_if(c.begin(), c.end(),
                            [](char x) { return std::isxdigit(static_cast<unsigned char>(x)); }),
              32)
        << c;
    EXPECT_NE(c, std::string(32, '0')) << "level " << level << " kept the placeholder";
    for (std::size_t other = 0; other < level; ++other) EXPECT_NE(c, checksums[other]);
  }
  EXPECT_NO_THROW(read_mip_file(path));  // each level's pixels give its checksum
  // Level 2's checksum changed in one digit, nothing else: the file is refused.
  std::string bytes = testing::slurp(path);
  const std::size_t at = bytes.find(checksums[2]);
  ASSERT_NE(at, std::string::npos);
  bytes[at] = bytes[at] == 'a' ? 'b' : 'a';
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  try {
    read_mip_file(path);
    ADD_FAILURE() << "a level whose checksum is not its pixels' was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("level 2 does not match its svbrdf:checksum"), std::string::npos)
        << e.what();
    EXPECT_EQ(e.exit_code(), 2);
  }
}

}  // namespace
}  // namespace svbrdf
