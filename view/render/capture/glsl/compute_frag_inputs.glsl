/* The fragment library's inputs (oit_glsl_fragment_lib follows), set per
 * (pixel, triangle) by compute_tiles.glsl's cs_fragment_at: the compute
 * capture shades with the raster captures' own functions, not copies. */
vec3 v_pos; vec4 v_rgba; vec3 v_normal; uint v_first_prim; vec4 v_plane; uint v_opaque;
vec4 cs_frag_coord;
#define OIT_FRAG_COORD cs_frag_coord
#define OIT_PRIMITIVE_ID 0u
