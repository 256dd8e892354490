/* prepare/partition/layers_measured.h: the most surfaces a line crosses, on shapes
 * whose count is known (cube, sphere, torus, a stack of sheets). */
#include "prepare/partition/layers_measured.h"
#include "tests/prepare/partition/partition_test.h"

static uint32_t measured(const tri_list *l)
{
    uint32_t layers = 0;
    oit_error err = {0};
    CHECK(oit_layers_measure(l->t, l->n, &layers, &err) == OIT_OK, "measure: %s", err.message);
    return layers;
}

static void test_layers_measured(void)
{
    tri_list cube = {0}, sphere = {0}, torus = {0}, stack = {0};
    make_cube(&cube, 0, 1);
    make_sphere(&sphere, 16, 24);
    make_torus(&torus, 48, 24);
    make_stack(&stack, 20);
    /* A closed convex surface: two crossings; a torus: four along its axis
     * plane; the stack: one a sheet. */
    CHECK(measured(&cube) == 2, "cube: %u layers, want 2", measured(&cube));
    CHECK(measured(&sphere) == 2, "sphere: %u layers, want 2", measured(&sphere));
    CHECK(measured(&torus) == 4, "torus: %u layers, want 4", measured(&torus));
    CHECK(measured(&stack) == 20, "stack of 20: %u layers", measured(&stack));
    CHECK(oit_layers_measure(NULL, 0, &(uint32_t){0}, NULL) == OIT_OK, "empty part");
    free(cube.t);
    free(sphere.t);
    free(torus.t);
    free(stack.t);
}

int main(void)
{
    test_layers_measured();
    return test_verdict();
}
