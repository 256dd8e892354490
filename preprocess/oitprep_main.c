#include <stdio.h>
int main(void)
{
    fprintf(stderr, "oitprep: not built yet\n");
    return 1;
}
