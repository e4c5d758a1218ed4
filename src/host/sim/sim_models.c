/* Model presets of the virtual sensor, with their published rated values. */
#include <string.h>

#include "leptrino/error.h"
#include "leptrino/sim.h"
#include "struct_api.h"

struct preset {
    const char *name;
    float rated[LEP_AXES];
};

/* Spec 5.2: N, N, N, N m, N m, N m. */
static const struct preset presets[] = {
    { "CFS018CA201U", { 100.0f, 100.0f, 200.0f, 1.0f, 1.0f, 1.0f } },
    { "CFS034CA301U", { 150.0f, 150.0f, 300.0f, 4.0f, 4.0f, 4.0f } },
    { "PFS055YA501U6", { 500.0f, 500.0f, 500.0f, 10.0f, 10.0f, 8.0f } },
    { "PFS080YS102U6", { 500.0f, 500.0f, 1000.0f, 40.0f, 40.0f, 30.0f } },
};

static const char *const names[] = { "CFS018CA201U", "CFS034CA301U", "PFS055YA501U6",
                                     "PFS080YS102U6", NULL };

const char *const *lep_sim_models(void)
{
    return names;
}

int lep_sim_model_rated_f(const char *model, lep_rated *out)
{
    size_t i;
    if (model == NULL || out == NULL)
        return LEP_E_ARG;
    for (i = 0; i < sizeof presets / sizeof presets[0]; i++) {
        if (strcmp(presets[i].name, model) == 0) {
            memcpy(out->axis, presets[i].rated, sizeof out->axis);
            return LEP_OK;
        }
    }
    return LEP_E_ARG;
}

size_t lep_sim_model_count(void)
{
    return sizeof names / sizeof names[0] - 1u;
}

const char *lep_sim_model_name(size_t i)
{
    return i < lep_sim_model_count() ? names[i] : NULL;
}

int lep_sim_model_rated(const char *model, double rated[6])
{
    lep_rated r;
    int k, rc;
    if (rated == NULL)
        return LEP_E_ARG;
    rc = lep_sim_model_rated_f(model, &r);
    if (rc != LEP_OK)
        return rc;
    for (k = 0; k < LEP_AXES; k++)
        rated[k] = (double)r.axis[k];
    return LEP_OK;
}
