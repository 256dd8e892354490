/* tools/common/flag_spelling.h against liboit:
 *  - every range liboit checks (liboit/desc_ranges.h), refused, comes back
 *    naming its field, and the tools' spelling turns it into a flag: no
 *    field a command line sets is left without one;
 *  - the rewrite itself: "field = value" as "flag value", whole words only,
 *    the cache's "off", fields without flags kept, a short buffer cut and
 *    terminated. No GL. */
#include <stdio.h>
#include <string.h>

#include "liboit/desc_ranges.h"
#include "tests/lib/test_check.h"
#include "tools/common/flag_spelling.h"

/* A value row r refuses. */
static void set_refused(oit_renderer_desc *d, const oit_desc_range *r)
{
    char *p = (char *)d + r->offset;
    if (r->type == OIT_DESC_U64) {
        uint64_t v = 1; /* every budget's least is above 1 byte */
        memcpy(p, &v, sizeof v);
    } else if (r->type == OIT_DESC_U32) {
        uint32_t v = (uint32_t)r->hi + 1;
        memcpy(p, &v, sizeof v);
    } else if (r->type == OIT_DESC_INT) {
        int v = (int)r->hi + 1;
        memcpy(p, &v, sizeof v);
    } else {
        float v = (float)r->hi;
        memcpy(p, &v, sizeof v);
    }
}

static void every_range_has_a_flag(void)
{
    for (size_t i = 0; i < OIT_DESC_RANGES; i++) {
        const oit_desc_range *r = &oit_desc_ranges[i];
        oit_renderer_desc d = {0};
        set_refused(&d, r);
        oit_error err = {0};
        oit_status s = oit_renderer_desc_check(&d, &err);
        char field[64];
        snprintf(field, sizeof field, "oit_renderer_desc.%s", r->field);
        CHECK(s == OIT_ERR_ARGUMENT && strstr(err.message, field) == err.message,
              "%s refused: %s '%s', not an error naming it first", field, oit_status_name(s),
              err.message);
        const char *flag = oit_flag_of(field);
        CHECK(flag != field && !strncmp(flag, "--", 2), "%s: no flag sets it (%s)", field, flag);
        oit_flags_spell_error(&err);
        printf("%-32s %s\n", field, err.message);
        CHECK(!strstr(err.message, "oit_renderer_desc") && !strstr(err.message, "OIT_RENDER") &&
                  !strncmp(err.message, flag, strlen(flag)) &&
                  err.message[strlen(flag)] == ' ' && err.message[strlen(flag) + 1] != '=',
              "%s: spelt '%s', not '%s VALUE...' without liboit's names", field, err.message,
              flag);
    }
}

static void rewrite(const char *in, size_t cap, const char *want)
{
    char buf[256];
    snprintf(buf, sizeof buf, "%s", in);
    oit_flags_spell(buf, cap);
    CHECK(!strcmp(buf, want), "'%s' (room %zu) spelt '%s', expected '%s'", in, cap, buf, want);
}

int main(void)
{
    every_range_has_a_flag();
    rewrite("oit_renderer_desc.pack = 7: not an oit_render_pack", 256,
            "--pack 7: not an oit_render_pack");
    rewrite("f.oitp: oit_renderer_desc.upload_budget 1 + oit_renderer_desc.cache_budget 2 = 3 "
            "bytes, more than oit_renderer_desc.gpu_budget 2", 256,
            "f.oitp: --upload-budget 1 + --cache-budget 2 = 3 bytes, more than --gpu-budget 2");
    rewrite("oit_renderer_desc.K = 1", 256, "--max-layers 1");
    rewrite("expected 0, 64..1T or OIT_RENDER_CACHE_OFF (no cache)", 256,
            "expected 0, 64..1T or off (no cache)");
    /* whole words only; a field without a flag keeps its name */
    rewrite("oit_renderer_desc.Kx, my_oit_renderer_desc.pack, oit_renderer_desc.frames", 256,
            "oit_renderer_desc.Kx, my_oit_renderer_desc.pack, oit_renderer_desc.frames");
    rewrite("oit_renderer_desc.capture = stencil at K=8", 256, "--capture stencil at K=8");
    rewrite("oit_renderer_desc.epsilon = 2", 8, "--epsil");
    rewrite("", 256, "");
    CHECK(oit_flag_of(NULL) == NULL, "the flag of no field");
    return test_verdict();
}
