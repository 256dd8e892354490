/* Transparent gzip input (gzip_input.h). zlib comes through a table
 * (zlib_load.h): linked in the tools; in liboit loaded for each gzip
 * input and released with it. */
#define _GNU_SOURCE /* fopencookie */
#include "formats/gzip_input.h"

#include "formats/zlib_load.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>

#define GZ_IN ((size_t)1 << 16)

struct oit_gz {
    FILE *src;
    oit_zlib z;
    z_stream zs;
    int between; /* after a member's end: another member or the end */
    int end;
    char msg[160];
    unsigned char in[GZ_IN];
};

int oit_gz_magic(const unsigned char *b, size_t n)
{
    return n >= 2 && b[0] == 0x1f && b[1] == 0x8b;
}

const char *oit_gz_message(const oit_gz *g)
{
    return g ? g->msg : "";
}

static ssize_t gz_fail(oit_gz *g, const char *what, const char *detail)
{
    snprintf(g->msg, sizeof g->msg, "%s%s%s%s", what, detail ? " (" : "", detail ? detail : "",
             detail ? ")" : "");
    errno = EIO;
    return -1;
}

/* Refills the input; 0 at the end of the compressed file. */
static size_t gz_refill(oit_gz *g)
{
    size_t n = fread(g->in, 1, GZ_IN, g->src);
    g->zs.next_in = g->in;
    g->zs.avail_in = (uInt)n;
    return n;
}

static ssize_t gz_read(void *cookie, char *buf, size_t size)
{
    oit_gz *g = cookie;
    g->zs.next_out = (Bytef *)buf;
    g->zs.avail_out = (uInt)(size > (1u << 30) ? 1u << 30 : size);
    uInt want = g->zs.avail_out;
    while (g->zs.avail_out > 0 && !g->end) {
        if (g->zs.avail_in == 0 && gz_refill(g) == 0) {
            if (ferror(g->src))
                return gz_fail(g, "read error", strerror(errno));
            if (!g->between)
                return gz_fail(g, "gzip stream truncated (the file ends inside it)", NULL);
            g->end = 1;
            break;
        }
        if (g->between) { /* trailing bytes that start no member end the data */
            if (g->zs.next_in[0] != 0x1f) {
                g->end = 1;
                break;
            }
            g->between = 0;
        }
        int r = g->z.inflate(&g->zs, Z_NO_FLUSH);
        if (r == Z_STREAM_END) {
            g->between = 1;
            g->z.inflate_reset(&g->zs);
        } else if (r != Z_OK && r != Z_BUF_ERROR) {
            return gz_fail(g, "corrupt gzip data", g->zs.msg ? g->zs.msg : g->z.error(r));
        }
    }
    return (ssize_t)(want - g->zs.avail_out);
}

static int gz_close(void *cookie)
{
    oit_gz *g = cookie;
    g->z.inflate_end(&g->zs);
    oit_zlib_close(&g->z);
    free(g);
    return 0;
}

/* Reads two bytes and puts them back: by seeking where f can, else through
 * stdio's push-back (glibc keeps more than one byte). */
static int peek2(FILE *f, unsigned char b[2])
{
    off_t here = ftello(f);
    int c0 = getc(f), c1 = c0 == EOF ? EOF : getc(f);
    b[0] = (unsigned char)(c0 == EOF ? 0 : c0);
    b[1] = (unsigned char)(c1 == EOF ? 0 : c1);
    if (here >= 0 && fseeko(f, here, SEEK_SET) == 0)
        return c1 != EOF;
    if (c1 != EOF && ungetc(c1, f) == EOF)
        return -1;
    if (c0 != EOF && ungetc(c0, f) == EOF)
        return -1;
    return c1 != EOF;
}

oit_status oit_gz_open(FILE *f, const char *name, FILE **out, oit_gz **state, oit_error *err)
{
    unsigned char b[2];
    *out = NULL;
    *state = NULL;
    int got = peek2(f, b);
    if (got < 0)
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot rewind after reading its first bytes",
                             name);
    if (!got || !oit_gz_magic(b, 2))
        return OIT_OK;
    oit_gz *g = calloc(1, sizeof *g);
    if (!g)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: out of memory for gzip input", name);
    g->src = f;
    oit_status s = oit_zlib_open(&g->z, name, err);
    if (s != OIT_OK) {
        free(g);
        return s;
    }
    if (oit_zlib_init_gzip(&g->z, &g->zs) != Z_OK) {
        oit_zlib_close(&g->z);
        free(g);
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot start gzip decompression", name);
    }
    cookie_io_functions_t io = {.read = gz_read, .close = gz_close};
    FILE *z = fopencookie(g, "rb", io);
    if (!z) {
        gz_close(g);
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot open gzip stream", name);
    }
    *out = z;
    *state = g;
    return OIT_OK;
}

static oit_status gunzip_grow(unsigned char **buf, size_t *cap, size_t limit, const char *name,
                              oit_error *err)
{
    if (*cap >= limit)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: gzip data inflates beyond the memory "
                             "budget of %zu bytes", name, limit);
    size_t ncap = *cap < 65536 ? 65536 : *cap * 2;
    if (ncap > limit || ncap < *cap)
        ncap = limit;
    unsigned char *q = realloc(*buf, ncap);
    if (!q)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: out of memory inflating gzip data", name);
    *buf = q;
    *cap = ncap;
    return OIT_OK;
}

oit_status oit_gunzip(const unsigned char *in, size_t n, size_t limit, const char *name,
                      unsigned char **out, size_t *out_n, oit_error *err)
{
    z_stream zs;
    memset(&zs, 0, sizeof zs);
    *out = NULL;
    *out_n = 0;
    oit_zlib z;
    oit_status s = oit_zlib_open(&z, name, err);
    if (s != OIT_OK)
        return s;
    if (oit_zlib_init_gzip(&z, &zs) != Z_OK) {
        oit_zlib_close(&z);
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot start gzip decompression", name);
    }
    unsigned char *buf = NULL;
    size_t cap = 0, used = 0;
    zs.next_in = (Bytef *)in;
    for (size_t left = n; s == OIT_OK;) {
        if (used == cap && (s = gunzip_grow(&buf, &cap, limit, name, err)) != OIT_OK)
            break;
        uInt chunk_in = left > (1u << 30) ? 1u << 30 : (uInt)left;
        uInt chunk_out = cap - used > (1u << 30) ? 1u << 30 : (uInt)(cap - used);
        zs.avail_in = chunk_in;
        zs.next_out = buf + used;
        zs.avail_out = chunk_out;
        int r = z.inflate(&zs, Z_NO_FLUSH);
        left -= chunk_in - zs.avail_in;
        used += chunk_out - zs.avail_out;
        if (r == Z_STREAM_END) { /* another member follows, or the data ends */
            if (left < 2 || !oit_gz_magic(zs.next_in, left))
                break;
            z.inflate_reset(&zs);
        } else if (r == Z_BUF_ERROR && left == 0 && zs.avail_out > 0) {
            s = oit_error_set(err, OIT_ERR_FORMAT, "%s: gzip stream truncated (the file ends "
                              "inside it)", name);
        } else if (r != Z_OK && r != Z_BUF_ERROR) {
            s = oit_error_set(err, OIT_ERR_FORMAT, "%s: corrupt gzip data (%s)", name,
                              zs.msg ? zs.msg : z.error(r));
        }
    }
    z.inflate_end(&zs);
    oit_zlib_close(&z);
    if (s != OIT_OK) {
        free(buf);
        return s;
    }
    *out = buf;
    *out_n = used;
    return OIT_OK;
}
