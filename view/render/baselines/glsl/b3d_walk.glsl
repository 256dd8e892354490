/* B3D's walk for the sorted resolve (sorted_resolve.glsl): a walk position
 * is slot * pixels + pixel, from the pixel's last slot down. */
layout(std430, binding = OIT_BIND_COUNTS) readonly buffer Counts { uint counts[]; };
layout(rgba32ui, binding = OIT_IMG_SLOTS) uniform uimage2DArray u_slots;
layout(location = OIT_LOC_K) uniform int u_k;
uint pixels() { return uint(u_size.x * u_size.y); }
uint oit_list_first(uint p) {
    uint n = min(counts[p], uint(u_k));
    return n == 0u ? OIT_LIST_END : (n - 1u) * pixels() + p;
}
uint oit_list_next(uint i) { return i >= pixels() ? i - pixels() : OIT_LIST_END; }
uvec4 oit_list_load(uint i) {
    uint p = i % pixels();
    return imageLoad(u_slots, ivec3(int(p % uint(u_size.x)), int(p / uint(u_size.x)),
                                    int(i / pixels())));
}
/* An array: the k-th of the walk is slot n-1-k, so a heap sort sorts
 * it in place. */
bool oit_list_can_relink() { return false; }
void oit_list_relink(uint i, uint n) {}
uint oit_first;
bool oit_list_index(uint first, uint n) { oit_first = first; return true; }
uint oit_list_at(uint k) { return oit_first - k * pixels(); }
void oit_list_store(uint i, uvec4 f) {
    uint p = i % pixels();
    imageStore(u_slots, ivec3(int(p % uint(u_size.x)), int(p / uint(u_size.x)),
                              int(i / pixels())), f);
}
