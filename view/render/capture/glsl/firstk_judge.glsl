/* Ahead mode's judge, one invocation, after firstk_totals.glsl, so that
 * the host reads nothing back between a pack's passes. Step 0, after pass
 * 1's resolve: pass 2's dispatch over the overflow box (none when nothing
 * overflowed). Step 1, after the allocation: the gate of the store's draw,
 * the frame's figures, and its flag when the store proved short. */
layout(local_size_x = 1) in;
uniform int u_step;
uniform uint u_cap;
void main() {
    if (u_step == 0) {
        bool any = spill_pixels != 0u;
        groups = uvec4(any ? (box[2] - box[0] + 7u) / 8u : 0u,
                       any ? (box[3] - box[1] + 7u) / 8u : 0u, 1u, 0u);
        return;
    }
    gate = spill_pixels != 0u ? 1u : 0u;
    if (spill_hi != 0u || spill_lo > u_cap) frame_short = 1u;
    need = max(need, spill_hi != 0u ? 0xffffffffu : spill_lo);
    second_pixels += spill_pixels;
    second_packs += gate;
}
