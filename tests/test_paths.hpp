// Where the tests find the programs, the samples and their own data in this
// build tree. Only test_paths.cpp is compiled with these folders on its
// command line: every other test source's command line is the same in any
// clone and any test executable, so a compiler cache serves them to a clone
// in another folder and all test executables share one precompiled header
// (docs/ci.md "Compiler cache").
#pragma once

#include <string>

namespace globe_test::paths {

std::string tiler();              // globe-tiler
std::string vectorize();          // globe-vectorize
std::string view();               // globe-view
std::string serve();              // globe-serve
std::string lib_tests();          // the lib_tests executable
std::string gdal_plugin_dir();    // gdal_GlobeTiles.so's folder
std::string kill_after_commit();  // the LD_PRELOAD shim of the crash tests
std::string fault_server();       // the misbehaving HTTP server (support/fault_server.cpp)
std::string source_dir();         // the repository
std::string binary_dir();         // this build tree
std::string samples_dir();        // samples/data
std::string test_data_dir();      // tests/data
std::string shared_dir();         // fixtures built once per tree (test_support.hpp)
std::string render_diff_dir();    // where render tests keep failing images
std::string user_cxx();           // how a user's program is compiled (install_test.cpp)
std::string project_version();

}  // namespace globe_test::paths
