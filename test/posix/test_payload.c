/* Payload: the gravity wrench, identification from synthetic poses (known
 * payload, bias and noise; against an independent least-squares solution),
 * refusals (degenerate poses, NaN/inf), poses read back from recordings, and
 * the virtual sensor carrying a payload at four orientations, identified. */
#define _DEFAULT_SOURCE

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "leptrino/error.h"
#include "leptrino/output.h"
#include "leptrino/payload.h"
#include "leptrino/session.h"
#include "leptrino/sim.h"
#include "host_os.h"
#include "struct_api.h"
#include "rng.h"
#include "unity.h"

#define G0 LEP_STANDARD_GRAVITY
#define MAXP 16

static char err[256];
static char dir[64];

void setUp(void)
{
    err[0] = '\0';
    snprintf(dir, sizeof dir, "/tmp/lep-test-payload-XXXXXX");
    TEST_ASSERT_NOT_NULL(lep_test_mkdtemp(dir));
}

void tearDown(void)
{
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    TEST_ASSERT_EQUAL_INT(0, system(cmd));
}

/* Approximately normal, zero mean, unit variance (sum of 12 uniforms). */
static double gauss(uint32_t *s)
{
    double sum = 0.0;
    int i;
    for (i = 0; i < 12; i++)
        sum += (double)rng_next(s) / 4294967296.0;
    return sum - 6.0;
}

/* A random unit vector times |g|. */
static void random_gravity(uint32_t *s, double g[3])
{
    double n;
    do {
        int k;
        for (k = 0; k < 3; k++)
            g[k] = gauss(s);
        n = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    } while (n < 0.1);
    g[0] *= G0 / n;
    g[1] *= G0 / n;
    g[2] *= G0 / n;
}

/* Synthetic means at n poses: the model plus Gaussian noise. */
static void synth(const lep_payload *p, const double fb[3], const double mb[3], const double *g,
                  size_t n, double sf, double sm, uint32_t *s, double *w)
{
    size_t i;
    int k;
    for (i = 0; i < n; i++) {
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_payload_wrench_p(p, &g[i * 3], &w[i * 6]));
        for (k = 0; k < 3; k++) {
            w[i * 6 + (size_t)k] += fb[k] + sf * gauss(s);
            w[i * 6 + 3u + (size_t)k] += mb[k] + sm * gauss(s);
        }
    }
}

/* ---- an independent reference: the 10-parameter least squares solved by
 * Gaussian elimination of the normal equations (x = m, F_b, m c, M_b) ---- */
static void reference_fit(const double *g, const double *w, size_t n, double x[10])
{
    double ata[10][11];
    size_t i;
    int r, c, k;
    memset(ata, 0, sizeof ata);
    for (i = 0; i < n; i++) {
        const double *gi = &g[i * 3];
        double rows[6][10];
        memset(rows, 0, sizeof rows);
        for (k = 0; k < 3; k++) { /* F_k = m g_k + Fb_k */
            rows[k][0] = gi[k];
            rows[k][1 + k] = 1.0;
            rows[3 + k][7 + k] = 1.0; /* M_k = (p x g)_k + Mb_k */
        }
        /* (p x g)_x = py gz - pz gy; _y = pz gx - px gz; _z = px gy - py gx */
        rows[3][5] = gi[2];
        rows[3][6] = -gi[1];
        rows[4][6] = gi[0];
        rows[4][4] = -gi[2];
        rows[5][4] = gi[1];
        rows[5][5] = -gi[0];
        for (k = 0; k < 6; k++) {
            for (r = 0; r < 10; r++) {
                for (c = 0; c < 10; c++)
                    ata[r][c] += rows[k][r] * rows[k][c];
                ata[r][10] += rows[k][r] * w[i * 6 + (size_t)k];
            }
        }
    }
    for (c = 0; c < 10; c++) {
        int piv = c;
        for (r = c + 1; r < 10; r++)
            if (fabs(ata[r][c]) > fabs(ata[piv][c]))
                piv = r;
        for (k = 0; k < 11; k++) {
            double t = ata[c][k];
            ata[c][k] = ata[piv][k];
            ata[piv][k] = t;
        }
        for (r = 0; r < 10; r++) {
            double f;
            if (r == c)
                continue;
            f = ata[r][c] / ata[c][c];
            for (k = c; k < 11; k++)
                ata[r][k] -= f * ata[c][k];
        }
    }
    for (r = 0; r < 10; r++)
        x[r] = ata[r][10] / ata[r][r];
}

static void test_wrench_is_the_model(void)
{
    lep_payload p = { 2.0, { 0.1, 0.0, 0.05 } };
    double g[3] = { 0, 0, -G0 }, w[6];
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_payload_wrench_p(&p, g, w));
    TEST_ASSERT_EQUAL_DOUBLE(0.0, w[0]);
    TEST_ASSERT_EQUAL_DOUBLE(-2.0 * G0, w[2]);
    /* c x F = (0.1, 0, 0.05) x (0, 0, -2g) = (0, 0.2 g, 0) */
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, 0.0, w[3]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, 0.2 * G0, w[4]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, 0.0, w[5]);
    p.mass_kg = -1.0;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_payload_wrench_p(&p, g, w));
    p.mass_kg = 1.0;
    g[1] = NAN;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_payload_wrench_p(&p, g, w));
    g[1] = 0.0;
    p.com_m[2] = INFINITY;
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_payload_wrench_p(&p, g, w));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_payload_wrench_p(NULL, g, w));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_payload_wrench_p(&p, NULL, w));
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_payload_wrench_p(&p, g, NULL));
}

/* Exact data: the payload and biases come back to rounding. */
static void test_identify_exact(void)
{
    lep_payload p = { 1.234, { 0.012, -0.034, 0.056 } };
    double fb[3] = { 3.1, -2.2, 5.0 }, mb[3] = { 0.11, -0.07, 0.2 };
    double g[3 * 3] = { 0, 0, -G0, G0, 0, 0, 0, G0, 0 }, w[3 * 6];
    lep_payload_fit f;
    uint32_t s = 1;
    int k;
    synth(&p, fb, mb, g, 3, 0.0, 0.0, &s, w);
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_payload_identify_fit(g, w, 3, &f, err, sizeof err),
                                  err);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, p.mass_kg, f.payload.mass_kg);
    for (k = 0; k < 3; k++) {
        TEST_ASSERT_DOUBLE_WITHIN(1e-12, p.com_m[k], f.payload.com_m[k]);
        TEST_ASSERT_DOUBLE_WITHIN(1e-12, fb[k], f.force_bias_N[k]);
        TEST_ASSERT_DOUBLE_WITHIN(1e-12, mb[k], f.torque_bias_Nm[k]);
    }
    for (k = 0; k < 6; k++)
        TEST_ASSERT_DOUBLE_WITHIN(1e-12, 0.0, f.residual[k]);
    TEST_ASSERT_EQUAL_size_t(3, f.poses);
    TEST_ASSERT_TRUE(f.spread > 0.5);
}

/* Noisy poses, many draws: within 1 % and 2 mm, equal to the independent
 * least-squares solution, residuals at the noise level. */
static void test_identify_noisy_matches_reference(void)
{
    uint32_t s = 12345;
    int trial, k;
    for (trial = 0; trial < 200; trial++) {
        size_t n = 4 + (size_t)(rng_next(&s) % 9), i;
        double g[MAXP * 3], w[MAXP * 6], x[10];
        double fb[3], mb[3], sf = 0.05, sm = 0.001;
        lep_payload p;
        lep_payload_fit f;
        p.mass_kg = 0.5 + 4.5 * (double)rng_next(&s) / 4294967296.0;
        for (k = 0; k < 3; k++) {
            p.com_m[k] = 0.1 * gauss(&s);
            fb[k] = 5.0 * gauss(&s);
            mb[k] = 0.3 * gauss(&s);
        }
        for (i = 0; i < n; i++)
            random_gravity(&s, &g[i * 3]);
        synth(&p, fb, mb, g, n, sf, sm, &s, w);
        if (lep_payload_identify_fit(g, w, n, &f, err, sizeof err) != LEP_OK) {
            /* random poses may be too close to one line: then refused, never wrong */
            TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "too few distinct directions"), err);
            continue;
        }
        reference_fit(g, w, n, x);
        TEST_ASSERT_DOUBLE_WITHIN(1e-9 * x[0], x[0], f.payload.mass_kg);
        for (k = 0; k < 3; k++) {
            TEST_ASSERT_DOUBLE_WITHIN(1e-9, x[1 + k], f.force_bias_N[k]);
            TEST_ASSERT_DOUBLE_WITHIN(1e-9, x[4 + k] / x[0], f.payload.com_m[k]);
            TEST_ASSERT_DOUBLE_WITHIN(1e-9, x[7 + k], f.torque_bias_Nm[k]);
        }
        if (f.spread > 0.3) {
            TEST_ASSERT_DOUBLE_WITHIN(0.01 * p.mass_kg, p.mass_kg, f.payload.mass_kg);
            for (k = 0; k < 3; k++)
                TEST_ASSERT_DOUBLE_WITHIN(0.002, p.com_m[k], f.payload.com_m[k]);
        }
        for (k = 0; k < 3; k++) {
            TEST_ASSERT_TRUE(f.residual[k] < 3 * sf);
            TEST_ASSERT_TRUE(f.residual[3 + k] < 3 * sm);
        }
    }
}

/* The case: four well-spread poses, noise, 1 % and 2 mm. */
static void test_identify_four_poses_with_noise(void)
{
    lep_payload p = { 0.85, { -0.004, 0.015, 0.072 } };
    double fb[3] = { -12.0, 4.0, 30.0 }, mb[3] = { 0.5, -0.25, 0.04 };
    const double r = G0 / sqrt(2.0);
    double g[4 * 3] = { 0, 0, -G0, r, 0, -r, 0, r, -r, -r, -r * 0.5, -r * 0.5 }, w[4 * 6];
    lep_payload_fit f;
    uint32_t s = 99;
    int k;
    synth(&p, fb, mb, g, 4, 0.03, 0.001, &s, w);
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_payload_identify_fit(g, w, 4, &f, err, sizeof err),
                                  err);
    TEST_ASSERT_DOUBLE_WITHIN(0.01 * p.mass_kg, p.mass_kg, f.payload.mass_kg);
    for (k = 0; k < 3; k++)
        TEST_ASSERT_DOUBLE_WITHIN(0.002, p.com_m[k], f.payload.com_m[k]);
}

static void expect_refused(const double *g, const double *w, size_t n, int code, const char *needle)
{
    lep_payload_fit f, before;
    memset(&f, 0x5A, sizeof f);
    before = f;
    TEST_ASSERT_EQUAL_INT_MESSAGE(code, lep_payload_identify_fit(g, w, n, &f, err, sizeof err),
                                  err);
    TEST_ASSERT_EQUAL_MEMORY(&before, &f, sizeof f); /* untouched */
    TEST_ASSERT_NULL_MESSAGE(strchr(err, '\n'), err);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, needle), err);
}

static void test_degenerate_sets_refused(void)
{
    lep_payload p = { 1.0, { 0.0, 0.0, 0.1 } };
    double zero[3] = { 0 };
    double g[6 * 3], w[6 * 6];
    uint32_t s = 7;
    int i;
    /* fewer than three */
    double g2[2 * 3] = { 0, 0, -G0, G0, 0, 0 };
    synth(&p, zero, zero, g2, 2, 0, 0, &s, w);
    expect_refused(g2, w, 2, LEP_E_VALUE, "at least 3");
    expect_refused(g2, w, 0, LEP_E_VALUE, "at least 3");
    /* six poses, one gravity: turning about the vertical changes nothing */
    for (i = 0; i < 6; i++) {
        g[i * 3] = 0;
        g[i * 3 + 1] = 0;
        g[i * 3 + 2] = -G0;
    }
    synth(&p, zero, zero, g, 6, 0.01, 0.001, &s, w);
    expect_refused(g, w, 6, LEP_E_VALUE, "too few distinct directions");
    /* up and down only: all on one line (the com along it is unknowable) */
    for (i = 0; i < 6; i++)
        g[i * 3 + 2] = (i % 2) ? G0 : -G0;
    synth(&p, zero, zero, g, 6, 0.01, 0.001, &s, w);
    expect_refused(g, w, 6, LEP_E_VALUE, "too few distinct directions");
    /* three distinct directions within half a degree: ill-conditioned */
    for (i = 0; i < 3; i++) {
        double a = 0.5 * 3.14159265358979 / 180.0;
        g[i * 3] = i == 1 ? G0 * sin(a) : 0.0;
        g[i * 3 + 1] = i == 2 ? G0 * sin(a) : 0.0;
        g[i * 3 + 2] = -G0 * (i == 0 ? 1.0 : cos(a));
    }
    synth(&p, zero, zero, g, 3, 0.0, 0.0, &s, w);
    expect_refused(g, w, 3, LEP_E_VALUE, "too few distinct directions");
    /* ... the same at 10 degrees is fine */
    for (i = 0; i < 3; i++) {
        double a = 10.0 * 3.14159265358979 / 180.0;
        g[i * 3] = i == 1 ? G0 * sin(a) : 0.0;
        g[i * 3 + 1] = i == 2 ? G0 * sin(a) : 0.0;
        g[i * 3 + 2] = -G0 * (i == 0 ? 1.0 : cos(a));
    }
    {
        lep_payload_fit f;
        synth(&p, zero, zero, g, 3, 0.0, 0.0, &s, w);
        TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK,
                                      lep_payload_identify_fit(g, w, 3, &f, err, sizeof err), err);
        TEST_ASSERT_DOUBLE_WITHIN(1e-9, 1.0, f.payload.mass_kg);
        TEST_ASSERT_DOUBLE_WITHIN(1e-9, 0.1, f.payload.com_m[2]);
    }
    /* gravity given with the wrong sign: a negative mass is refused */
    for (i = 0; i < 9; i++)
        g[i] = -g[i];
    expect_refused(g, w, 3, LEP_E_VALUE, "not positive");
    /* no payload at all */
    memset(w, 0, sizeof w);
    expect_refused(g, w, 3, LEP_E_VALUE, "not positive");
}

static void test_non_finite_and_null_refused(void)
{
    lep_payload p = { 1.0, { 0.0, 0.0, 0.1 } };
    double zero[3] = { 0 };
    double g[3 * 3] = { 0, 0, -G0, G0, 0, 0, 0, G0, 0 }, w[3 * 6];
    lep_payload_fit f;
    uint32_t s = 3;
    synth(&p, zero, zero, g, 3, 0, 0, &s, w);
    g[4] = NAN;
    expect_refused(g, w, 3, LEP_E_ARG, "pose 2: gravity gy is nan");
    g[4] = 0.0;
    w[2 * 6 + 5] = -INFINITY;
    expect_refused(g, w, 3, LEP_E_ARG, "pose 3: wrench mz is -inf");
    w[2 * 6 + 5] = 0.0;
    expect_refused(NULL, w, 3, LEP_E_ARG, "no gravity");
    expect_refused(g, NULL, 3, LEP_E_ARG, "no gravity");
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_payload_identify_fit(g, w, 3, NULL, NULL, 0));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_payload_identify_fit(g, w, 3, &f, NULL, 0));
}

/* ---- poses from recordings ---- */

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    TEST_ASSERT_NOT_NULL(f);
    fputs(text, f);
    fclose(f);
}

#define META_HEAD                                                                      \
    "# leptrino-metadata: {\"library_version\":\"0.1.0\",\"model\":\"PFS055YA501U6\"," \
    "\"rated\":{\"fx_N\":500,\"fy_N\":500,\"fz_N\":500,\"mx_Nm\":10,\"my_Nm\":10,\"mz_Nm\":8},"

static void test_pose_read_hand_made(void)
{
    char path[128];
    double m[6];
    uint64_t n = 0;
    snprintf(path, sizeof path, "%s/raw.csv", dir);
    write_file(path, META_HEAD "\"rotation\":[1,0,0,0,1,0,0,0,1],\"shift_m\":[0,0,0],"
                               "\"tared\":false,\"tare_counts\":[0,0,0,0,0,0],\"sim\":true}\n"
                               "t_s,fx_counts,fy_counts,fz_counts,mx_counts,my_counts,mz_counts\n"
                               "0.1,100,0,-200,10,0,5\n"
                               "# gap from=0.1 to=0.2 lost=3 reason=gap\n"
                               "0.2,300,0,-400,30,0,15\n");
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_payload_pose_read(path, m, &n, err, sizeof err), err);
    TEST_ASSERT_EQUAL_UINT64(2, n);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, 200 * 0.05, m[0]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, -300 * 0.05, m[2]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, 20 * 0.001, m[3]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, 10 * 0.0008, m[5]);

    /* SI columns, tared, with a re-tare in the middle: offsets added back */
    snprintf(path, sizeof path, "%s/si.csv", dir);
    write_file(path, META_HEAD "\"rotation\":[1,0,0,0,1,0,0,0,1],\"shift_m\":[0,0,0],"
                               "\"tared\":true,\"tare_counts\":[100,0,0,0,0,1000],\"sim\":true}\n"
                               "t_s,fx_N,fy_N,fz_N,mx_Nm,my_Nm,mz_Nm,status\n"
                               "# tare at=0.0 fx=100.0 fy=0 fz=0 mx=0 my=0 mz=1000.0\n"
                               "0.1,1,2,3,0.1,0.2,0.3,0\n"
                               "# tare at=0.15 fx=0 fy=0 fz=0 mx=0 my=0 mz=0\n"
                               "0.2,6,2,3,0.1,0.2,1.1,0");
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_payload_pose_read(path, m, &n, err, sizeof err), err);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, 6.0, m[0]); /* (1 + 5, 6 + 0) / 2 */
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, 1.1, m[5]); /* (0.3 + 0.8, 1.1 + 0) / 2 */

    /* refusals, each naming the file */
    snprintf(path, sizeof path, "%s/bad.csv", dir);
    write_file(path, "t_s,fx_N\n0.1,2\n");
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_payload_pose_read(path, m, &n, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "bad.csv:1: no '# leptrino-metadata:'"), err);
    write_file(path, "{\"metadata\":{}}\n");
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_payload_pose_read(path, m, &n, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "JSON lines"), err);
    write_file(path, META_HEAD "\"rotation\":[1,0,0,0,1,0,0,0,1],\"shift_m\":[0,0,0],"
                               "\"tared\":false,\"tare_counts\":[0,0,0,0,0,0]}\n"
                               "t_s,fx_N,fy_N,fz_N,mx_Nm,my_Nm,mz_Nm,status\n"
                               "0.1,1,2,3,0.1,0.2,0.3,4\n");
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_payload_pose_read(path, m, &n, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "bad.csv:3: an overloaded sample"), err);
    write_file(path, META_HEAD "\"rotation\":[1,0,0,0,1,0,0,0,1],\"shift_m\":[0,0,0],"
                               "\"tared\":false,\"tare_counts\":[0,0,0,0,0,0]}\n"
                               "t_s,fx_N,fy_N,fz_N,mx_Nm,my_Nm,mz_Nm\n"
                               "0.1,1,2,nan,0.1,0.2,0.3\n");
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_payload_pose_read(path, m, &n, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "not a number"), err);
    write_file(path, META_HEAD "\"rotation\":[1,0,0,0,1,0,0,0,1],\"shift_m\":[0,0,0],"
                               "\"tared\":false,\"tare_counts\":[0,0,0,0,0,0]}\n"
                               "t_s,status\n0.1,0\n");
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_payload_pose_read(path, m, &n, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "neither the SI columns"), err);
    write_file(path, META_HEAD "\"rotation\":[1,0,0,0,1,0,0,0,1],\"shift_m\":[0,0,0],"
                               "\"tared\":false,\"tare_counts\":[0,0,0,0,0,0]}\n"
                               "t_s,fx_N,fy_N,fz_N,mx_Nm,my_Nm,mz_Nm\n");
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_payload_pose_read(path, m, &n, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "no data rows"), err);
    write_file(path, META_HEAD "\"rotation\":[1,0,0],\"shift_m\":[0,0,0]}\n");
    TEST_ASSERT_EQUAL_INT(LEP_E_VALUE, lep_payload_pose_read(path, m, &n, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "metadata without"), err);
    snprintf(path, sizeof path, "%s/missing.csv", dir);
    TEST_ASSERT_EQUAL_INT(LEP_E_NOT_FOUND, lep_payload_pose_read(path, m, &n, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "missing.csv"), err);
    TEST_ASSERT_EQUAL_INT(LEP_E_ARG, lep_payload_pose_read(NULL, m, &n, err, sizeof err));
}

/* ---- the virtual sensor carrying a payload ---- */

/* Record `seconds` of a virtual sensor at gravity g into path through the
 * session and its writer, with the given tare and output frame. */
static void record_pose(const char *path, const char *payload, const double g[3], unsigned tare,
                        const double rpy[3], const double shift[3], unsigned columns)
{
    lep_session_options o;
    lep_session *s;
    lep_output_options oo;
    lep_output *w;
    char gtext[96];
    double t[600], si[600 * 6], zeroed[600 * 6];
    int16_t raw[600 * 6];
    uint8_t status[600], flags[600];
    lep_session_batch b;
    int idx;
    uint64_t got = 0;

    lep_session_options_init(&o);
    o.use_sim = true;
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_option_set(&o.sim, "amplitude", "0", err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_option_set(&o.sim, "noise", "0.002", err, sizeof err));
    TEST_ASSERT_EQUAL_INT_MESSAGE(
        LEP_OK, lep_sim_option_set(&o.sim, "payload", payload, err, sizeof err), err);
    snprintf(gtext, sizeof gtext, "%.17g,%.17g,%.17g", g[0], g[1], g[2]);
    TEST_ASSERT_EQUAL_INT_MESSAGE(
        LEP_OK, lep_sim_option_set(&o.sim, "gravity", gtext, err, sizeof err), err);
    o.tare_samples = tare;
    o.count = 600;
    if (rpy != NULL)
        lep_rotation_from_rpy(rpy[0], rpy[1], rpy[2], o.rotation);
    if (shift != NULL)
        memcpy(o.shift_m, shift, sizeof o.shift_m);
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_session_open_so(&o, &s, err, sizeof err), err);
    lep_output_options_init(&oo);
    oo.columns = columns;
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_output_open_opts(path, &oo, &w, err, sizeof err),
                                  err);
    idx = lep_output_add_session(w, s, NULL);
    TEST_ASSERT_TRUE(idx >= 0);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_session_start(s));
    for (;;) {
        lep_session_event ev[16];
        size_t nev = 0;
        int rc;
        memset(&b, 0, sizeof b);
        b.cap = 600;
        b.t_mono = t;
        b.si = si;
        b.zeroed = zeroed;
        b.raw = raw;
        b.status = status;
        b.flags = flags;
        rc = lep_session_read_batch(s, &b, 1000);
        while (nev < 16 && lep_session_pop_event(s, &ev[nev]))
            nev++;
        TEST_ASSERT_EQUAL_INT(LEP_OK, lep_output_write_batch(w, idx, &b, 0, ev, nev));
        got += b.n;
        if (rc == LEP_E_END)
            break;
        TEST_ASSERT_TRUE_MESSAGE(rc == LEP_OK || rc == LEP_E_TIMEOUT, lep_strerror(rc));
    }
    TEST_ASSERT_EQUAL_UINT64(600, got);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_output_close(w));
    lep_session_close(s);
}

/* The virtual sensor reads the payload's gravity wrench through its rated
 * values (counts), exactly, at any gravity. */
static void test_sim_reads_the_payload(void)
{
    lep_sim_options o;
    lep_sim *sim;
    lep_sample smp;
    lep_rated rated;
    lep_payload p = { 2.5, { 0.02, -0.01, 0.12 } };
    double g[3] = { 3.0, -4.0, -8.0 }, w[6];
    int k;
    lep_sim_options_init(&o);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_option_set(&o, "constant", NULL, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_option_set(&o, "amplitude", "0", err, sizeof err));
    TEST_ASSERT_EQUAL_INT(
        LEP_OK, lep_sim_option_set(&o, "payload", "2.5,0.02,-0.01,0.12", err, sizeof err));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_option_set(&o, "gravity", "3,-4,-8", err, sizeof err));
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_sim_start_so(&o, &sim, err, sizeof err), err);
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_model_rated_f(o.model, &rated));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_sim_sample_at(sim, 5, 0, &smp));
    TEST_ASSERT_EQUAL_INT(LEP_OK, lep_payload_wrench_p(&p, g, w));
    for (k = 0; k < 6; k++) {
        double counts = w[k] / (double)rated.axis[k] * LEP_RAW_FULL_SCALE;
        TEST_ASSERT_DOUBLE_WITHIN(0.5, counts, (double)smp.raw[k]);
    }
    TEST_ASSERT_EQUAL_UINT8(0, smp.status);
    lep_sim_stop(sim);
}

/* Four orientations of the virtual sensor carrying a tool, recorded through
 * the session and writer (tared, rotated output, raw columns), read back as
 * poses and identified: 1 % and 2 mm. */
static void test_sim_four_poses_identified(void)
{
    const char *payload = "1.5,0.01,-0.02,0.08";
    const double r = G0 / sqrt(2.0);
    double g[4 * 3] = { 0, 0, -G0, r, 0, -r, 0, -r, -r, -r * 0.6, r * 0.5, -r * 0.9 };
    double w[4 * 6], rpy[3] = { 0.3, -0.2, 1.0 }, shift[3] = { 0.0, 0.05, 0.1 };
    lep_payload_fit f;
    int i, k;
    for (i = 0; i < 4; i++) {
        char path[160];
        uint64_t n = 0;
        snprintf(path, sizeof path, "%s/pose%d.csv", dir, i + 1);
        record_pose(path, payload, &g[i * 3], i == 1 || i == 2 ? 50u : 0u, i == 2 ? rpy : NULL,
                    i == 2 ? shift : NULL,
                    i == 3 ? (LEP_COL_RAW | LEP_COL_STATUS) : LEP_COL_DEFAULT);
        TEST_ASSERT_EQUAL_INT_MESSAGE(
            LEP_OK, lep_payload_pose_read(path, &w[i * 6], &n, err, sizeof err), err);
        TEST_ASSERT_EQUAL_UINT64(600, n);
    }
    TEST_ASSERT_EQUAL_INT_MESSAGE(LEP_OK, lep_payload_identify_fit(g, w, 4, &f, err, sizeof err),
                                  err);
    printf("sim, 4 poses x 600 samples: mass %.5f kg (1.5), com %.5f %.5f %.5f m "
           "(0.01 -0.02 0.08), spread %.3f, residual %.3g N %.3g N m\n",
           f.payload.mass_kg, f.payload.com_m[0], f.payload.com_m[1], f.payload.com_m[2], f.spread,
           f.residual[2], f.residual[5]);
    TEST_ASSERT_DOUBLE_WITHIN(0.015, 1.5, f.payload.mass_kg);
    TEST_ASSERT_DOUBLE_WITHIN(0.002, 0.01, f.payload.com_m[0]);
    TEST_ASSERT_DOUBLE_WITHIN(0.002, -0.02, f.payload.com_m[1]);
    TEST_ASSERT_DOUBLE_WITHIN(0.002, 0.08, f.payload.com_m[2]);
    for (k = 0; k < 3; k++) { /* the virtual sensor has no bias */
        TEST_ASSERT_DOUBLE_WITHIN(0.2, 0.0, f.force_bias_N[k]);
        TEST_ASSERT_DOUBLE_WITHIN(0.005, 0.0, f.torque_bias_Nm[k]);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_wrench_is_the_model);
    RUN_TEST(test_identify_exact);
    RUN_TEST(test_identify_noisy_matches_reference);
    RUN_TEST(test_identify_four_poses_with_noise);
    RUN_TEST(test_degenerate_sets_refused);
    RUN_TEST(test_non_finite_and_null_refused);
    RUN_TEST(test_pose_read_hand_made);
    RUN_TEST(test_sim_reads_the_payload);
    RUN_TEST(test_sim_four_poses_identified);
    return UNITY_END();
}
