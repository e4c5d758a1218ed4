/* A payload's gravity wrench, and its identification from static poses by
 * linear least squares (leptrino/payload.h states the model and the source). */
#include <math.h>
#include <string.h>

#include "errmsg.h"
#include "leptrino/error.h"
#include "leptrino/payload.h"
#include "struct_api.h"

static void cross(const double a[3], const double b[3], double out[3])
{
    double x = a[1] * b[2] - a[2] * b[1];
    double y = a[2] * b[0] - a[0] * b[2];
    double z = a[0] * b[1] - a[1] * b[0];
    out[0] = x;
    out[1] = y;
    out[2] = z;
}

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static int finite_all(const double *v, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return 0;
    return 1;
}

int lep_payload_wrench_p(const lep_payload *p, const double gravity[3], double wrench[LEP_AXES])
{
    double f[3], m[3];
    int k;
    if (p == NULL || gravity == NULL || wrench == NULL || !isfinite(p->mass_kg) ||
        p->mass_kg < 0.0 || !finite_all(p->com_m, 3) || !finite_all(gravity, 3))
        return LEP_E_ARG;
    for (k = 0; k < 3; k++)
        f[k] = p->mass_kg * gravity[k];
    cross(p->com_m, f, m);
    for (k = 0; k < 3; k++) {
        wrench[k] = f[k];
        wrench[3 + k] = m[k];
    }
    return LEP_OK;
}

/* Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations:
 * a is destroyed (its diagonal ends as the eigenvalues, lam), v gets the
 * eigenvectors as columns. Converges quadratically; 50 sweeps is far more
 * than a 3x3 needs. */
static void jacobi3(double a[3][3], double lam[3], double v[3][3])
{
    int sweep, p, q, i;
    memset(v, 0, 9 * sizeof v[0][0]);
    for (i = 0; i < 3; i++)
        v[i][i] = 1.0;
    for (sweep = 0; sweep < 50; sweep++) {
        double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
        double diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
        if (off <= 1e-30 * diag || off == 0.0)
            break;
        for (p = 0; p < 2; p++) {
            for (q = p + 1; q < 3; q++) {
                double theta, t, c, s, tau;
                if (a[p][q] == 0.0)
                    continue;
                theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                t = (theta >= 0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
                c = 1.0 / sqrt(t * t + 1.0);
                s = t * c;
                tau = s / (1.0 + c);
                {
                    double apq = a[p][q];
                    int r;
                    a[p][p] -= t * apq;
                    a[q][q] += t * apq;
                    a[p][q] = a[q][p] = 0.0;
                    for (r = 0; r < 3; r++) {
                        if (r != p && r != q) {
                            double arp = a[r][p], arq = a[r][q];
                            a[r][p] = a[p][r] = arp - s * (arq + tau * arp);
                            a[r][q] = a[q][r] = arq + s * (arp - tau * arq);
                        }
                    }
                    for (r = 0; r < 3; r++) {
                        double vrp = v[r][p], vrq = v[r][q];
                        v[r][p] = vrp - s * (vrq + tau * vrp);
                        v[r][q] = vrq + s * (vrp - tau * vrq);
                    }
                }
            }
        }
    }
    for (i = 0; i < 3; i++)
        lam[i] = a[i][i];
}

static const char *const axis_name[LEP_AXES] = { "fx", "fy", "fz", "mx", "my", "mz" };
static const char *const g_name[3] = { "gx", "gy", "gz" };

/* The first non-finite input, named in err; 0 when all are finite. */
static int find_non_finite(const double *gravity, const double *wrench, size_t n, char *err,
                           size_t errlen)
{
    size_t i;
    int k;
    for (i = 0; i < n; i++) {
        for (k = 0; k < 3; k++) {
            if (!isfinite(gravity[i * 3 + (size_t)k])) {
                lep_priv_set_err(err, errlen, "pose %zu: gravity %s is %g (not a finite number)",
                                 i + 1, g_name[k], gravity[i * 3 + (size_t)k]);
                return 1;
            }
        }
        for (k = 0; k < LEP_AXES; k++) {
            if (!isfinite(wrench[i * LEP_AXES + (size_t)k])) {
                lep_priv_set_err(err, errlen, "pose %zu: wrench %s is %g (not a finite number)",
                                 i + 1, axis_name[k], wrench[i * LEP_AXES + (size_t)k]);
                return 1;
            }
        }
    }
    return 0;
}

int lep_payload_identify_fit(const double *gravity, const double *wrench, size_t n,
                             lep_payload_fit *out, char *err, size_t errlen)
{
    double gm[3] = { 0 }, fm[3] = { 0 }, mm[3] = { 0 };
    double a[3][3] = { { 0 } }, b[3] = { 0 }, lam[3], v[3][3];
    double sdd = 0.0, sdf = 0.0, gsq = 0.0, lmin, mass, p[3] = { 0 };
    lep_payload_fit fit;
    size_t i;
    int j, k;

    if (err != NULL && errlen > 0)
        err[0] = '\0';
    if (gravity == NULL || wrench == NULL || out == NULL) {
        lep_priv_set_err(err, errlen, "no gravity, wrench or result given");
        return LEP_E_ARG;
    }
    if (n < LEP_PAYLOAD_MIN_POSES) {
        lep_priv_set_err(err, errlen,
                         "%zu poses: a payload needs at least %u, with gravity in directions "
                         "that are not all on one line",
                         n, LEP_PAYLOAD_MIN_POSES);
        return LEP_E_VALUE;
    }
    if (find_non_finite(gravity, wrench, n, err, errlen))
        return LEP_E_ARG;

    /* means */
    for (i = 0; i < n; i++) {
        for (k = 0; k < 3; k++) {
            gm[k] += gravity[i * 3 + (size_t)k];
            fm[k] += wrench[i * LEP_AXES + (size_t)k];
            mm[k] += wrench[i * LEP_AXES + 3u + (size_t)k];
        }
        gsq += dot(&gravity[i * 3], &gravity[i * 3]);
    }
    for (k = 0; k < 3; k++) {
        gm[k] /= (double)n;
        fm[k] /= (double)n;
        mm[k] /= (double)n;
    }
    gsq /= (double)n;

    /* Centred: F_i - mean F = m d_i, M_i - mean M = (m c) x d_i, d_i = g_i -
     * mean g. Normal equations: m = sum d.(F - mean F) / sum |d|^2, and
     * A (m c) = sum d x (M - mean M) with A = sum(|d|^2 I - d d^T). */
    for (i = 0; i < n; i++) {
        double d[3], e[3], dxe[3], dd;
        for (k = 0; k < 3; k++) {
            d[k] = gravity[i * 3 + (size_t)k] - gm[k];
            e[k] = wrench[i * LEP_AXES + 3u + (size_t)k] - mm[k];
        }
        dd = dot(d, d);
        sdd += dd;
        for (k = 0; k < 3; k++)
            sdf += d[k] * (wrench[i * LEP_AXES + (size_t)k] - fm[k]);
        cross(d, e, dxe);
        for (j = 0; j < 3; j++) {
            b[j] += dxe[j];
            for (k = 0; k < 3; k++)
                a[j][k] += (j == k ? dd : 0.0) - d[j] * d[k];
        }
    }

    /* Conditioning: A's smallest eigenvalue against the size of gravity. */
    {
        double w[3][3];
        memcpy(w, a, sizeof w);
        jacobi3(w, lam, v);
    }
    lmin = lam[0];
    for (k = 1; k < 3; k++)
        if (lam[k] < lmin)
            lmin = lam[k];
    fit.spread = gsq > 0.0 && lmin > 0.0 ? sqrt(lmin / ((double)n * gsq)) : 0.0;
    if (!(fit.spread >= LEP_PAYLOAD_MIN_SPREAD)) {
        lep_priv_set_err(err, errlen,
                         "the %zu gravity vectors spread %.3g < %g: too few distinct directions "
                         "(they lie on or near one line); tilt the tool about two different axes "
                         "between poses",
                         n, fit.spread, LEP_PAYLOAD_MIN_SPREAD);
        return LEP_E_VALUE;
    }

    mass = sdf / sdd;
    if (!(mass > 0.0)) {
        lep_priv_set_err(err, errlen,
                         "the poses give a mass of %.6g kg, not positive: no payload, or gravity "
                         "given with the wrong sign or in another frame than the sensor's",
                         mass);
        return LEP_E_VALUE;
    }

    /* m c = V diag(1/lam) V^T b */
    for (k = 0; k < 3; k++) {
        double proj = v[0][k] * b[0] + v[1][k] * b[1] + v[2][k] * b[2];
        for (j = 0; j < 3; j++)
            p[j] += v[j][k] * proj / lam[k];
    }

    fit.payload.mass_kg = mass;
    {
        double pxg[3];
        cross(p, gm, pxg);
        for (k = 0; k < 3; k++) {
            fit.payload.com_m[k] = p[k] / mass;
            fit.force_bias_N[k] = fm[k] - mass * gm[k];
            fit.torque_bias_Nm[k] = mm[k] - pxg[k];
        }
    }

    /* residuals of the fitted model at each pose */
    {
        double bias[LEP_AXES];
        memcpy(bias, fit.force_bias_N, sizeof fit.force_bias_N);
        memcpy(bias + 3, fit.torque_bias_Nm, sizeof fit.torque_bias_Nm);
        for (k = 0; k < LEP_AXES; k++)
            fit.residual[k] = 0.0;
        for (i = 0; i < n; i++) {
            double model[LEP_AXES];
            (void)lep_payload_wrench_p(&fit.payload, &gravity[i * 3], model);
            for (k = 0; k < LEP_AXES; k++) {
                double r = wrench[i * LEP_AXES + (size_t)k] - model[k] - bias[k];
                fit.residual[k] += r * r;
            }
        }
    }
    for (k = 0; k < LEP_AXES; k++)
        fit.residual[k] = sqrt(fit.residual[k] / (double)n);
    fit.poses = n;
    *out = fit;
    return LEP_OK;
}

/* ---- the flat form (leptrino/payload.h) ---- */

double lep_standard_gravity(void)
{
    return LEP_STANDARD_GRAVITY;
}

double lep_payload_min_spread(void)
{
    return LEP_PAYLOAD_MIN_SPREAD;
}

int lep_payload_wrench(const double payload[4], const double gravity[3], double wrench[6])
{
    lep_payload p;
    if (payload == NULL)
        return LEP_E_ARG;
    p.mass_kg = payload[0];
    memcpy(p.com_m, payload + 1, sizeof p.com_m);
    return lep_payload_wrench_p(&p, gravity, wrench);
}

int lep_payload_identify(const double *gravity, const double *wrench, size_t n, double *fit,
                         size_t nfit, char *err, size_t errlen)
{
    lep_payload_fit r;
    double f[LEP_FIT_COUNT];
    int rc;
    if (fit == NULL && nfit > 0) {
        lep_priv_set_err(err, errlen, "payload: no array for the fit");
        return LEP_E_ARG;
    }
    rc = lep_payload_identify_fit(gravity, wrench, n, &r, err, errlen);
    if (rc != LEP_OK)
        return rc;
    f[LEP_FIT_PAYLOAD] = r.payload.mass_kg;
    memcpy(f + LEP_FIT_PAYLOAD + 1, r.payload.com_m, sizeof r.payload.com_m);
    memcpy(f + LEP_FIT_FORCE_BIAS_N, r.force_bias_N, sizeof r.force_bias_N);
    memcpy(f + LEP_FIT_TORQUE_BIAS_NM, r.torque_bias_Nm, sizeof r.torque_bias_Nm);
    memcpy(f + LEP_FIT_RESIDUAL, r.residual, sizeof r.residual);
    f[LEP_FIT_SPREAD] = r.spread;
    f[LEP_FIT_POSES] = (double)r.poses;
    memcpy(fit, f, sizeof(double) * (nfit < LEP_FIT_COUNT ? nfit : LEP_FIT_COUNT));
    return LEP_OK;
}
