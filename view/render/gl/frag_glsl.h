/* The GLSL that every GL method shares, so that DFB and both capture
 * backends generate bit-identical fragments and composite them the same way
 * (shade.h is the definition; this is its mirror).
 *
 * Vertex stage: vertex pulling. The triangle soup (16-byte vertices) is bound
 * as an SSBO at binding OIT_BIND_VERTS; each vertex reads all three vertices
 * of its triangle and computes the geometric normal with the same operations
 * in the same order, so the flat normal is identical whichever vertex is
 * provoking. This keeps the 16-byte layout (no per-vertex normal) and avoids
 * a geometry shader, which costs throughput on every GPU.
 *
 * Primitive id (the tie-break key): prim = first prim + gl_PrimitiveID. The
 * first prim comes per draw through the one vertex input, a uvec2 at
 * OIT_IN_DRAW = (the draw's first vertex in the binding, the prim of its
 * first triangle), passed flat; the first vertex tells each vertex where its
 * triangle starts (tri = (gl_VertexID - x) / 3). gl_PrimitiveID restarts at
 * 0 with every command of a multi-draw (GL 4.5, 10.4: MultiDrawArraysIndirect
 * behaves as DrawArraysIndirect called once per command, and the id counts
 * from the last drawing command), so the id is the same whether a mesh is
 * drawn alone or in a group. The input is always a per-instance array
 * indexed by the draw's baseInstance (gpu_draw_record.h; core GL 4.5 has no
 * gl_DrawID), never the attribute's current value. A triangle whose
 * vertices or prim would lie outside their bindings is dropped whole
 * rather than read out of range. Both blocks are bound on every draw.
 * Why gl_PrimitiveID and not first prim + tri from the vertex stage (the
 * same number): on llvmpipe a fragment shader that does not read
 * gl_PrimitiveID rasterized a dense model twice as slowly (DFB, 99K
 * triangles at 256x256: 120 ms instead of 60; cause not found).
 *
 * Sourced draws (a streamed part file's parts, gpu_mesh.h
 * oit_gpu_mesh_set_range_sourced): the prim is each triangle's source
 * index (partfile/triangles.h), a u32 per triangle in an SSBO at
 * OIT_BIND_PRIMS. Such a draw's a_draw.y is 0x80000000 | the word index, in
 * that binding, of its first triangle's source index; the vertex stage reads
 * prims[that + tri] and passes it flat with bit 31 set, which tells the
 * fragment stage to take it as the prim instead of adding gl_PrimitiveID
 * (still read there on the other path). Prims are 31 bits either way.
 *
 * A fragment is packed into one uvec4 (16 bytes):
 *   x  the tie rule's key (shade.h): floatBitsToUint(t) of the plane's
 *      distance along the pixel's ray, low bits cleared (t > 0)
 *   y  prim (31 bits) | front << 31
 *   transparent: z = unorm16(colour.r, colour.g), w = unorm16(colour.b, alpha)
 *   translucent: z = unorm16(light, fresnel alpha)  (the colour is grey)
 *                w = base rgb as unorm 11/11/10    (the medium colour)
 * so translucency needs no second word. Sort key: (x, y & 0x7fffffff)
 * ascending; t > 0 makes its bit pattern order like the float.
 */
#ifndef OIT_RENDER_FRAG_GLSL_H
#define OIT_RENDER_FRAG_GLSL_H

#include "view/render/gl/gl_util.h"
#include "view/render/gl/program_cache.h"
#include "view/render/gl/glsl_bindings.h"
#include "view/render/gl/glsl_locations.h"
#include "view/render/gl/glsl_program.h"
#include "view/render/image/view.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Uniform locations, the vertex input and fragment outputs: glsl_locations.h. */

/* "#version 450 core", then the binding points as GLSL #defines
 * (glsl_bindings.h): every program's first string. */
extern const char oit_glsl_version[];
extern const char oit_glsl_vertex[];    /* the vertex-pulling vertex shader */
/* Its declarations and functions without its inputs, outputs and main
 * (the bindings Verts and Prims, u_view, u_proj, u_eye, u_model, u_mode,
 * u_attrs, u_colour_space, oit_world(), oit_srgb_decode(),
 * oit_tie_plane()), for the compute capture's triangle set-up, so that it
 * transforms vertices and derives the tie plane as the vertex stage does. */
extern const char oit_glsl_vertex_lib[];
/* Fragment-stage library: oit_fragment() returns the packed fragment and
 * oit_pixel_index() the pixel's linear index (GL rows, bottom first). */
extern const char oit_glsl_fragment_gen[];
/* The functions of oit_glsl_fragment_gen (and its uniforms but u_mode)
 * without its inputs, for a compute stage that generates fragments itself
 * (capture_compute.h): before it, that stage declares u_mode (as
 * oit_glsl_composite does) and as plain globals the inputs v_pos, v_rgba,
 * v_normal, v_first_prim, v_plane, v_opaque, and #defines OIT_FRAG_COORD
 * (what gl_FragCoord would be: the pixel's centre and window depth) and
 * OIT_PRIMITIVE_ID (what gl_PrimitiveID would be). */
extern const char oit_glsl_fragment_lib[];
/* oit_glsl_fragment_gen also defines oit_behind_opaque(): true when an
 * opaque depth is set (oit_glsl_set_opaque) and the fragment's window depth
 * gl_FragCoord.z is >= the depth texel under it, a sampler2D at texture
 * unit OIT_TEX_OPAQUE_DEPTH read with texelFetch at gl_FragCoord.xy +
 * u_opaque_origin; or when the opaque keys are on (keyed) and the
 * fragment's key (oit_fragment_key()) is greater than the least opaque key
 * at its pixel (opaque_keys.h). Every fragment main that counts or stores
 * fragments discards those first, so that counts and stores agree. */
/* oit_glsl_fragment_gen also defines oit_clipped(): true when a section
 * plane (oit_view.clip, clip.h) removes the fragment. Every fragment main
 * that counts, stores or blends fragments discards those first, before
 * anything else, so that counts and stores agree and every method shows
 * the same cut. */
/* Any stage: oit_state, oit_state_begin(), oit_frag_less(a, b),
 * oit_composite(inout oit_state, uvec4 frag), oit_state_final(). */
extern const char oit_glsl_composite[];
/* After oit_glsl_composite and a read-write `uvec4 frags[]` buffer:
 * oit_segment_composite(inout oit_state s, uint b, uint n) composites
 * frags[b .. b+n) front to back. Short lists sort in registers; long ones
 * are heap-sorted in place in their own segment, so no layer count is ever
 * cut off (DFB and the counted capture). */
extern const char oit_glsl_segment_composite[];
/* The longest list it sorts in registers; the scan (scan_glsl.h) counts the
 * fragments in longer ones, the counted capture weighs them. */
#define OIT_GLSL_SEGMENT_LOCAL 32

/* The per-pixel state carried across batches, oit_state, is in registers
 * (glsl/state_struct.glsl); depth peeling keeps its own buffer of these
 * (std430, 48 bytes). */
/* The capture's state buffer, `uint state_words[]`, holds a pixel in
 * oit_state_words(mode) words: transparent shading carries C, one T (its
 * channels are equal: alpha is one number) and the fragment count, 20
 * bytes; translucent all of oit_state, 48. Floats are stored as their bits,
 * so carrying the state across batches changes no bit of the result, and T
 * as its bits XOR those of 1.0, so an all-zero buffer is the state of a
 * pixel nothing has reached (C = 0, T = 1): a frame starts with a buffer
 * clear, not a pass over every pixel. After `uniform int u_mode` (1:
 * translucent), it declares oit_state and the buffer (OIT_BIND_STATE) and
 * defines oit_state_load(p), oit_state_store(p, s), oit_state_T(p). */
extern const char oit_glsl_state_io[];
#define OIT_STATE_WORDS_TRANSPARENT 5u
#define OIT_STATE_WORDS_TRANSLUCENT 12u
/* Bytes a pixel's state takes in the capture's state buffer. */
static inline unsigned oit_state_bytes(int translucent)
{
    return 4u * (translucent ? OIT_STATE_WORDS_TRANSLUCENT : OIT_STATE_WORDS_TRANSPARENT);
}

/* Sets the view and shading uniforms of a program built from the pieces
 * above (uniforms that a program does not use are skipped). */
void oit_glsl_set_view(GLuint prog, const oit_view *view);
/* The same for progs[0..n) (those not built yet, 0, are skipped: a
 * program built on first use gets its uniforms then); and their
 * early-termination threshold (`u_epsilon`, where a program has it). */
void oit_glsl_set_view_all(const GLuint *progs, int n, const oit_view *view);
void oit_glsl_set_epsilon_all(const GLuint *progs, int n, float epsilon);

/* The caller's opaque depth (liboit's oit_frame.depth_texture). A program
 * never given one (or given NULL or enabled 0) tests nothing: uniforms
 * start at 0. proj replaces u_proj, so that gl_FragCoord.z is the depth
 * the caller's projection gives; call it after oit_glsl_set_view, which
 * sets u_proj from the camera. The texture is bound by whoever draws. */
typedef struct oit_opaque_depth {
    int enabled;    /* 1: test the caller's depth (the fields below)     */
    int keyed;      /* 1: test the opaque triangles' least keys, bound at
                       OIT_TEX_OPAQUE_KEYS (opaque_keys.h); independent of
                       enabled                                           */
    int origin[2];  /* texel of frame pixel (0, 0): the viewport's corner */
    float proj[16]; /* column-major, the caller's projection */
} oit_opaque_depth;
void oit_glsl_set_opaque(GLuint prog, const oit_opaque_depth *o);
void oit_glsl_set_opaque_all(const GLuint *progs, int n, const oit_opaque_depth *o);

/* Binds fbo (no attachments needed) for fragment generation: viewport
 * w x h, no depth, stencil, blending, culling or colour writes, so the
 * fragment shader sees every fragment of every triangle, both faces. */
void oit_glsl_raster_begin(GLuint fbo, int w, int h);
/* The same for an fbo without attachments, whose default size it sets to
 * w x h first. */
void oit_glsl_raster_begin_sized(GLuint fbo, int w, int h);


#ifdef __cplusplus
}
#endif
#endif
