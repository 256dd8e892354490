/* liboit's methods (liboit_internal.h): the one table of every method a
 * renderer runs, in the order oit_render_methods lists them, and the
 * in-core ones opened behind the method interface (view/render/method.h) in the
 * caller's context. The stream is the streamer (liboit.c); the reference
 * is Embree's, loaded as a plugin (liboit_reference.h) so that liboit
 * links no C++. */
#include "liboit/liboit_internal.h"

#include "view/render/baselines/methods.h"
#include "view/render/gl/gl_context.h"
#include "liboit/liboit_reference.h"

#define GL OIT_RENDER_METHOD_GL
#define CLIP OIT_RENDER_METHOD_CLIP
#define EPS OIT_RENDER_METHOD_EPSILON
#define COUNTS OIT_RENDER_METHOD_COUNTS

/* The methods as callers see them, and (same index) the tables that run
 * the in-core ones: NULL for the stream (the streamer, liboit.c) and the
 * reference (its plugin). A table's flags must be its entry's
 * (oit_lib_method_open checks). */
static const oit_render_method_info methods[] = {
    {"dfb", GL | COUNTS | CLIP},
    {"reference", COUNTS | OIT_RENDER_METHOD_AMBIGUITY | EPS | CLIP},
    {"array", GL | CLIP},
    {"stencil", GL | CLIP},
    {"stream", GL | COUNTS | OIT_RENDER_METHOD_PART_FILE | EPS | CLIP},
    {"unsorted", GL | CLIP},
    {"wboit", GL | CLIP},
    {"pll", GL | CLIP},
    {"dp", GL | CLIP},
    {"ppll4", GL | CLIP},
    {"b3d", GL | CLIP},
    {"ddp", GL | CLIP},
    {"guarded", GL | EPS | CLIP},
    {"f2b", GL | EPS | CLIP},
    {"compute", GL | CLIP},
};
static const oit_method *const tables[] = {
    &oit_method_dfb,     NULL,           &oit_method_array,   &oit_method_stencil,
    NULL,                &oit_method_unsorted, &oit_method_wboit, &oit_method_pll,
    &oit_method_dp,      &oit_method_ppll4, &oit_method_b3d,  &oit_method_ddp,
    &oit_method_guarded, &oit_method_f2b, &oit_method_compute,
};
enum { METHODS = sizeof methods / sizeof methods[0] };
_Static_assert(sizeof tables / sizeof tables[0] == METHODS, "a table a method");

const oit_render_method_info *oit_render_methods(uint32_t *count)
{
    if (count)
        *count = METHODS;
    return methods;
}

const oit_lib_method *oit_lib_method_find(const char *name)
{
    for (size_t i = 0; name && i < METHODS; i++)
        if (!strcmp(methods[i].name, name))
            return &methods[i];
    return NULL;
}

oit_status oit_lib_method_check(const char *name, oit_error *err)
{
    if (!name || !*name || oit_lib_method_find(name))
        return OIT_OK;
    char list[256];
    size_t used = 0;
    list[0] = 0;
    for (size_t i = 0; i < METHODS && used < sizeof list; i++)
        used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "",
                                 methods[i].name);
    return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_renderer_desc.method = \"%.64s\": expected "
                         "NULL (the scene's default) or one of %s", name, list);
}

oit_status oit_lib_method_for(const oit_renderer *r, const oit_scene *scene,
                              const oit_lib_method **out, oit_error *err)
{
    const char *asked = r->desc.method;
    *out = oit_lib_method_find(asked ? asked : scene->pf ? "stream" : "dfb");
    int part_file = !!((*out)->flags & OIT_RENDER_METHOD_PART_FILE);
    if (part_file == !!scene->pf)
        return OIT_OK;
    return oit_error_set(err, OIT_ERR_UNSUPPORTED, "oit_renderer_desc.method = \"%s\" draws %s; "
                         "this scene is %s", (*out)->name,
                         part_file ? "part files" : "in-core scenes (a mesh)",
                         scene->pf ? "a part file (method \"stream\" or NULL)"
                                   : "in core (a mesh file or arrays)");
}

/* The table m runs with: its own, or the reference's from its plugin,
 * loaded once a renderer and kept until it is destroyed. */
oit_status oit_lib_method_table(oit_renderer *r, const oit_lib_method *m,
                                const oit_method **out, oit_error *err)
{
    *out = tables[m - methods];
    if (!*out && !r->reference) {
        oit_status s = oit_lib_reference_load(&r->reference_plugin, &r->reference, err);
        if (s != OIT_OK)
            return s;
    }
    if (!*out)
        *out = r->reference;
    if ((*out)->flags == m->flags)
        return OIT_OK;
    return oit_error_set(err, OIT_ERR_UNSUPPORTED, "method %s: its table has flags 0x%x, "
                         "liboit's list 0x%x (a plugin of another build?)", m->name,
                         (*out)->flags, m->flags);
}

/* A threshold the method reads: epsilon where given (its exact zero
 * spelt OIT_RENDER_EPSILON_ZERO), else NULL, the method's default. */
static const float *threshold_of(const oit_renderer_desc *d, float *keep)
{
    if (d->epsilon == 0.0f)
        return NULL;
    *keep = d->epsilon == OIT_RENDER_EPSILON_ZERO ? 0.0f : d->epsilon;
    return keep;
}

oit_status oit_lib_method_open(oit_renderer *r, const oit_lib_method *m, const oit_scene *scene,
                               oit_error *err)
{
    const oit_method *table = NULL;
    oit_status s = oit_lib_method_table(r, m, &table, err);
    if (s == OIT_OK && (table->flags & OIT_RENDER_METHOD_GL) && !r->run_gl)
        s = oit_gl_borrow_current(&r->run_gl, err);
    if (s != OIT_OK)
        return s;
    float threshold = 0.0f;
    oit_method_options opt = {.max_layers = r->desc.K ? (int)r->desc.K : OIT_LIB_IN_CORE_K,
                              .gl = r->run_gl, .threshold = threshold_of(&r->desc, &threshold),
                              .ambiguity_px = r->desc.ambiguity_px,
                              .store_limit = r->desc.binding_limit, .timer = r->timer};
    return oit_method_open(table, &scene->mesh, &opt, &r->run, err);
}
