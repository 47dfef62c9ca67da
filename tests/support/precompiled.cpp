// The executable that owns the tests' precompiled header (tests/CMakeLists.txt): every test
// executable reuses the header built for it. It has no tests and CTest does not run it.
