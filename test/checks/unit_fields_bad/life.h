/* A made-up session that breaks each rule of unit_fields.py once (the
 * check's own test: test/checks/CMakeLists.txt expects 6 findings).
 *
 * Files:  life.c */
#include "unit_a.h"
#include "unit_b.h"

struct lep_session {
    int own;
    unit_a a;
    unit_b b;
};
