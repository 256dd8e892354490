/* The viewer's pick (I, or a left click that does not drag): every layer of
 * the pixel under the cursor (pick_json.h, oit_renderer_pick), listed in a
 * panel beside a marker on the pixel, and on stdout for scripts. */
#include "tools/oitstream/viewer_internal.h"

#include "tools/oitstream/pick_json.h"

/* The image pixel under window point (wx, wy); 0 outside the image. */
static int pixel_under(const viewer *v, double wx, double wy, int *x, int *y)
{
    int ww = 0, wh = 0;
    glfwGetWindowSize(v->win, &ww, &wh);
    if (ww <= 0 || wh <= 0)
        return 0;
    *x = (int)floor(wx * v->view.width / ww);
    *y = (int)floor(wy * v->view.height / wh);
    return *x >= 0 && *y >= 0 && *x < v->view.width && *y < v->view.height;
}

static void print_layers(const viewer *v, const oit_pick_layer *l, size_t n)
{
    printf("viewer: pick %d,%d: %zu layer%s (%s)\n", v->pick_x, v->pick_y, n, n == 1 ? "" : "s",
           v->methods[v->current]->name);
    for (size_t i = 0; i < n; i++) {
        printf("viewer:   layer %zu: depth %.7g alpha %.4f colour %.4f,%.4f,%.4f transmittance "
               "%.4f part ", i, l[i].depth, l[i].alpha, l[i].colour[0], l[i].colour[1],
               l[i].colour[2], l[i].transmittance[0]);
        if (l[i].part == OIT_PICK_NO_PART)
            printf("-");
        else
            printf("%u", l[i].part);
        const double *o = v->mesh->info.origin;
        printf(" source %llu point %.9g,%.9g,%.9g\n", (unsigned long long)l[i].source_triangle,
               l[i].point[0] + o[0], l[i].point[1] + o[1], l[i].point[2] + o[2]);
    }
    fflush(stdout);
}

void viewer_pick_at(viewer *v, double wx, double wy)
{
    int x, y;
    if (!pixel_under(v, wx, wy, &x, &y)) {
        viewer_say(v, "pick: the cursor is outside the image");
        return;
    }
    oit_pick_request rq = {.model = v->pf ? v->stream_path : v->model_name,
                           .part_file = v->pf != NULL, .mesh = v->mesh,
                           .method = v->methods[v->current]->name, .view = &v->view, .x = x,
                           .y = y, .origin = v->mesh->info.origin};
    oit_pick_layer *layers = NULL;
    size_t n = 0;
    oit_error err = {0};
    if (oit_pick_get(&rq, &layers, &n, &err) != OIT_OK) {
        viewer_say(v, "pick: %s", err.message);
        return;
    }
    v->picked = 1;
    v->pick_x = x;
    v->pick_y = y;
    v->pick_count = n;
    memcpy(v->pick, layers, (n < VIEWER_PICK_ROWS ? n : VIEWER_PICK_ROWS) * sizeof *layers);
    print_layers(v, layers, n);
    free(layers);
    v->recompose = 1;
}

/* A left press remembers when; its release picks where it is unless the
 * camera moved in between (a drag, even one back to where it began). */
void viewer_pick_button(viewer *v, int pressed)
{
    if (pressed)
        v->press_time = glfwGetTime();
    else if (!(v->last_move >= v->press_time))
        viewer_pick_at(v, v->mouse_x, v->mouse_y);
}
