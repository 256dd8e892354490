// Our warnings back after a third-party library's headers
// (third_party_begin.h).
#if defined(__clang__)
#pragma clang diagnostic pop
#elif defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
