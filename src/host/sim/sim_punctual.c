/* Virtual sensor: sleeping to a deadline, then watching the clock to it
 * (contract in sim_punctual.h). */
#include "sim_punctual.h"

#include "posix_clock.h"

void lep_priv_sim_punctual_init(sim_punctual *p)
{
    p->margin_ns = SIM_PUNCTUAL_MAX_NS;
}

int64_t lep_priv_sim_punctual_wake(const sim_punctual *p, int64_t deadline)
{
    return deadline - p->margin_ns;
}

void lep_priv_sim_punctual_learn(sim_punctual *p, int64_t late_ns)
{
    if (late_ns > p->margin_ns)
        p->margin_ns += SIM_PUNCTUAL_UP_NS;
    else
        p->margin_ns -= SIM_PUNCTUAL_DOWN_NS;
    if (p->margin_ns > SIM_PUNCTUAL_MAX_NS)
        p->margin_ns = SIM_PUNCTUAL_MAX_NS;
    if (p->margin_ns < 0)
        p->margin_ns = 0;
}

void lep_priv_sim_punctual_sleep(sim_punctual *p, int64_t deadline)
{
    int64_t wake = lep_priv_sim_punctual_wake(p, deadline);
    int64_t now = lep_priv_monotonic_ns();
    if (now < wake) {
        lep_priv_sleep_until_ns(wake);
        now = lep_priv_monotonic_ns();
        lep_priv_sim_punctual_learn(p, now - wake);
    }
    while (now < deadline)
        now = lep_priv_monotonic_ns();
}
