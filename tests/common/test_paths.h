#pragma once
// Where the tests find the checkout, ../shared, the build tree and the programs the build makes. The
// values are this build's, in a source file tests/CMakeLists.txt generates: compile definitions would
// put the checkout's path on every test file's command line and defeat ccache in a new clone. Each is
// a constant array, initialized before any test's own static constants.

extern const char svbrdf_test_source_dir[];
extern const char svbrdf_test_shared_dir[];
extern const char svbrdf_test_binary_dir[];
extern const char svbrdf_test_bake[];
extern const char svbrdf_test_render[];
extern const char svbrdf_test_brdf[];
extern const char svbrdf_test_lod_report[];

#define SVBRDF_SOURCE_DIR svbrdf_test_source_dir
#define SVBRDF_SHARED_DIR svbrdf_test_shared_dir
#define SVBRDF_BINARY_DIR svbrdf_test_binary_dir
#define SVBRDF_BAKE svbrdf_test_bake
#define SVBRDF_RENDER svbrdf_test_render
#define SVBRDF_BRDF_EXE svbrdf_test_brdf
#define SVBRDF_LOD_REPORT svbrdf_test_lod_report
