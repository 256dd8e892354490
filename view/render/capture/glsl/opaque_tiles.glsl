/* The largest opaque depth of each OIT_OPAQUE_TILE-square tile of the view
 * (opaque_tiles.h), so that the stream can skip a part behind every tile
 * its rectangle touches without drawing it. */
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = OIT_TEX_OPAQUE_DEPTH) uniform sampler2D u_opaque_depth;
layout(std430, binding = OIT_BIND_OPAQUE_TILES) writeonly buffer Tiles { float tile_max[]; };
uniform ivec2 u_size;
uniform ivec2 u_origin;
uniform ivec2 u_tiles;
void main() {
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (t.x >= u_tiles.x || t.y >= u_tiles.y) return;
    ivec2 p0 = t * OIT_OPAQUE_TILE;
    ivec2 p1 = min(p0 + OIT_OPAQUE_TILE, u_size);
    float m = 0.0;
    for (int y = p0.y; y < p1.y; y++)
        for (int x = p0.x; x < p1.x; x++)
            m = max(m, texelFetch(u_opaque_depth, ivec2(x, y) + u_origin, 0).r);
    tile_max[t.y * u_tiles.x + t.x] = m;
}
