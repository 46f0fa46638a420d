// This build tree's folders and programs (see test_paths.hpp), from the
// compile definitions tests/CMakeLists.txt gives this file alone.
#include "test_paths.hpp"

namespace globe_test::paths {

std::string tiler() {
  return GLOBE_TILER_PATH;
}
std::string vectorize() {
  return GLOBE_VECTORIZE_PATH;
}
std::string view() {
  return GLOBE_VIEW_PATH;
}
std::string serve() {
  return GLOBE_SERVE_PATH;
}
std::string lib_tests() {
  return GLOBE_LIB_TESTS_PATH;
}
std::string gdal_plugin_dir() {
  return GLOBE_GDAL_PLUGIN_DIR;
}
std::string kill_after_commit() {
  return GLOBE_KILL_AFTER_COMMIT_PATH;
}
std::string fault_server() {
  return GLOBE_FAULT_SERVER_PATH;
}
std::string source_dir() {
  return GLOBE_SOURCE_DIR;
}
std::string binary_dir() {
  return GLOBE_BINARY_DIR;
}
std::string samples_dir() {
  return GLOBE_SAMPLES_DIR;
}
std::string test_data_dir() {
  return GLOBE_TEST_DATA_DIR;
}
std::string shared_dir() {
  return GLOBE_TEST_SHARED_DIR;
}
std::string render_diff_dir() {
  return GLOBE_RENDER_DIFF_DIR;
}
std::string user_cxx() {
  return GLOBE_USER_CXX;
}
std::string project_version() {
  return GLOBE_PROJECT_VERSION;
}

}  // namespace globe_test::paths
