/* Locations: every explicit uniform location, vertex input and fragment
 * output that a GLSL program shares with the C code that sets or binds it,
 * in one list, as glsl_bindings.h does for binding points. The C side gets
 * each entry as an enumerator; every program gets the same entries as GLSL
 * #defines (OIT_GLSL_LOCATIONS, which oit_glsl_version carries after the
 * bindings). Shaders write layout(location = OIT_LOC_SIZE) and C code
 * glProgramUniform2i(prog, OIT_LOC_SIZE, ...); neither spells a location
 * as a number (tests/view/render/test_glsl_bindings.sh).
 *
 * The prefix tells the kind: OIT_LOC_ uniforms, OIT_IN_ vertex inputs,
 * OIT_OUT_ fragment outputs (colour attachments). The uniforms from
 * OIT_LOC_VIEW to OIT_LOC_CLIP are the shared set that oit_glsl_set_view
 * fills in every program built on frag_glsl.h's pieces; the names after
 * them reuse a number of that set in programs that do not use the name the
 * number was first given to (the compute passes of saturation, DFB's and
 * the counted capture's band resolves), as binding points are reused. A
 * uniform without a location is set by name: a program may leave any of
 * them out, and glGetUniformLocation then gives -1, which GL ignores. */
#ifndef OIT_RENDER_GLSL_LOCATIONS_H
#define OIT_RENDER_GLSL_LOCATIONS_H

/* X(name, number): a decimal literal, as in glsl_bindings.h. */
#define OIT_GLSL_LOCATION_LIST(X)                                              \
    X(OIT_LOC_VIEW, 0)          /* mat4 */                                     \
    X(OIT_LOC_PROJ, 1)          /* mat4 */                                     \
    X(OIT_LOC_MODE, 3)          /* int: oit_shading_mode */                    \
    X(OIT_LOC_ATTRS, 4)         /* uint: OIT_ATTR_* */                         \
    X(OIT_LOC_ALPHA, 5)         /* float */                                    \
    X(OIT_LOC_DEFAULT_RGB, 6)   /* vec3 */                                     \
    X(OIT_LOC_WIDTH, 7)         /* int: frame width (pixel index) */           \
    X(OIT_LOC_SIGMA, 8)         /* float: absorption / scene_scale */          \
    X(OIT_LOC_BACKGROUND, 9)    /* vec3, negative clamped to 0 */              \
    X(OIT_LOC_K, 10)            /* int: capture slots per pixel */             \
    X(OIT_LOC_SIZE, 11)         /* ivec2: frame size */                        \
    X(OIT_LOC_RECT, 12)         /* ivec4: GL-oriented rect x0,y0,x1,y1 */      \
    X(OIT_LOC_COUNT, 13)        /* uint: element count (scans) */              \
    X(OIT_LOC_FIRST_LEVEL, 14)  /* int: scan level 0 accumulates totals */     \
    X(OIT_LOC_EYE, 15)          /* dvec3: the eye, vertices' coordinates */    \
    X(OIT_LOC_RAY, 16)          /* vec4: window coordinates to view ray */     \
    X(OIT_LOC_OPAQUE, 17)       /* int: 1 tests the opaque depth */            \
    X(OIT_LOC_OPAQUE_ORIGIN, 18) /* ivec2: texel of frame pixel (0, 0) */      \
    X(OIT_LOC_ORIGIN_MAP, 24)   /* vec4: window coordinates to ray origin */   \
    X(OIT_LOC_ORIGIN_Z, 25)     /* float: the ray origin's view-space z */     \
    X(OIT_LOC_MODEL, 26)        /* mat4: model to world */                     \
    X(OIT_LOC_CLIP_COUNT, 27)   /* int: section planes (oit_clipped) */        \
    X(OIT_LOC_CLIP, 28)         /* vec4[OIT_CLIP_MAX]: view space, 28..33 */   \
    X(OIT_LOC_TILES_SIZE, 0)    /* ivec2: saturation's frame size */           \
    X(OIT_LOC_TILE0, 1)         /* ivec3: saturation's first tile, tiles/row */ \
    X(OIT_LOC_BASE, 12)         /* uint: a band's first fragment */            \
    X(OIT_LOC_ORIGIN, 12)       /* ivec2: a rect's first pixel */              \
    X(OIT_LOC_ROWS, 13)         /* ivec2: a band's rows */                     \
    X(OIT_LOC_CAPACITY, 13)     /* uint: a store's fragments */                \
    X(OIT_IN_DRAW, 0)           /* uvec2: the draw record (frag_glsl.h) */     \
    X(OIT_OUT_COLOUR, 0)        /* the first colour attachment */              \
    X(OIT_OUT_SECOND, 1)        /* the second (WBOIT's revealage) */

#define OIT_GLSL_LOCATION_ENUM_(name, n) name = n,
enum { OIT_GLSL_LOCATION_LIST(OIT_GLSL_LOCATION_ENUM_) };

/* "#define OIT_LOC_VIEW 0\n..." for the GLSL preprocessor. */
#define OIT_GLSL_LOCATION_DEFINE_(name, n) "#define " #name " " #n "\n"
#define OIT_GLSL_LOCATIONS OIT_GLSL_LOCATION_LIST(OIT_GLSL_LOCATION_DEFINE_)

#endif
