/* Test support: a virtual sensor's write trace file (lep_sim_trace_writes)
 * read whole, for the tests that check what the sensor did (its writes, in
 * order, on its clock) instead of timing it from outside. */
#ifndef LEP_TEST_SIM_TRACE_FILE_H
#define LEP_TEST_SIM_TRACE_FILE_H

#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>

#include "struct_api.h"
#include "unity.h"

/* The whole file at path; *n records (malloc'd: free it). */
static inline lep_sim_trace_record *lep_test_load_trace(const char *path, size_t *n)
{
    struct stat st;
    lep_sim_trace_record *r;
    FILE *f;
    TEST_ASSERT_EQUAL_INT(0, stat(path, &st));
    TEST_ASSERT_EQUAL_INT(0, (int)(st.st_size % (off_t)sizeof(lep_sim_trace_record)));
    *n = (size_t)st.st_size / sizeof(lep_sim_trace_record);
    r = malloc(*n * sizeof *r + 1u);
    TEST_ASSERT_NOT_NULL(r);
    f = fopen(path, "rb");
    TEST_ASSERT_NOT_NULL(f);
    TEST_ASSERT_EQUAL_size_t(*n, fread(r, sizeof *r, *n, f));
    fclose(f);
    return r;
}

#endif
