/* Rule 5: the lifecycle writes a unit's field (and passes one whole: allowed). */
#include "life.h"

void life_run(struct lep_session *s)
{
    s->own = 2;
    unit_b_take(&s->b, &s->a);
    s->b.n = 3;
}
