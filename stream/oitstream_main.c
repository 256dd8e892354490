#include <stdio.h>
int main(void)
{
    fprintf(stderr, "oitstream: not built yet\n");
    return 1;
}
