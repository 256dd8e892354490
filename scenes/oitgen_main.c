#include <stdio.h>
int main(void)
{
    fprintf(stderr, "oitgen: not built yet\n");
    return 1;
}
