// stb_image and tinygltf compiled into the fuzz binary from Debian's headers (the same versions as the
// libstb and libtinygltf the engine links), with the sanitizers on. The linker takes these definitions
// before the shared libraries', so the engine's calls land here and an out-of-bounds read inside a
// decoder is a report instead of silence. Only the sanitized build has this file (tests/CMakeLists.txt).
// OpenMesh ships no sources: its readers run uninstrumented (ASan still sees their allocations).
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_INCLUDE_STB_IMAGE  // included above, with its implementation
#include <tiny_gltf.h>
