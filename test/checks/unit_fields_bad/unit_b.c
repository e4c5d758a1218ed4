/* Rule 4: it follows a pointer to another unit's struct. */
#include "unit_b.h"

void unit_b_take(unit_b *b, unit_a *a)
{
    b->n = a->n;
}
