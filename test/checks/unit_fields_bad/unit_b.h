/* Unit b.
 *
 * Owns:   unit_b */
#include "unit_a.h"
typedef struct unit_b {
    int n;
} unit_b;
void unit_b_take(unit_b *b, unit_a *a);
