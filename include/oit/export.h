/* OIT_API marks the functions liboit.so exports. The project builds with
 * hidden visibility (CMake's visibility presets), so a function without it
 * stays inside the library whatever its name; the library's version script
 * then keeps anything else (a dependency's symbols) local too. */
#ifndef OIT_EXPORT_H
#define OIT_EXPORT_H

#if defined(__GNUC__)
#define OIT_API __attribute__((visibility("default")))
#else
#define OIT_API
#endif

#endif
