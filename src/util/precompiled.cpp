// The object that owns the library's precompiled header (src/CMakeLists.txt,
// cmake/library_pch.cmake): every layer's library reuses the header built for it. It defines
// nothing.
