/* Rule 2 (it includes the lifecycle header, and names the session) and
 * rule 3 (it includes another unit's header). */
#include "life.h"
#include "unit_b.h"

void unit_a_poke(struct lep_session *s)
{
    s->own = 1;
}
