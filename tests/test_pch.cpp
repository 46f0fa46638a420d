// An empty source: the target that makes the test executables' shared
// precompiled header (tests/CMakeLists.txt, globe_test_pch).
