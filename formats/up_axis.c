/* Which way is up in a model (up_axis.h). */
#include "formats/up_axis.h"

#include <math.h>
#include <string.h>
#include <strings.h>

/* 1 when name ends in ext (case-insensitive), also before a ".gz". */
static int has_ext(const char *name, const char *ext)
{
    size_t n = strlen(name), e = strlen(ext);
    if (n > 3 && !strcasecmp(name + n - 3, ".gz"))
        n -= 3;
    return n > e && !strncasecmp(name + n - e, ext, e);
}

static int format_says(const char *path, const char **why)
{
    static const char *const y_up[] = {".gltf", ".glb"};
    static const char *const z_up[] = {".step", ".stp", ".iges", ".igs"};
    for (size_t i = 0; path && i < sizeof y_up / sizeof *y_up; i++)
        if (has_ext(path, y_up[i])) {
            *why = "glTF is Y-up";
            return 1;
        }
    for (size_t i = 0; path && i < sizeof z_up / sizeof *z_up; i++)
        if (has_ext(path, z_up[i])) {
            *why = "STEP and IGES are Z-up";
            return 2;
        }
    return -1;
}

int oit_up_axis_guess(const char *path, const float bmin[3], const float bmax[3],
                      const char **why)
{
    const char *said = "the default";
    int axis = format_says(path, &said);
    if (axis < 0) {
        double e[3];
        for (int k = 0; k < 3; k++)
            e[k] = (double)bmax[k] - bmin[k];
        int finite = isfinite(e[0]) && isfinite(e[1]) && isfinite(e[2]);
        axis = finite && e[2] < 0.5 * e[0] && e[2] < 0.5 * e[1] ? 2 : 1;
        if (axis == 2)
            said = "flat in z";
    }
    if (why)
        *why = said;
    return axis;
}
