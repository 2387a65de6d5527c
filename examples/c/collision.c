/*
 * Two equal adhesive spheres collide head-on, integrated with velocity Verlet on tabor's
 * Maugis-Dugdale force-overlap law (capi/include/tabor_dem.h): the coefficient of restitution
 * against the impact velocity, the energy each collision loses against the law's loop energy,
 * and the sticking velocity against the JKR estimate.
 *
 * Build and run (after `cargo build --release -p tabor-capi`):
 *   cc examples/c/collision.c -Icapi/include -Ltarget/release -ltabor_dem -lm -o collision
 *   LD_LIBRARY_PATH=target/release ./collision        (dry)
 *   LD_LIBRARY_PATH=target/release ./collision 0.5    (in air of 50% relative humidity)
 *
 * Polystyrene spheres, R = 10 um each (R* = 5 um), E = 3 GPa, nu = 0.35, 1050 kg/m^3:
 * w = 0.1 J/m^2, z0 = 0.3 nm (lambda about 10, near the JKR limit); in humid air a water
 * meniscus (contact angle 20 degrees) joins the solid's adhesion.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "tabor_dem.h"

/* One collision: the pair starts `gap` apart (beyond the force's reach) approaching at v0 (m/s,
 * relative velocity) and is followed until it is that far apart again, or until `t_max`.
 * Returns the restitution coefficient (0: stuck); *lost is the kinetic energy lost (J) and
 * *deepest the largest overlap (m). */
static double collide(const TaborDemLaw *law, double m_eff, double v0, double gap, double dt,
                      double t_max, double *lost, double *deepest) {
    uint8_t history = TABOR_DEM_FREE;
    double d = -gap, v = v0, f, k;
    *deepest = d;
    if (tabor_dem_law_eval(law, d, &history, &f, &k) < 0) return NAN;
    double a = -f / m_eff; /* f > 0 pushes the spheres apart: the overlap decelerates */
    for (double t = 0.0; t < t_max; t += dt) {
        d += v * dt + 0.5 * a * dt * dt;
        if (tabor_dem_law_eval(law, d, &history, &f, &k) < 0) return NAN;
        double a_next = -f / m_eff;
        v += 0.5 * (a + a_next) * dt;
        a = a_next;
        if (d > *deepest) *deepest = d;
        if (d <= -gap && v < 0.0 && history == TABOR_DEM_FREE) {
            *lost = 0.5 * m_eff * (v0 * v0 - v * v);
            return -v / v0;
        }
    }
    *lost = 0.5 * m_eff * v0 * v0;
    return 0.0;
}

int main(int argc, char **argv) {
    const double radius = 10e-6, density = 1050.0;
    const double humidity = argc > 1 ? atof(argv[1]) : 0.0;
    TaborDemPair pair = {
        .youngs_modulus1_pa = 3e9, .poisson_ratio1 = 0.35, .radius1_m = radius,
        .youngs_modulus2_pa = 3e9, .poisson_ratio2 = 0.35, .radius2_m = radius,
        .work_of_adhesion_j_m2 = 0.1, .dugdale_stress_pa = 0.0, .lj_range_m = 0.3e-9,
        .overlap_max_m = 2e-6, .relative_humidity = humidity, .contact_angle_deg = 20.0,
    };
    char error[256];
    TaborDemLaw *law = tabor_dem_law_new(&pair, error, sizeof error);
    if (!law) {
        fprintf(stderr, "error: %s\n", error);
        return 1;
    }
    TaborDemInfo info;
    tabor_dem_law_info(law, &info);
    const double mass = density * 4.0 / 3.0 * M_PI * radius * radius * radius;
    const double m_eff = mass / 2.0;
    /* Start (and end) twice as far apart as the farthest reach of the force: the attraction's
     * start, the jump-out and the non-contact branch's end. */
    double reach = fmax(-info.attraction_from_m, -info.jump_out_m);
    if (!isnan(info.non_contact_end_m)) reach = fmax(reach, -info.non_contact_end_m);
    const double gap = 2.0 * reach;
    printf("lambda %.6g, R* %.6g m, E* %.6g Pa, pull-off %.6g N, jump-in %.6g m, jump-out %.6g m\n",
           info.lambda, info.radius_m, info.reduced_modulus_pa, info.pulloff_force_n,
           info.jump_in_m, info.jump_out_m);
    printf("loop energy %.9e J, table error %.3g\n", info.loop_energy_j, info.table_error);
    if (info.meniscus_work_j_m2 > 0.0)
        printf("meniscus at RH %.3g: w %.6g J/m^2 over a height of %.6g m\n", humidity,
               info.meniscus_work_j_m2, info.meniscus_range_m);

    /* The sticking velocity: the pair sticks where the kinetic energy is at most the loop. */
    const double v_loop = sqrt(2.0 * info.loop_energy_j / m_eff);
    /* JKR's estimate (contact forming at zero overlap, released at the rigid-grip fold): the
     * loop 1.27494 pi w R* (pi^2 w^2 R* / K^2)^(1/3), i.e. 1.0348 (F_c^5 / (m*^3 R* E*^2))^(1/6)
     * with F_c = 1.5 pi w R*, for the solid's w alone (a meniscus adds its own loop). */
    const double fc = 1.5 * M_PI * pair.work_of_adhesion_j_m2 * info.radius_m;
    const double v_jkr = 1.0348 * pow(pow(fc, 5) / (pow(m_eff, 3) * info.radius_m *
                                                    pow(info.reduced_modulus_pa, 2)),
                                      1.0 / 6.0);
    printf("sticking velocity from the loop %.6g m/s; JKR estimate %.6g m/s (ratio %.4f)\n",
           v_loop, v_jkr, v_loop / v_jkr);

    printf("v0_m_s,restitution,energy_lost_j,loop_energy_j,deepest_overlap_m\n");
    const double factors[] = {0.5, 0.9, 0.99, 1.01, 1.1, 1.5, 2, 5, 10, 100};
    for (size_t i = 0; i < sizeof factors / sizeof factors[0]; i++) {
        double v0 = factors[i] * v_loop, lost = NAN, deepest = NAN;
        /* dt: 1/2000 of the time to cross the range at v0, at most 1/2000 of the contact time. */
        double dt = fmin(gap / v0, 2.87 * pow(m_eff * m_eff / (info.radius_m *
                         info.reduced_modulus_pa * info.reduced_modulus_pa * v0), 0.2)) / 2000.0;
        double e = collide(law, m_eff, v0, gap, dt, 2000.0 * gap / v0 + 1e3 * dt, &lost, &deepest);
        double loop = tabor_dem_law_loop_energy(law, deepest);
        printf("%.6e,%.6f,%.9e,%.9e,%.6e\n", v0, e, lost, e > 0.0 ? loop : NAN, deepest);
    }
    tabor_dem_law_free(law);
    return 0;
}
