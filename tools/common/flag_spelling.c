/* flag_spelling.h */
#include "tools/common/flag_spelling.h"

#include <string.h>

typedef struct spelling {
    const char *field, *flag;
} spelling;

/* oitstream's, oitbench's and oitstream-mpi's flags (their --help) for the
 * fields of include/oit/liboit.h they set, then oitprep's. */
static const spelling spellings[] = {
    {"oit_renderer_desc.K", "--max-layers"},
    {"oit_renderer_desc.pack", "--pack"},
    {"oit_renderer_desc.schedule", "--schedule"},
    {"oit_renderer_desc.capture", "--capture"},
    {"oit_renderer_desc.epsilon", "--epsilon"},
    {"oit_renderer_desc.see_through", "--see-through"},
    {"oit_renderer_desc.gpu_budget", "--gpu-budget"},
    {"oit_renderer_desc.upload_budget", "--upload-budget"},
    {"oit_renderer_desc.cache_budget", "--cache-budget"},
    {"oit_renderer_desc.slot_budget", "--slot-budget"},
    {"oit_renderer_desc.store_budget", "--store-budget"},
    {"oit_renderer_desc.reader_threads", "--upload-threads"},
    {"oit_renderer_desc.program_cache", "--program-cache"},
    {"OIT_RENDER_CACHE_OFF", "off"},
    {"oit_frame.clip", "--clip"},
    /* oitprep's, for prepare/convert/convert.h's options */
    {"oit_convert_options.scheme", "--scheme"},
    {"oit_convert_options.manage", "--manage"},
    {"oit_convert_options.grid", "--grid"},
    {"oit_convert_options.max_piece_triangles", "--max-piece-triangles"},
};

#define SPELLINGS (sizeof spellings / sizeof spellings[0])

const char *oit_flag_of(const char *field)
{
    for (size_t i = 0; field && i < SPELLINGS; i++)
        if (!strcmp(field, spellings[i].field))
            return spellings[i].flag;
    return field;
}

static int ident(char c)
{
    return c == '_' || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
}

/* The spelling whose field starts at p as a whole word, or NULL. */
static const spelling *field_at(const char *msg, const char *p)
{
    if (p > msg && ident(p[-1]))
        return NULL;
    for (size_t i = 0; i < SPELLINGS; i++) {
        size_t n = strlen(spellings[i].field);
        if (!strncmp(p, spellings[i].field, n) && !ident(p[n]))
            return &spellings[i];
    }
    return NULL;
}

void oit_flags_spell(char *msg, size_t cap)
{
    if (!msg || !cap)
        return;
    char out[1024];
    size_t o = 0, room = cap < sizeof out ? cap : sizeof out;
    for (const char *p = msg; *p && o + 1 < room;) {
        const spelling *s = field_at(msg, p);
        if (!s) {
            out[o++] = *p++;
            continue;
        }
        for (const char *f = s->flag; *f && o + 1 < room; f++)
            out[o++] = *f;
        p += strlen(s->field);
        if (!strncmp(p, " = ", 3))
            p += 2; /* "--pack 7", as the command line reads */
    }
    out[o] = 0;
    memcpy(msg, out, o + 1);
}

void oit_flags_spell_error(oit_error *err)
{
    if (err)
        oit_flags_spell(err->message, sizeof err->message);
}
