/* DFB's resolve to colours, after dfb_resolve.glsl: the frame's rgba. */
layout(std430, binding = OIT_BIND_OUT) writeonly buffer Out { vec4 out_rgba[]; };
