/* Program binaries kept in a folder (program_cache.h). */
#define _POSIX_C_SOURCE 200809L
#include "view/render/gl/program_cache.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define CACHE_PATH_MAX 4096
#define CACHE_FORMATS_MAX 16
/* An entry larger than this is not one of ours: never read whole. */
#define CACHE_ENTRY_MAX (64u << 20)

static const char magic[8] = {'O', 'I', 'T', 'P', 'B', 'I', 'N', '1'};

/* What precedes the binary in an entry. */
typedef struct entry_head { /* program_cache.h spells its layout */
    char magic[8];
    uint64_t key_b;    /* the second hash of the key */
    uint64_t key_len;  /* bytes hashed */
    uint64_t checksum; /* of the binary */
    uint32_t format;   /* the driver's binary format */
    uint32_t length;   /* of the binary */
} entry_head;

_Static_assert(sizeof(entry_head) == 40, "the entry header program_cache.h spells");

struct oit_program_cache {
    char dir[CACHE_PATH_MAX];
    GLint formats[CACHE_FORMATS_MAX];
    int n_formats;
    /* the key's start: the driver's strings, hashed once */
    uint64_t driver_a, driver_b, driver_len;
    oit_program_cache_stats stats;
};

/* Two hashes of the same bytes, so a name clash (the first) is caught by
 * the entry's header (the second): FNV-1a 64, and a multiply-xorshift of
 * another seed. */
typedef struct key_hash {
    uint64_t a, b, len;
} key_hash;

static void hash_bytes(key_hash *h, const void *data, size_t n)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < n; i++) {
        h->a = (h->a ^ p[i]) * 0x100000001b3ull;
        h->b = (h->b + p[i] + 1) * 0x9e3779b97f4a7c15ull;
        h->b ^= h->b >> 29;
    }
    h->len += n;
}

/* Each string with its terminator, so "ab"+"c" and "a"+"bc" as separate
 * fields differ where fields are separated. */
static void hash_string(key_hash *h, const char *s)
{
    hash_bytes(h, s ? s : "", strlen(s ? s : "") + 1);
}

uint64_t oit_program_cache_checksum(const void *data, size_t n)
{
    key_hash h = {0xcbf29ce484222325ull, 0, 0};
    hash_bytes(&h, data, n);
    return h.a ^ h.b;
}

/* ---- the folder ------------------------------------------------------------ */

void oit_program_cache_folder(const char *asked, char *out, size_t size)
{
    out[0] = '\0';
    const char *env = getenv("OIT_PROGRAM_CACHE");
    const char *v = asked ? asked : env && env[0] ? env : NULL;
    if (v) {
        if (strcmp(v, "off") != 0)
            snprintf(out, size, "%s", v);
        return;
    }
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    /* the XDG spec ignores a relative XDG_CACHE_HOME */
    if (xdg && xdg[0] == '/')
        snprintf(out, size, "%s/oit", xdg);
    else if (home && home[0])
        snprintf(out, size, "%s/.cache/oit", home);
}

/* mkdir -p; whatever fails shows when the folder is used. */
static void make_folder(const char *dir)
{
    char path[CACHE_PATH_MAX];
    snprintf(path, sizeof path, "%s", dir);
    for (char *p = path + 1; *p; p++)
        if (*p == '/') {
            *p = '\0';
            mkdir(path, 0755);
            *p = '/';
        }
    mkdir(path, 0755);
}

oit_status oit_program_cache_open(const char *asked, oit_program_cache **out, oit_error *err)
{
    *out = NULL;
    char dir[CACHE_PATH_MAX];
    oit_program_cache_folder(asked, dir, sizeof dir);
    GLint n = 0;
    glGetIntegerv(GL_NUM_PROGRAM_BINARY_FORMATS, &n);
    if (!dir[0] || n <= 0)
        return OIT_OK;
    make_folder(dir);
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode))
        return OIT_OK;
    oit_program_cache *pc = calloc(1, sizeof *pc);
    if (!pc)
        return oit_error_set(err, OIT_ERR_NOMEM, "program cache %s: out of memory", dir);
    snprintf(pc->dir, sizeof pc->dir, "%s", dir);
    GLint *formats = calloc((size_t)n, sizeof *formats);
    if (!formats) {
        free(pc);
        return oit_error_set(err, OIT_ERR_NOMEM, "program cache %s: out of memory", dir);
    }
    glGetIntegerv(GL_PROGRAM_BINARY_FORMATS, formats);
    pc->n_formats = n < CACHE_FORMATS_MAX ? n : CACHE_FORMATS_MAX;
    memcpy(pc->formats, formats, (size_t)pc->n_formats * sizeof formats[0]);
    free(formats);
    key_hash h = {0xcbf29ce484222325ull, 0x84222325cbf29ce4ull, 0};
    hash_string(&h, (const char *)glGetString(GL_VENDOR));
    hash_string(&h, (const char *)glGetString(GL_RENDERER));
    hash_string(&h, (const char *)glGetString(GL_VERSION));
    pc->driver_a = h.a;
    pc->driver_b = h.b;
    pc->driver_len = h.len;
    *out = pc;
    return OIT_OK;
}

void oit_program_cache_close(oit_program_cache *pc)
{
    free(pc);
}

const char *oit_program_cache_dir(const oit_program_cache *pc)
{
    return pc ? pc->dir : "";
}

oit_program_cache_stats oit_program_cache_get_stats(const oit_program_cache *pc)
{
    oit_program_cache_stats none = {0};
    return pc ? pc->stats : none;
}

/* ---- entries --------------------------------------------------------------- */

static void hash_stage(key_hash *h, int tag, const char *const *parts)
{
    char t = (char)tag;
    hash_bytes(h, &t, 1);
    for (int i = 0; parts && parts[i]; i++)
        hash_bytes(h, parts[i], strlen(parts[i]));
    hash_bytes(h, "", 1);
}

static key_hash program_key(const oit_program_cache *pc, const char *const *vs,
                            const char *const *fs, const char *const *cs)
{
    key_hash h = {pc->driver_a, pc->driver_b, pc->driver_len};
    hash_stage(&h, cs ? 'c' : 'v', cs ? cs : vs);
    if (!cs)
        hash_stage(&h, 'f', fs);
    return h;
}

static void entry_path(const oit_program_cache *pc, const key_hash *k, char *out, size_t size)
{
    snprintf(out, size, "%s/%016llx.bin", pc->dir, (unsigned long long)k->a);
}

static int known_format(const oit_program_cache *pc, uint32_t f)
{
    for (int i = 0; i < pc->n_formats; i++)
        if ((uint32_t)pc->formats[i] == f)
            return 1;
    return 0;
}

/* The entry's binary when it is whole and of this key, else NULL (*found:
 * whether a file was there at all). */
static void *read_entry(const oit_program_cache *pc, const char *path, const key_hash *k,
                        entry_head *head, int *found)
{
    *found = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    *found = 1;
    void *bin = NULL;
    if (fread(head, sizeof *head, 1, f) == 1 && !memcmp(head->magic, magic, sizeof magic) &&
        head->key_b == k->b && head->key_len == k->len && head->length > 0 &&
        head->length <= CACHE_ENTRY_MAX && known_format(pc, head->format)) {
        bin = malloc(head->length);
        /* exactly length bytes: a longer file is not ours either */
        if (bin && (fread(bin, 1, head->length, f) != head->length || fgetc(f) != EOF ||
                    oit_program_cache_checksum(bin, head->length) != head->checksum)) {
            free(bin);
            bin = NULL;
        }
    }
    fclose(f);
    return bin;
}

/* A program from the entry at path, or 0 (the driver refused it). */
static GLuint load_entry(const entry_head *head, const void *bin)
{
    GLuint prog = glCreateProgram();
    glProgramBinary(prog, (GLenum)head->format, bin, (GLsizei)head->length);
    GLint ok = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (ok)
        return prog;
    glDeleteProgram(prog);
    return 0;
}

/* Writes prog's binary as the entry at path: a temporary file beside it
 * renamed over it, so a reader sees the old entry or the new one whole.
 * Any failure leaves no entry (the next run compiles again). */
static int write_entry(const char *path, const key_hash *k, GLuint prog)
{
    GLint len = 0;
    glGetProgramiv(prog, GL_PROGRAM_BINARY_LENGTH, &len);
    if (len <= 0 || (uint64_t)len > CACHE_ENTRY_MAX)
        return 0;
    void *bin = malloc((size_t)len);
    if (!bin)
        return 0;
    GLenum format = 0;
    GLsizei got = 0;
    glGetProgramBinary(prog, len, &got, &format, bin);
    entry_head head = {.key_b = k->b, .key_len = k->len, .format = format,
                       .length = (uint32_t)got, .checksum = oit_program_cache_checksum(bin, (size_t)got)};
    memcpy(head.magic, magic, sizeof magic);
    char tmp[CACHE_PATH_MAX + 48];
    snprintf(tmp, sizeof tmp, "%s.XXXXXX", path);
    int fd = got > 0 ? mkstemp(tmp) : -1;
    int ok = 0;
    if (fd >= 0) {
        FILE *f = fdopen(fd, "wb");
        ok = f && fwrite(&head, sizeof head, 1, f) == 1 &&
             fwrite(bin, 1, (size_t)got, f) == (size_t)got;
        ok = (f ? fclose(f) == 0 : close(fd) == 0) && ok;
        ok = ok && rename(tmp, path) == 0;
        if (!ok)
            unlink(tmp);
    }
    free(bin);
    return ok;
}

oit_status oit_program_cache_build(oit_program_cache *pc, const char *what,
                                   const char *const *vs, const char *const *fs,
                                   const char *const *cs, GLuint *out, oit_error *err)
{
    if (!pc)
        return oit_gl_program_build(what, vs, fs, cs, 0, out, err);
    key_hash k = program_key(pc, vs, fs, cs);
    char path[CACHE_PATH_MAX + 32];
    entry_path(pc, &k, path, sizeof path);
    entry_head head;
    int found = 0;
    void *bin = read_entry(pc, path, &k, &head, &found);
    GLuint prog = bin ? load_entry(&head, bin) : 0;
    if (prog) {
        free(bin);
        pc->stats.hits++;
        *out = prog;
        return OIT_OK;
    }
    if (bin)
        pc->stats.refused++;
    else if (found)
        pc->stats.rejected++;
    else
        pc->stats.misses++;
    free(bin);
    oit_status s = oit_gl_program_build(what, vs, fs, cs, 1, out, err);
    if (s == OIT_OK && write_entry(path, &k, *out))
        pc->stats.written++;
    return s;
}
