/* Shared GLSL (frag_glsl.h). Every line of shading and compositing here
 * mirrors shade.h / shade.c; keep them in step. */
#include "render/gl/frag_glsl.h"

#include "render/gl/gpu_mesh.h"
#include "render/image/shade.h"

#include <math.h>

const char oit_glsl_version[] = "#version 450 core\n" OIT_GLSL_BINDINGS;

#define OIT_GLSL_TIE_PLANE \
    /* The tie rule's plane (shade.h, oit_depth_plane): in double from the \
     * float vertices, rounded to float, so that every triangle of one plane \
     * carries the same numbers; the normal is then rotated into view space. */ \
    "vec4 oit_tie_plane(vec3 p0, vec3 p1, vec3 p2) {\n" \
    "    dvec3 q0 = dvec3(p0);\n" \
    "    dvec3 nn = cross(dvec3(p1) - q0, dvec3(p2) - q0);\n" \
    "    double len = sqrt(dot(nn, nn));\n" \
    "    if (!(len > 0.0lf)) return vec4(0.0);\n" \
    "    dvec3 nu = nn / len;\n" \
    "    vec3 n = vec3(nu);\n" \
    /* Rotated term by term, in shade.c's order (reference.c key_hits): \
     * precise forbids the compiler to fuse or reorder (GLSL 4.50 4.7.1). */ \
    "    precise vec3 r;\n" \
    "    r.x = u_view[0].x * n.x + u_view[1].x * n.y + u_view[2].x * n.z;\n" \
    "    r.y = u_view[0].y * n.x + u_view[1].y * n.y + u_view[2].y * n.z;\n" \
    "    r.z = u_view[0].z * n.x + u_view[1].z * n.y + u_view[2].z * n.z;\n" \
    "    return vec4(r, float(dot(nu, q0 - u_eye)));\n" \
    "}\n" \

/* What the vertex stage and the compute capture's triangle set-up share
 * (frag_glsl.h, oit_glsl_vertex_lib): the bindings, the transforms and the
 * tie rule's plane. */
#define OIT_GLSL_VERTEX_LIB \
    "layout(std430, binding = OIT_BIND_VERTS) readonly buffer Verts { uvec4 verts[]; };\n" \
    "layout(location = 0) uniform mat4 u_view;\n" \
    "layout(location = 1) uniform mat4 u_proj;\n" \
    /* Source indices of sourced draws (frag_glsl.h, "Primitive id"). */ \
    "layout(std430, binding = OIT_BIND_PRIMS) readonly buffer Prims { uint prims[]; };\n" \
    "layout(location = 15) uniform dvec3 u_eye;\n" \
    /* Model to world (oit_view.model; the identity changes no bit). */ \
    "layout(location = 26) uniform mat4 u_model;\n" \
    "vec3 oit_world(uvec4 v) { return (u_model * vec4(uintBitsToFloat(v.xyz), 1.0)).xyz; }\n" \
    "layout(location = 3) uniform int u_mode;\n" \
    "layout(location = 4) uniform uint u_attrs;\n" \
    /* oit_shading.colour_space (shade.h, "Colour space"); set by name. */ \
    "uniform int u_colour_space;\n" \
    OIT_GLSL_SRGB_FUNCS \
    OIT_GLSL_TIE_PLANE

const char oit_glsl_vertex_lib[] = OIT_GLSL_VERTEX_LIB;

const char oit_glsl_vertex[] =
    OIT_GLSL_VERTEX_LIB
    "layout(location = 0) in uvec2 a_draw;\n"
    "out vec3 v_pos;\n"
    /* The opaque pre-pass and the captures are different programs that
     * must compute the same key from it (oit_fragment_key). */
    "invariant v_pos;\n"
    "out vec4 v_rgba;\n"
    "flat out vec3 v_normal;\n"
    "flat out uint v_first_prim;\n"
    "flat out vec4 v_plane;\n"
    /* Opaque triangle (shade.h, "Opaque triangles"): every vertex reads
     * all three alphas, so the flat value is the same whichever provokes. */
    "flat out uint v_opaque;\n"
    "invariant gl_Position;\n"
    /* Whether the triangle's three vertices and its prim lie in their
     * bindings. A draw's own vertices always do; the test keeps a wrong
     * record or binding from reading out of range, which GL leaves
     * undefined (robust drivers return 0: a collapsed triangle). Every
     * vertex of a triangle computes the same answer. */
    "bool oit_in_range(uint vid, uint v0, uint prim_word, bool sourced) {\n"
    "    uint nv = uint(verts.length());\n"
    "    return vid >= a_draw.x && v0 + 2u < nv &&\n"
    "           (!sourced || prim_word < uint(prims.length()));\n"
    "}\n"
    "void main() {\n"
    /* The draw's triangles start at vertex a_draw.x of the binding. */
    "    uint vid = uint(gl_VertexID);\n"
    "    uint tri = (vid - a_draw.x) / 3u;\n"
    "    uint v0 = a_draw.x + tri * 3u;\n"
    "    bool sourced = (a_draw.y & 0x80000000u) != 0u;\n"
    "    uint prim_word = (a_draw.y & 0x7fffffffu) + tri;\n"
    "    if (!oit_in_range(vid, v0, prim_word, sourced)) {\n"
    /* Outside the clip volume: the triangle is dropped whole. */
    "        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);\n"
    "        v_pos = vec3(0.0); v_rgba = vec4(0.0); v_normal = vec3(0.0);\n"
    "        v_first_prim = 0u; v_plane = vec4(0.0); v_opaque = 0u;\n"
    "        return;\n"
    "    }\n"
    "    vec3 p0 = oit_world(verts[v0]);\n"
    "    vec3 p1 = oit_world(verts[v0 + 1u]);\n"
    "    vec3 p2 = oit_world(verts[v0 + 2u]);\n"
    "    uvec4 me = verts[vid];\n"
    /* Geometric normal in world space, then rotated: dot products with
     * view-space vectors equal the world-space ones of shade.h. */
    "    v_normal = mat3(u_view) * cross(p1 - p0, p2 - p0);\n"
    "    v_first_prim = sourced ? prims[prim_word] | 0x80000000u : a_draw.y;\n"
    "    v_plane = oit_tie_plane(p0, p1, p2);\n"
    "    v_opaque = u_mode == 0 && (u_attrs & 2u) != 0u &&\n"
    "               (verts[v0].w & verts[v0 + 1u].w & verts[v0 + 2u].w) >> 24 == 255u ? 1u : 0u;\n"
    "    vec4 vp = u_view * vec4(oit_world(me), 1.0);\n"
    "    v_pos = vp.xyz;\n"
    "    v_rgba = unpackUnorm4x8(me.w);\n"
    "    if (u_colour_space == 1) v_rgba.rgb = oit_srgb_decode(v_rgba.rgb);\n"
    "    gl_Position = u_proj * vp;\n"
    "}\n";

/* The caller's opaque depth and the opaque triangles' least keys
 * (frag_glsl.h, oit_behind_opaque). A fragment at the least key is kept:
 * the opaque one itself, and coplanar ones the tie rule orders. */
#define OIT_GLSL_OPAQUE                                                          \
    "layout(binding = OIT_TEX_OPAQUE_DEPTH) uniform sampler2D u_opaque_depth;\n" \
    "layout(binding = OIT_TEX_OPAQUE_KEYS) uniform sampler2D u_opaque_keys;\n"   \
    "layout(location = 17) uniform int u_opaque;\n"                              \
    "layout(location = 18) uniform ivec2 u_opaque_origin;\n"                     \
    "uniform int u_opaque_keyed;\n"                                              \
    "bool oit_behind_opaque() {\n"                                               \
    "    if (u_opaque_keyed != 0 && oit_fragment_key() >\n"                      \
    "        floatBitsToUint(texelFetch(u_opaque_keys, ivec2(OIT_FRAG_COORD.xy), 0).r))\n" \
    "        return true;\n"                                                     \
    "    if (u_opaque == 0) return false;\n"                                     \
    "    ivec2 q = ivec2(OIT_FRAG_COORD.xy) + u_opaque_origin;\n"                  \
    "    return OIT_FRAG_COORD.z >= texelFetch(u_opaque_depth, q, 0).r;\n"         \
    "}\n"

/* The fragment library (frag_glsl.h) over OIT_FRAG_COORD and
 * OIT_PRIMITIVE_ID, which the fragment stage defines as gl_FragCoord and
 * gl_PrimitiveID and the compute capture as its own per-pixel values. */
#define OIT_GLSL_FRAGMENT_LIB \
    "layout(location = 16) uniform vec4 u_ray;\n" \
    "layout(location = 24) uniform vec4 u_org;\n" \
    "layout(location = 25) uniform float u_org_z;\n" \
    /* The view-space origin of the pixel centre's ray (view.h, \
     * oit_view_origin_map): the eye, 0, for a perspective; the point of the \
     * near plane for an orthographic view. */ \
    "vec3 oit_ray_origin() {\n" \
    "    vec2 c = floor(OIT_FRAG_COORD.xy) + 0.5;\n" \
    "    precise vec3 o = vec3(c.x * u_org.x + u_org.z, c.y * u_org.y + u_org.w, u_org_z);\n" \
    "    return o;\n" \
    "}\n" \
    "uint oit_pixel_index() {\n" \
    "    return uint(OIT_FRAG_COORD.y) * uint(u_width) + uint(OIT_FRAG_COORD.x);\n" \
    "}\n" \
    "uint oit_pack_111110(vec3 c) {\n" \
    "    uvec3 q = uvec3(round(clamp(c, 0.0, 1.0) * vec3(2047.0, 2047.0, 1023.0)));\n" \
    "    return q.x | (q.y << 11) | (q.z << 22);\n" \
    "}\n" \
    /* The tie rule's key (shade.h, oit_depth_key): t of the triangle's \
     * plane along the pixel centre's unit ray from its origin o, which every \
     * triangle at this pixel shares, with the low mantissa bits cleared: \
     * (d - n . o) / (n . dir), d - 0 = d for a perspective (o = 0); an \
     * orthographic ray map is 0, so dir = (0, 0, -1). */ \
    /* floor + 0.5: the centre even where a multisampled target lets \
     * OIT_FRAG_COORD lie anywhere in the pixel. */ \
    /* Every operation is written out in the order view.c \
     * (oit_view_pixel_ray) and shade.c (oit_depth_key) use, and precise: \
     * a GPU compiler may otherwise fuse multiply-adds or reassociate \
     * (GLSL 4.50 4.7.1), so that faces coplanar up to rounding get keys on \
     * either side of a grid line than the CPU reference's. Division and \
     * sqrt stay within GLSL's stated ulps of the CPU's. */ \
    "uint oit_depth_key(float t_interp) {\n" \
    "    vec2 c = floor(OIT_FRAG_COORD.xy) + 0.5;\n" \
    "    precise vec3 dir = vec3(c.x * u_ray.x + u_ray.z, c.y * u_ray.y + u_ray.w, -1.0);\n" \
    "    precise float len2 = dir.x * dir.x + dir.y * dir.y + dir.z * dir.z;\n" \
    "    precise float inv = 1.0 / sqrt(len2);\n" \
    "    dir = dir * inv;\n" \
    "    vec3 n = v_plane.xyz;\n" \
    "    precise float nd = n.x * dir.x + n.y * dir.y + n.z * dir.z;\n" \
    "    float t = t_interp;\n" \
    "    if (abs(nd) >= " OIT_GLSL_STR(OIT_DEPTH_GRAZING) ") {\n" \
    "        vec3 o = oit_ray_origin();\n" \
    "        precise float no = n.x * o.x + n.y * o.y + n.z * o.z;\n" \
    "        precise float tp = (v_plane.w - no) / nd;\n" \
    "        if (tp > 0.0 && !isinf(tp)) t = tp;\n" \
    "    }\n" \
    "    return floatBitsToUint(t) & ~" OIT_GLSL_STR(OIT_DEPTH_KEY_MASK) "u;\n" \
    "}\n" \
    /* Section planes (clip.h): u_clip holds them in view space \
     * (oit_clip_eye). The point tested is where the pixel centre's ray \
     * meets the triangle's plane, computed as oit_depth_key computes its t \
     * and as reference.c does, not the interpolated position, which a \
     * multisampled capture may take anywhere in the pixel; a grazing \
     * plane falls back to the interpolated distance along the same ray. */ \
    "layout(location = 27) uniform int u_clip_count;\n" \
    "layout(location = 28) uniform vec4 u_clip[" OIT_GLSL_STR(OIT_CLIP_MAX) "];\n" \
    "bool oit_clipped() {\n" \
    "    if (u_clip_count == 0) return false;\n" \
    "    vec2 c = floor(OIT_FRAG_COORD.xy) + 0.5;\n" \
    "    precise vec3 dir = vec3(c.x * u_ray.x + u_ray.z, c.y * u_ray.y + u_ray.w, -1.0);\n" \
    "    precise float len2 = dir.x * dir.x + dir.y * dir.y + dir.z * dir.z;\n" \
    "    precise float inv = 1.0 / sqrt(len2);\n" \
    "    dir = dir * inv;\n" \
    "    vec3 o = oit_ray_origin();\n" \
    "    vec3 n = v_plane.xyz;\n" \
    "    precise float nd = n.x * dir.x + n.y * dir.y + n.z * dir.z;\n" \
    "    float t = length(v_pos - o);\n" \
    "    if (abs(nd) >= " OIT_GLSL_STR(OIT_DEPTH_GRAZING) ") {\n" \
    "        precise float no = n.x * o.x + n.y * o.y + n.z * o.z;\n" \
    "        precise float tp = (v_plane.w - no) / nd;\n" \
    "        if (tp > 0.0 && !isinf(tp)) t = tp;\n" \
    "    }\n" \
    "    precise vec3 p = o + dir * t;\n" \
    "    for (int i = 0; i < u_clip_count; i++) {\n" \
    "        vec4 q = u_clip[i];\n" \
    "        precise float s = q.x * p.x + q.y * p.y + q.z * p.z + q.w;\n" \
    "        if (s < 0.0) return true;\n" \
    "    }\n" \
    "    return false;\n" \
    "}\n" \
    /* One expression for the key, so that the opaque pre-pass and the \
     * captures compute the same bits. */ \
    "uint oit_fragment_key() {\n" \
    "    precise vec3 rel = v_pos - oit_ray_origin();\n" \
    "    precise float t_interp = length(rel);\n" \
    "    return oit_depth_key(t_interp);\n" \
    "}\n" \
    OIT_GLSL_OPAQUE \
    "uvec4 oit_fragment() {\n" \
    "    vec3 rel = v_pos - oit_ray_origin();\n" \
    "    float t_interp = length(rel);\n" \
    "    vec3 v = -rel / t_interp;\n" \
    /* Degenerate triangles shade as edge-on, like shade.c. */ \
    "    float nn = dot(v_normal, v_normal);\n" \
    "    float nv = nn > 0.0 ? dot(v_normal * inversesqrt(nn), v) : 0.0;\n" \
    "    float ndv = abs(nv);\n" \
    "    float light = 0.3 + 0.7 * ndv;\n" \
    "    vec3 base = (u_attrs & 1u) != 0u ? v_rgba.rgb : u_default_rgb;\n" \
    "    float a = v_opaque != 0u ? 1.0 : (u_attrs & 2u) != 0u ? v_rgba.a : u_alpha;\n" \
    "    uint prim = (v_first_prim & 0x80000000u) != 0u ? v_first_prim\n" \
    "                                                   : v_first_prim + uint(OIT_PRIMITIVE_ID);\n" \
    "    uvec4 f;\n" \
    "    f.x = oit_fragment_key();\n" \
    "    f.y = (prim & 0x7fffffffu) | (nv > 0.0 ? 0x80000000u : 0u);\n" \
    "    if (u_mode == 1) {\n" \
    "        float fresnel = 0.04 + 0.96 * pow(1.0 - ndv, 5.0);\n" \
    "        f.z = packUnorm2x16(vec2(light, fresnel));\n" \
    "        f.w = oit_pack_111110(base);\n" \
    "    } else {\n" \
    "        vec3 c = base * light;\n" \
    "        f.z = packUnorm2x16(c.rg);\n" \
    "        f.w = packUnorm2x16(vec2(c.b, a));\n" \
    "    }\n" \
    "    return f;\n" \
    "}\n" \

#define OIT_GLSL_FRAGMENT_UNIFORMS \
    "layout(location = 4) uniform uint u_attrs;\n" \
    "layout(location = 5) uniform float u_alpha;\n" \
    "layout(location = 6) uniform vec3 u_default_rgb;\n" \
    "layout(location = 7) uniform int u_width;\n"

const char oit_glsl_fragment_gen[] =
    "layout(location = 3) uniform int u_mode;\n"
    OIT_GLSL_FRAGMENT_UNIFORMS
    "in vec3 v_pos;\n"
    "in vec4 v_rgba;\n"
    "flat in vec3 v_normal;\n"
    "flat in uint v_first_prim;\n"
    "flat in vec4 v_plane;\n"
    "flat in uint v_opaque;\n"
    "#define OIT_FRAG_COORD gl_FragCoord\n"
    "#define OIT_PRIMITIVE_ID gl_PrimitiveID\n"
    OIT_GLSL_FRAGMENT_LIB;

const char oit_glsl_fragment_lib[] = OIT_GLSL_FRAGMENT_UNIFORMS OIT_GLSL_FRAGMENT_LIB;

/* The XOR-ed T is only ever held as bits: as a float it may be denormal,
 * which a driver is free to flush. */
const char oit_glsl_state_io[] =
    OIT_GLSL_STATE_STRUCT
    "layout(std430, binding = OIT_BIND_STATE) buffer State { uint state_words[]; };\n"
    "const uint OIT_ONE_BITS = 0x3f800000u;\n"
    "uint oit_state_base(uint p) { return p * (u_mode == 1 ? 12u : 5u); }\n"
    "uvec3 oit_state_bits3(uint w) {\n"
    "    return uvec3(state_words[w], state_words[w + 1u], state_words[w + 2u]);\n"
    "}\n"
    "void oit_state_put3(uint w, uvec3 b) {\n"
    "    state_words[w] = b.x; state_words[w + 1u] = b.y; state_words[w + 2u] = b.z;\n"
    "}\n"
    "vec3 oit_state_T(uint p) {\n"
    "    uint w = oit_state_base(p);\n"
    "    if (u_mode != 1) return vec3(uintBitsToFloat(state_words[w + 3u] ^ OIT_ONE_BITS));\n"
    "    return uintBitsToFloat(oit_state_bits3(w + 4u) ^ uvec3(OIT_ONE_BITS));\n"
    "}\n"
    "oit_state oit_state_load(uint p) {\n"
    "    uint w = oit_state_base(p);\n"
    "    oit_state s;\n"
    "    s.C = uintBitsToFloat(oit_state_bits3(w));\n"
    "    s.T = oit_state_T(p);\n"
    "    if (u_mode != 1) {\n"
    "        s.t_prev = 0.0; s.nest = 0; s.medium = vec3(0.0); s.nfrag = state_words[w + 4u];\n"
    "        return s;\n"
    "    }\n"
    "    s.t_prev = uintBitsToFloat(state_words[w + 3u]);\n"
    "    s.nest = int(state_words[w + 7u]);\n"
    "    s.medium = uintBitsToFloat(oit_state_bits3(w + 8u));\n"
    "    s.nfrag = state_words[w + 11u];\n"
    "    return s;\n"
    "}\n"
    "void oit_state_store(uint p, oit_state s) {\n"
    "    uint w = oit_state_base(p);\n"
    "    oit_state_put3(w, floatBitsToUint(s.C));\n"
    "    if (u_mode != 1) {\n"
    "        state_words[w + 3u] = floatBitsToUint(s.T.r) ^ OIT_ONE_BITS;\n"
    "        state_words[w + 4u] = s.nfrag;\n"
    "        return;\n"
    "    }\n"
    "    state_words[w + 3u] = floatBitsToUint(s.t_prev);\n"
    "    oit_state_put3(w + 4u, floatBitsToUint(s.T) ^ uvec3(OIT_ONE_BITS));\n"
    "    state_words[w + 7u] = uint(s.nest);\n"
    "    oit_state_put3(w + 8u, floatBitsToUint(s.medium));\n"
    "    state_words[w + 11u] = s.nfrag;\n"
    "}\n";

const char oit_glsl_composite[] =
    "layout(location = 3) uniform int u_mode;\n"
    "uniform int u_colour_space;\n"
    OIT_GLSL_SRGB_FUNCS
    "layout(location = 8) uniform float u_sigma;\n"
    "layout(location = 9) uniform vec3 u_background;\n"
    OIT_GLSL_OUTPUT
    OIT_GLSL_STATE_STRUCT
    "oit_state oit_state_begin() {\n"
    "    return oit_state(vec3(0.0), 0.0, vec3(1.0), 0, vec3(0.0), 0u);\n"
    "}\n"
    "bool oit_frag_less(uvec4 a, uvec4 b) {\n"
    "    return a.x < b.x || (a.x == b.x && (a.y & 0x7fffffffu) < (b.y & 0x7fffffffu));\n"
    "}\n"
    /* One insertion-sort step: x joins the sorted f[0..i). A while loop with
     * a break, because llvmpipe miscompiles the for-loop form whose
     * condition calls oit_frag_less. */
    "#define OIT_SORTED_INSERT(f, i, x) { uint j_ = (i); while (j_ > 0u) { "
    "if (!oit_frag_less((x), f[j_ - 1u])) break; f[j_] = f[j_ - 1u]; j_--; } f[j_] = (x); }\n"
    "vec3 oit_unpack_111110(uint w) {\n"
    "    return vec3(float(w & 0x7ffu) / 2047.0, float((w >> 11) & 0x7ffu) / 2047.0,\n"
    "                float(w >> 22) / 1023.0);\n"
    "}\n"
    "void oit_composite(inout oit_state s, uvec4 f) {\n"
    "    float t = uintBitsToFloat(f.x);\n"
    "    bool translucent = u_mode == 1;\n"
    "    vec3 colour; float a;\n"
    "    if (translucent) {\n"
    "        vec2 la = unpackUnorm2x16(f.z);\n"
    "        colour = vec3(la.x); a = la.y;\n"
    "        if (s.nest > 0)\n"
    "            s.T *= exp(-u_sigma * (vec3(1.0) - s.medium) * (t - s.t_prev));\n"
    "    } else {\n"
    "        vec2 rg = unpackUnorm2x16(f.z), ba = unpackUnorm2x16(f.w);\n"
    "        colour = vec3(rg, ba.x); a = ba.y;\n"
    "    }\n"
    "    s.C += s.T * a * colour;\n"
    "    s.T *= 1.0 - a;\n"
    "    if (translucent) {\n"
    "        if ((f.y & 0x80000000u) != 0u) { s.nest += 1; s.medium = oit_unpack_111110(f.w); }\n"
    "        else s.nest = max(s.nest - 1, 0);\n"
    "        s.t_prev = t;\n"
    "    }\n"
    "}\n"
    "vec4 oit_state_final(oit_state s) {\n"
    "    return vec4(oit_output(s.C + s.T * oit_background()), 1.0);\n"
    "}\n";

/* Uniforms are set by name: a location a program does not use is -1, which
 * GL ignores, whereas an unused explicit location is an error. */
/* src = oit_glsl_version, then 'lead' (when set), then parts up to their
 * first NULL, then NULL. */
static void stage_sources(const char *lead, const char *const *parts, const char **src)
{
    int n = 0;
    src[n++] = oit_glsl_version;
    if (lead)
        src[n++] = lead;
    for (int i = 0; i < OIT_GLSL_PARTS_MAX && parts[i]; i++)
        src[n++] = parts[i];
    src[n] = NULL;
}

oit_status oit_glsl_programs_build(oit_program_cache *pc, const oit_glsl_program *table, int n, GLuint *out,
                                   oit_error *err)
{
    static const char *const vs[] = {oit_glsl_version, oit_glsl_vertex, NULL};
    oit_status s = OIT_OK;
    for (int i = 0; i < n && s == OIT_OK; i++) {
        const char *src[OIT_GLSL_PARTS_MAX + 3];
        if (table[i].fs[0]) {
            stage_sources(oit_glsl_fragment_gen, table[i].fs, src);
            s = oit_program_cache_build(pc, table[i].what, vs, src, NULL, &out[i], err);
        } else {
            stage_sources(NULL, table[i].cs, src);
            s = oit_program_cache_build(pc, table[i].what, NULL, NULL, src, &out[i], err);
        }
    }
    return s;
}

void oit_glsl_programs_delete(GLuint *progs, int n)
{
    for (int i = 0; i < n; i++) {
        glDeleteProgram(progs[i]);
        progs[i] = 0;
    }
}

static GLint loc(GLuint prog, const char *name)
{
    return glGetUniformLocation(prog, name);
}

void oit_glsl_set_view(GLuint prog, const oit_view *view)
{
    float m[16];
    const oit_shading *s = &view->shading;
    oit_camera_view_matrix(&view->camera, m);
    glProgramUniformMatrix4fv(prog, loc(prog, "u_view"), 1, GL_FALSE, m);
    oit_camera_proj_matrix(&view->camera, (float)view->width / (float)view->height, m);
    glProgramUniformMatrix4fv(prog, loc(prog, "u_proj"), 1, GL_FALSE, m);
    glProgramUniform1i(prog, loc(prog, "u_mode"), (GLint)s->mode);
    glProgramUniform1i(prog, loc(prog, "u_colour_space"), (GLint)s->colour_space);
    glProgramUniform1ui(prog, loc(prog, "u_attrs"), oit_shading_attrs(s));
    glProgramUniform1f(prog, loc(prog, "u_alpha"), s->alpha);
    float drgb[3];
    for (int c = 0; c < 3; c++)
        drgb[c] = s->colour_space == OIT_COLOUR_LINEAR ? (float)oit_srgb_decode(s->default_rgb[c])
                                                       : s->default_rgb[c];
    glProgramUniform3fv(prog, loc(prog, "u_default_rgb"), 1, drgb);
    glProgramUniform1i(prog, loc(prog, "u_width"), view->width);
    float sigma = s->scene_scale > 0.0f ? s->absorption / s->scene_scale : 0.0f;
    glProgramUniform1f(prog, loc(prog, "u_sigma"), sigma);
    float bg[3];
    for (int c = 0; c < 3; c++)
        bg[c] = fmaxf(s->background[c], 0.0f);
    glProgramUniform3fv(prog, loc(prog, "u_background"), 1, bg);
    glProgramUniform2i(prog, loc(prog, "u_size"), view->width, view->height);
    const float *e = view->camera.eye;
    glProgramUniform3d(prog, loc(prog, "u_eye"), e[0], e[1], e[2]);
    float ray[4];
    oit_view_ray_map(view, ray);
    glProgramUniform4fv(prog, loc(prog, "u_ray"), 1, ray);
    float org[4], org_z;
    oit_view_origin_map(view, org, &org_z);
    glProgramUniform4fv(prog, loc(prog, "u_org"), 1, org);
    double md[16];
    oit_view_model(view, md);
    for (int i = 0; i < 16; i++)
        m[i] = (float)md[i];
    glProgramUniformMatrix4fv(prog, loc(prog, "u_model"), 1, GL_FALSE, m);
    glProgramUniform1f(prog, loc(prog, "u_org_z"), org_z);
    float clip[OIT_CLIP_MAX][4];
    oit_camera_view_matrix(&view->camera, m);
    oit_clip_eye(&view->clip, m, clip);
    glProgramUniform1i(prog, loc(prog, "u_clip_count"), view->clip.count);
    glProgramUniform4fv(prog, loc(prog, "u_clip"), OIT_CLIP_MAX, &clip[0][0]);
}

void oit_glsl_set_opaque(GLuint prog, const oit_opaque_depth *o)
{
    int on = o && o->enabled;
    glProgramUniform1i(prog, loc(prog, "u_opaque"), on);
    glProgramUniform1i(prog, loc(prog, "u_opaque_keyed"), o && o->keyed);
    glProgramUniform2i(prog, loc(prog, "u_opaque_origin"), on ? o->origin[0] : 0,
                       on ? o->origin[1] : 0);
    if (on)
        glProgramUniformMatrix4fv(prog, loc(prog, "u_proj"), 1, GL_FALSE, o->proj);
}

void oit_glsl_set_opaque_all(const GLuint *progs, int n, const oit_opaque_depth *o)
{
    for (int i = 0; i < n; i++)
        if (progs[i])
            oit_glsl_set_opaque(progs[i], o);
}

void oit_glsl_set_view_all(const GLuint *progs, int n, const oit_view *view)
{
    for (int i = 0; i < n; i++)
        if (progs[i])
            oit_glsl_set_view(progs[i], view);
}

void oit_glsl_set_epsilon_all(const GLuint *progs, int n, float epsilon)
{
    for (int i = 0; i < n; i++)
        if (progs[i])
            glProgramUniform1f(progs[i], loc(progs[i], "u_epsilon"), epsilon);
}

void oit_glsl_raster_begin(GLuint fbo, int w, int h)
{
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, w, h);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_MULTISAMPLE);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthMask(GL_FALSE);
}

void oit_glsl_raster_begin_sized(GLuint fbo, int w, int h)
{
    glNamedFramebufferParameteri(fbo, GL_FRAMEBUFFER_DEFAULT_WIDTH, w);
    glNamedFramebufferParameteri(fbo, GL_FRAMEBUFFER_DEFAULT_HEIGHT, h);
    oit_glsl_raster_begin(fbo, w, h);
}

const char oit_glsl_segment_composite[] =
    "#define OIT_SEGMENT_LOCAL " OIT_GLSL_STR(OIT_GLSL_SEGMENT_LOCAL) "u\n"
    "void oit_segment_sift(uint b, uint root, uint n) {\n"
    "    for (;;) {\n"
    "        uint child = 2u * root + 1u;\n"
    "        if (child >= n) return;\n"
    "        if (child + 1u < n && oit_frag_less(frags[b + child], frags[b + child + 1u])) child++;\n"
    "        if (!oit_frag_less(frags[b + root], frags[b + child])) return;\n"
    "        uvec4 tmp = frags[b + root]; frags[b + root] = frags[b + child]; frags[b + child] = tmp;\n"
    "        root = child;\n"
    "    }\n"
    "}\n"
    "void oit_segment_composite(inout oit_state s, uint b, uint n) {\n"
    "    if (n <= OIT_SEGMENT_LOCAL) {\n"
    "        uvec4 f[OIT_SEGMENT_LOCAL];\n"
    "        for (uint i = 0u; i < n; i++) {\n"
    "            uvec4 x = frags[b + i];\n"
    "            OIT_SORTED_INSERT(f, i, x)\n"
    "        }\n"
    "        for (uint i = 0u; i < n; i++) oit_composite(s, f[i]);\n"
    "        return;\n"
    "    }\n"
    "    for (uint i = n / 2u; i > 0u; i--) oit_segment_sift(b, i - 1u, n);\n"
    "    for (uint e = n - 1u; e > 0u; e--) {\n"
    "        uvec4 tmp = frags[b]; frags[b] = frags[b + e]; frags[b + e] = tmp;\n"
    "        oit_segment_sift(b, 0u, e);\n"
    "    }\n"
    "    for (uint i = 0u; i < n; i++) oit_composite(s, frags[b + i]);\n"
    "}\n";

void oit_glsl_draw_scissored(GLuint fbo, int w, int h, GLuint prog, struct oit_gpu_draws *draws,
                             const struct oit_gpu_mesh *const *meshes, int n, const int r[4])
{
    oit_glsl_raster_begin(fbo, w, h);
    glEnable(GL_SCISSOR_TEST);
    glScissor(r[0], r[1], r[2] - r[0], r[3] - r[1]);
    glUseProgram(prog);
    oit_gpu_mesh_draw_many(draws, meshes, n);
    glDisable(GL_SCISSOR_TEST);
}

void oit_glsl_draw_scissored_gated(GLuint fbo, int w, int h, GLuint prog,
                                   struct oit_gpu_draws *draws,
                                   const struct oit_gpu_mesh *const *meshes, int n,
                                   const int r[4], GLuint gate, unsigned word)
{
    oit_glsl_raster_begin(fbo, w, h);
    glEnable(GL_SCISSOR_TEST);
    glScissor(r[0], r[1], r[2] - r[0], r[3] - r[1]);
    glUseProgram(prog);
    oit_gpu_mesh_draw_many_gated(draws, meshes, n, gate, word);
    glDisable(GL_SCISSOR_TEST);
}
