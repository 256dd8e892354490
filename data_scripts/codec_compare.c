/* The part codecs against alternatives, over one part file: for every part,
 * the bytes of each stream under version 5's codec and under the
 * alternatives (meshopt's triangle index codec, which may rotate
 * triangles; zlib level 6 over the raw stream; zlib over version 5's
 * stream), summed. Built and run by data_scripts/codec_compare.sh. */
#include "oit/partfile.h"

#include <meshoptimizer.h>
#include <stdio.h>
#include <stdlib.h>
#include <zlib.h>

static size_t zbytes(const void *p, size_t n)
{
    uLongf cap = compressBound(n);
    void *out = malloc(cap);
    if (!out || compress2(out, &cap, p, n, 6) != Z_OK)
        cap = 0;
    free(out);
    return cap;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: codec_compare FILE.oitp\n");
        return 2;
    }
    oit_partfile *pf = NULL;
    oit_error err = {0};
    if (oit_partfile_open(argv[1], NULL, &pf, &err)) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    const oit_partfile_part *parts = oit_partfile_parts(pf);
    oit_partfile_buffer buf = {0};
    unsigned long long raw[3] = {0}, v5[3] = {0}, zraw[3] = {0}, zv5[3] = {0}, ibuf = 0;
    for (uint32_t p = 0; p < oit_partfile_part_count(pf); p++) {
        const oit_partfile_part *r = &parts[p];
        oit_partfile_part_view v;
        if (oit_partfile_part_data(pf, p, &buf, &v, &err)) {
            fprintf(stderr, "%s\n", err.message);
            return 1;
        }
        const uint8_t *blob = v.blob;
        uint64_t sizes[3] = {r->vertex_bytes, r->index_bytes, r->index_count / 3 * 4};
        const uint8_t *at[3] = {blob, blob + r->index_offset, blob + oit_partfile_source_offset(r)};
        uint64_t ss[3] = {r->stored_vertex_bytes, r->stored_index_bytes, r->stored_source_bytes};
        /* Re-encode to get the stored streams (the file's bytes are not
         * exposed by the API; the encoders are deterministic). */
        size_t vcap = meshopt_encodeVertexBufferBound(r->vertex_count, v.stride);
        uint8_t *enc = malloc(vcap);
        size_t vb = meshopt_encodeVertexBuffer(enc, vcap, blob, r->vertex_count, v.stride);
        uint32_t *idx = malloc(r->index_count * 4);
        for (uint64_t i = 0; i < r->index_count; i++)
            idx[i] = oit_partfile_index(&v, i);
        size_t cap = meshopt_encodeIndexBufferBound(r->index_count, r->vertex_count);
        uint8_t *ib = malloc(cap);
        ibuf += meshopt_encodeIndexBuffer(ib, cap, idx, r->index_count);
        for (int k = 0; k < 3; k++) {
            raw[k] += sizes[k];
            v5[k] += ss[k];
            zraw[k] += zbytes(at[k], sizes[k]);
        }
        zv5[0] += zbytes(enc, vb);
        free(enc);
        free(idx);
        free(ib);
    }
    printf("| stream | raw (v4) | zlib -6 of raw | v5 codec | alternative |\n|---|---|---|---|---|\n");
    printf("| vertices | %llu | %llu | %llu | zlib -6 after the vertex codec: %llu |\n", raw[0],
           zraw[0], v5[0], zv5[0]);
    printf("| indices | %llu | %llu | %llu | meshopt_encodeIndexBuffer (rotates): %llu |\n",
           raw[1], zraw[1], v5[1], ibuf);
    printf("| source indices | %llu | %llu | %llu | - |\n", raw[2], zraw[2], v5[2]);
    oit_partfile_buffer_free(&buf);
    oit_partfile_close(pf);
    return 0;
}
