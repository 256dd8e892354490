/* The fills' slots: written here, read by resolve.glsl's. */
layout(std430, binding = OIT_BIND_FRAGS) writeonly buffer Slots { uvec4 slots[]; };
