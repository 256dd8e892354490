/* Shared pieces of the baseline methods (baseline_common.h). */
#include "render/baseline_common.h"

#include "render/image.h"

#include <stdlib.h>
#include <string.h>

/* Mirrors the decoding in oit_composite (frag_glsl.c). */
const char oit_glsl_premultiplied[] =
    "vec4 oit_premultiplied(uvec4 f) {\n"
    "    if (u_mode == 1) {\n"
    "        vec2 la = unpackUnorm2x16(f.z);\n"
    "        return vec4(vec3(la.x * la.y), la.y);\n"
    "    }\n"
    "    vec2 rg = unpackUnorm2x16(f.z), ba = unpackUnorm2x16(f.w);\n"
    "    return vec4(vec3(rg, ba.x) * ba.y, ba.y);\n"
    "}\n";

oit_status oit_baseline_check_frame(const char *method, const oit_view *v, int n,
                                    oit_error *err)
{
    GLint max_w = 0, max_h = 0;
    glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &max_w);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &max_h);
    if (v->width <= 0 || v->height <= 0 || v->width > max_w || v->height > max_h || n < 0)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: frame %dx%d (with %d meshes) is "
                             "not renderable (at most %dx%d pixels)", method, v->width,
                             v->height, n, max_w, max_h);
    return OIT_OK;
}

/* tmp holds w*h RGBA floats, bottom row first. */
static void flip_into(const float *tmp, oit_image *out)
{
    size_t row = (size_t)out->width * 4;
    for (int y = 0; y < out->height; y++) {
        float *dst = out->rgba + (size_t)y * row;
        memcpy(dst, tmp + (size_t)(out->height - 1 - y) * row, row * sizeof *dst);
        for (int x = 0; x < out->width; x++)
            dst[4 * x + 3] = 1.0f;
    }
}

static oit_status read_any(const char *method, GLuint obj, int is_texture, int w, int h,
                           oit_image *out, oit_error *err)
{
    size_t bytes = (size_t)w * h * 16;
    float *tmp = malloc(bytes);
    if (!tmp)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate %zu bytes for the "
                             "readback", method, bytes);
    oit_status s = oit_image_alloc(out, w, h, err);
    if (s == OIT_OK) {
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
        if (is_texture)
            glGetTextureImage(obj, 0, GL_RGBA, GL_FLOAT, (GLsizei)bytes, tmp);
        else
            glGetNamedBufferSubData(obj, 0, (GLsizeiptr)bytes, tmp);
        s = oit_gl_check(is_texture ? "readback: glGetTextureImage"
                                    : "readback: glGetNamedBufferSubData", err);
        if (s == OIT_OK)
            flip_into(tmp, out);
        else
            oit_image_free(out);
    }
    free(tmp);
    return s;
}

oit_status oit_baseline_read_texture(const char *method, GLuint tex, int w, int h,
                                     oit_image *out, oit_error *err)
{
    return read_any(method, tex, 1, w, h, out, err);
}

oit_status oit_baseline_read_buffer(const char *method, GLuint buf, int w, int h,
                                    oit_image *out, oit_error *err)
{
    return read_any(method, buf, 0, w, h, out, err);
}
