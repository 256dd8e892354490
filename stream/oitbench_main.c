#include <stdio.h>
int main(void)
{
    fprintf(stderr, "oitbench: not built yet\n");
    return 1;
}
