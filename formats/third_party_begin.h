// Included before a third-party library's headers (tinygltf, Draco), and
// third_party_end.h after them: their warnings are not ours to fix, and
// under -Wall -Wextra they would bury ours. No include guard: each block of
// such headers includes the pair once.
#if defined(__clang__)
#pragma clang diagnostic push
#pragma clang diagnostic ignored "-Weverything"
#elif defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wall"
#pragma GCC diagnostic ignored "-Wextra"
#endif
