/* The part file a test is given on its command line. */
#ifndef OIT_TESTS_TEST_PARTFILE_H
#define OIT_TESTS_TEST_PARTFILE_H

#include <stdio.h>
#include <stdlib.h>

#include "oit/partfile.h"

/* For a test run as "TEST FILE.oitp": the part file, open, or the test
 * exits: 2 for another command line, 1 naming why it did not open. */
static inline oit_partfile *test_partfile_arg(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s FILE.oitp\n", argv[0]);
        exit(2);
    }
    oit_error err = {0};
    oit_partfile *pf = NULL;
    if (oit_partfile_open(argv[1], NULL, &pf, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: %s\n", err.message);
        exit(1);
    }
    return pf;
}

#endif
