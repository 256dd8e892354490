/* The walk for the sorted resolve (sorted_resolve.glsl) of a list store
 * whose units are single nodes, each with its own link (PLL, guarded):
 * nodes, links, relinking for the merge sort, and a pixel's list from the
 * first of its OIT_LIST_HEAD_WORDS head words (list_store.h: a GLSL uint
 * the method defines, as it sizes its heads). */
layout(std430, binding = OIT_BIND_COUNTS) readonly buffer Heads { uint heads[]; };
layout(std430, binding = OIT_BIND_FRAGS) readonly buffer Nodes { uvec4 nodes[]; };
layout(std430, binding = OIT_BIND_TOTALS) buffer Next { uint next[]; };
bool oit_list_can_relink() { return true; }
void oit_list_relink(uint i, uint n) { next[i] = n; }
bool oit_list_index(uint first, uint n) { return false; }
uint oit_list_at(uint k) { return OIT_LIST_END; }
void oit_list_store(uint i, uvec4 f) {}
uint oit_list_next(uint i) { return next[i]; }
uvec4 oit_list_load(uint i) { return nodes[i]; }
uint oit_list_first(uint p) { return heads[OIT_LIST_HEAD_WORDS * p]; }
