/* One VTK XML DataArray decoded (vtp_internal.h: vtp_decode): ascii
 * numbers, or binary data (base64 inline or appended, raw appended) behind
 * its UInt32/UInt64 header, either byte order, maybe zlib-compressed blocks.
 * Apart as the bytes of one array, whatever element holds them. */
#include "formats/vtp_internal.h"

#include <inttypes.h>
#include <stdint.h>
#include <string.h>

/* ---- decoding an array ------------------------------------------------- */

typedef struct vtp_src {
    size_t pos, end;
    int b64;
} vtp_src;

static int b64_val(unsigned char ch)
{
    if (ch >= 'A' && ch <= 'Z') return ch - 'A';
    if (ch >= 'a' && ch <= 'z') return ch - 'a' + 26;
    if (ch >= '0' && ch <= '9') return ch - '0' + 52;
    if (ch == '+') return 62;
    if (ch == '/') return 63;
    return -1;
}

/* Appends the source's next bytes to dec until it holds at least `need`
 * (base64: up to 2 more, the rest of the last quartet, kept for the next
 * call). Base64 is decoded a quartet at a time, padding allowed in each:
 * VTK encodes a header and its data as one run or as two. */
static oit_status vtp_take(vtp *V, vtp_src *s, size_t need, size_t at)
{
    if (need <= V->dec_len)
        return OIT_OK;
    size_t have_src = s->end - s->pos;
    if ((s->b64 ? have_src / 4 * 3 : have_src) < need - V->dec_len)
        return vtp_fail(V, at, OIT_ERR_FORMAT, "the data array needs %zu bytes, the file has "
                        "fewer (truncated?)", need - V->dec_len);
    oit_status st = oit_rd_grow(&V->c->budget, (void **)&V->dec, &V->dec_cap, 1, need + 3,
                                V->c->name, "decoded array", V->c->err);
    if (st != OIT_OK)
        return st;
    if (!s->b64) {
        memcpy(V->dec + V->dec_len, V->buf + s->pos, need - V->dec_len);
        s->pos += need - V->dec_len;
        V->dec_len = need;
        return OIT_OK;
    }
    while (V->dec_len < need) {
        int q[4], k = 0;
        while (k < 4 && s->pos < s->end) {
            unsigned char ch = V->buf[s->pos++];
            if (vtp_xml_space(ch))
                continue;
            q[k++] = ch == '=' ? -2 : b64_val(ch);
            if (q[k - 1] == -1)
                return vtp_fail(V, s->pos - 1, OIT_ERR_FORMAT, "byte 0x%02x in base64 data", ch);
        }
        if (k < 4)
            return vtp_fail(V, at, OIT_ERR_FORMAT, "base64 data ends early (truncated?)");
        if (q[0] < 0 || q[1] < 0 || (q[2] == -2 && q[3] != -2))
            return vtp_fail(V, s->pos - 4, OIT_ERR_FORMAT, "bad base64 padding");
        unsigned char out[3] = {(unsigned char)(q[0] << 2 | q[1] >> 4), 0, 0};
        int nout = 1;
        if (q[2] >= 0)
            out[1] = (unsigned char)((q[1] & 15) << 4 | q[2] >> 2), nout = 2;
        if (q[2] >= 0 && q[3] >= 0)
            out[2] = (unsigned char)((q[2] & 3) << 6 | q[3]), nout = 3;
        memcpy(V->dec + V->dec_len, out, (size_t)nout);
        V->dec_len += (size_t)nout;
    }
    return OIT_OK;
}

static uint64_t vtp_word(const vtp *V, size_t off)
{
    const unsigned char *b = V->dec + off;
    if (!V->header64)
        return oit_rd_u32(b, V->big);
    uint64_t lo = oit_rd_u32(b + (V->big ? 4 : 0), V->big);
    uint64_t hi = oit_rd_u32(b + (V->big ? 0 : 4), V->big);
    return hi << 32 | lo;
}

static oit_status vtp_inflate(vtp *V, const unsigned char *in, size_t n, unsigned char *out,
                              size_t out_n, size_t at)
{
    z_stream zs;
    memset(&zs, 0, sizeof zs);
    if (!V->z.inflate) {
        oit_status st = oit_zlib_open(&V->z, V->c->name, V->c->err);
        if (st != OIT_OK)
            return st;
    }
    if (V->z.inflate_init2(&zs, 15, ZLIB_VERSION, (int)sizeof zs) != Z_OK)
        return vtp_fail(V, at, OIT_ERR_NOMEM, "zlib cannot start inflating");
    zs.next_in = (unsigned char *)in;
    zs.avail_in = (uInt)n;
    zs.next_out = out;
    zs.avail_out = (uInt)out_n;
    int r = V->z.inflate(&zs, Z_FINISH);
    V->z.inflate_end(&zs);
    if (r != Z_STREAM_END || zs.avail_out != 0)
        return vtp_fail(V, at, OIT_ERR_FORMAT, "a zlib block does not inflate to its %zu bytes "
                        "(%s)", out_n, r == Z_STREAM_END ? "too short" : V->z.error(r));
    return OIT_OK;
}

/* Binary data (header then data, maybe compressed) into dec[0, *n). */
static oit_status vtp_binary(vtp *V, vtp_src *s, size_t at, size_t *n)
{
    size_t w = V->header64 ? 8 : 4;
    V->dec_len = 0;
    oit_status st = vtp_take(V, s, w, at);
    if (st != OIT_OK)
        return st;
    if (!V->zlib) {
        uint64_t bytes = vtp_word(V, 0);
        if (bytes > SIZE_MAX - w)
            return vtp_fail(V, at, OIT_ERR_FORMAT, "data array of %" PRIu64 " bytes", bytes);
        st = vtp_take(V, s, w + (size_t)bytes, at);
        if (st == OIT_OK)
            memmove(V->dec, V->dec + w, (size_t)bytes);
        *n = (size_t)bytes;
        return st;
    }
    if ((st = vtp_take(V, s, 3 * w, at)) != OIT_OK)
        return st;
    uint64_t nb = vtp_word(V, 0), bs = vtp_word(V, w), last = vtp_word(V, 2 * w);
    if (nb > (s->end - s->pos) / w + 1 || (nb > 0 && bs == 0) || last > bs ||
        (nb > 0 && (bs > V->c->budget.limit || nb - 1 > V->c->budget.limit / bs)))
        return vtp_fail(V, at, OIT_ERR_FORMAT, "bad compression header (%" PRIu64 " blocks of "
                        "%" PRIu64 " bytes, the last %" PRIu64 ")", nb, bs, last);
    size_t head = (size_t)(3 + nb) * w;
    if ((st = vtp_take(V, s, head, at)) != OIT_OK)
        return st;
    uint64_t csum = 0;
    for (uint64_t i = 0; i < nb && csum <= s->end - s->pos; i++)
        csum += vtp_word(V, (size_t)(3 + i) * w) > s->end ? s->end : vtp_word(V, (size_t)(3 + i) * w);
    uint64_t total = nb == 0 ? 0 : (nb - 1) * bs + (last ? last : bs);
    if (csum > s->end - s->pos)
        return vtp_fail(V, at, OIT_ERR_FORMAT, "compressed blocks of %" PRIu64 " bytes: more "
                        "than the file holds (truncated?)", csum);
    /* deflate expands at most about 1032:1: a header claiming more is not
     * allocated for */
    if (total > csum * 1040 + 1024)
        return vtp_fail(V, at, OIT_ERR_FORMAT, "compressed blocks of %" PRIu64 " bytes cannot "
                        "inflate to the %" PRIu64 " the header claims", csum, total);
    if ((st = vtp_take(V, s, head + (size_t)csum, at)) != OIT_OK)
        return st;
    unsigned char *out = NULL;
    size_t out_cap = 0;
    st = oit_rd_grow(&V->c->budget, (void **)&out, &out_cap, 1, (size_t)total + 1, V->c->name,
                     "inflated array", V->c->err);
    size_t in_at = head, out_at = 0;
    for (uint64_t i = 0; i < nb && st == OIT_OK; i++) {
        size_t cs = (size_t)vtp_word(V, (size_t)(3 + i) * w);
        size_t us = (size_t)(i + 1 == nb && last ? last : bs);
        st = vtp_inflate(V, V->dec + in_at, cs, out + out_at, us, at);
        in_at += cs, out_at += us;
    }
    oit_rd_release(&V->c->budget, (void **)&V->dec, &V->dec_cap, 1);
    V->dec = out, V->dec_cap = out_cap, V->dec_len = (size_t)total;
    *n = (size_t)total;
    return st;
}

/* ASCII numbers into dec as native doubles. */
static oit_status vtp_ascii(vtp *V, const vtp_array *a, size_t count)
{
    if (count > (a->text_end - a->text + 1) / 2) /* a digit and a blank each at least */
        return vtp_fail(V, a->at, OIT_ERR_FORMAT, "ascii DataArray '%.*s' of %zu bytes cannot "
                        "hold %zu values", (int)(a->name_len > 40 ? 40 : a->name_len),
                        a->name ? a->name : "", a->text_end - a->text, count);
    oit_status st = oit_rd_grow(&V->c->budget, (void **)&V->dec, &V->dec_cap, sizeof(double),
                                count + 1, V->c->name, "decoded array", V->c->err);
    size_t p = a->text, i = 0;
    while (st == OIT_OK && i < count) {
        while (p < a->text_end && vtp_xml_space(V->buf[p]))
            p++;
        if (p >= a->text_end)
            return vtp_fail(V, a->at, OIT_ERR_FORMAT, "ascii DataArray '%.*s' holds %zu of "
                            "%zu values", (int)(a->name_len > 40 ? 40 : a->name_len),
                            a->name ? a->name : "", i, count);
        char tmp[64];
        size_t k = 0;
        while (p < a->text_end && !vtp_xml_space(V->buf[p]) && k < sizeof tmp - 1)
            tmp[k++] = (char)V->buf[p++];
        tmp[k] = '\0';
        char *q = tmp;
        double d;
        if (!oit_rd_double(&q, &d) || *q)
            return vtp_fail(V, p - k, OIT_ERR_FORMAT, "not a number: '%.40s'", tmp);
        memcpy(V->dec + i * sizeof d, &d, sizeof d);
        i++;
    }
    return st;
}

/* Decodes array a, which must hold `count` values, into dec (moved out to
 * *owned so that several arrays can be held at once). */
oit_status vtp_decode(vtp *V, const vtp_array *a, size_t count, vtp_view *view,
                      unsigned char **owned, size_t *owned_cap)
{
    if (a->type == VT_BAD)
        return vtp_fail(V, a->at, OIT_ERR_UNSUPPORTED, "DataArray '%.*s': type missing or not "
                        "numeric", (int)(a->name_len > 40 ? 40 : a->name_len),
                        a->name ? a->name : "");
    memset(view, 0, sizeof *view);
    view->type = a->type, view->big = V->big, view->count = count;
    oit_status st;
    size_t n = 0;
    V->dec_len = 0;
    if (a->format == FMT_ASCII) {
        st = vtp_ascii(V, a, count);
        view->native_double = 1;
        n = count * vt_size[a->type];
    } else if (a->format == FMT_BINARY) {
        vtp_src s = {a->text, a->text_end, 1};
        st = vtp_binary(V, &s, a->at, &n);
    } else {
        if (!V->appended)
            return vtp_fail(V, a->at, OIT_ERR_FORMAT, "appended DataArray but no "
                            "<AppendedData> (truncated?)");
        if (a->offset >= V->appended_end - V->appended)
            return vtp_fail(V, a->at, OIT_ERR_FORMAT, "appended offset %" PRIu64 " beyond the "
                            "appended data (truncated?)", a->offset);
        vtp_src s = {V->appended + (size_t)a->offset, V->appended_end, V->appended_b64};
        st = vtp_binary(V, &s, a->at, &n);
    }
    if (st == OIT_OK && n / vt_size[a->type] < count)
        st = vtp_fail(V, a->at, OIT_ERR_FORMAT, "DataArray '%.*s' holds %zu values, %zu "
                      "expected", (int)(a->name_len > 40 ? 40 : a->name_len),
                      a->name ? a->name : "", n / vt_size[a->type], count);
    *owned = V->dec, *owned_cap = V->dec_cap;
    V->dec = NULL, V->dec_cap = V->dec_len = 0;
    view->b = *owned;
    return st;
}
