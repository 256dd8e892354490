/* A batch's bands of rows, cut on the GPU after the scan, so that the host
 * need not wait for the scan to split a batch: from row u_rows.x on, one
 * band where the rows' fragments fit the store (u_fit), else each band the
 * most rows whose fragments stay within u_target (a row that alone passes
 * it is a band of its own), at most u_bands of them. Its slot of the band
 * table (capture_counted.c's S_*): the bands (bit 31 set where rows were
 * left), the scan's high word, the first row's offset, then each band's
 * end row and the offset there. */
layout(local_size_x = 1) in;
layout(std430, binding = OIT_BIND_TOTALS) readonly buffer Scan { uint lo; uint hi; uint most; uint over; };
layout(std430, binding = OIT_BIND_OFFSETS) readonly buffer Offsets { uint offsets[]; };
layout(std430, binding = OIT_BIND_SUMS) writeonly buffer Table { uint table[]; };
uniform uint u_width;
uniform uvec2 u_rows;
uniform uint u_fit;
uniform uint u_target;
uniform uint u_slot;
uniform uint u_bands;
void main() {
    uint y = u_rows.x, n = 0u, at = u_slot + 3u;
    table[u_slot + 1u] = hi;
    table[u_slot + 2u] = offsets[y * u_width];
    uint all = offsets[u_rows.y * u_width] - offsets[y * u_width];
    uint target = hi == 0u && all <= u_fit ? u_fit : u_target;
    while (y < u_rows.y && n < u_bands) {
        uint start = offsets[y * u_width], a = y + 1u, b = u_rows.y;
        while (a < b) {
            uint m = b - (b - a) / 2u;
            if (offsets[m * u_width] - start <= target) a = m; else b = m - 1u;
        }
        table[at] = a;
        table[at + 1u] = offsets[a * u_width];
        at += 2u;
        y = a;
        n++;
    }
    table[u_slot] = y < u_rows.y ? n | 0x80000000u : n;
}
