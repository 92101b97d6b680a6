/* Duct: at the last step, where each injected particle is: deposited on which wall, still
   in the air, or gone through the outlet (what was injected and is neither). Written to
   `duct_census.csv`, one row per size, for duct_report.py; with depo's walls, the contacts
   and the time per call of the law written to the log. Serial runs only. */

#include "cs_defs.h"

#include <math.h>
#include <stdio.h>

#include "bft_error.h"
#include "cs_lagr.h"
#include "cs_lagr_particle.h"
#include "cs_lagr_prototypes.h"
#include "cs_parall.h"
#include "cs_time_step.h"

#include "bft_printf.h"
#include "depo_code_saturne.h"
#include "duct.h"

BEGIN_C_DECLS

void
cs_user_lagr_extra_operations(const cs_real_t  dt[])
{
  CS_UNUSED(dt);
  if (cs_glob_time_step->nt_cur != cs_glob_time_step->nt_max)
    return;
  if (cs_glob_n_ranks > 1)
    bft_error(__FILE__, __LINE__, 0, "duct: the census is written by serial runs only\n");

  /* Per size: floor, ceiling, sides, airborne. */
  long counts[DUCT_SIZES][4] = {{0}};
  cs_lagr_particle_set_t *p = cs_glob_lagr_particle_set;
  for (cs_lnum_t i = 0; i < p->n_particles; i++) {
    double d = cs_lagr_particles_get_real(p, i, CS_LAGR_DIAMETER);
    int s = 0;
    while (s < DUCT_SIZES - 1 && fabs(d - duct_diameters[s]) > 1e-3 * duct_diameters[s])
      s++;
    const cs_real_t *x = cs_lagr_particles_attr_const(p, i, CS_LAGR_COORDS);
    int where = 3;
    if (cs_lagr_particles_get_flag(p, i, CS_LAGR_PART_DEPOSITED)) {
      /* The nearest wall of the 0.2 m x 0.2 m section. */
      double floor = x[2], ceiling = 0.2 - x[2], side = fmin(x[1], 0.2 - x[1]);
      where = (floor <= ceiling && floor <= side) ? 0 : (ceiling <= side ? 1 : 2);
    }
    counts[s][where] += 1;
  }
  long injected = (long)DUCT_PER_STEP * (DUCT_LAST_STEP - DUCT_FIRST_STEP + 1);
  FILE *f = fopen("duct_census.csv", "w");
  fprintf(f, "walls,diameter,injected,floor,ceiling,sides,airborne,outlet\n");
  for (int s = 0; s < DUCT_SIZES; s++) {
    long out = injected - counts[s][0] - counts[s][1] - counts[s][2] - counts[s][3];
    fprintf(f, "%s,%g,%ld,%ld,%ld,%ld,%ld,%ld\n", duct_walls_mode() == DUCT_DEPO ? "depo" : "sink",
            duct_diameters[s], injected, counts[s][0], counts[s][1], counts[s][2],
            counts[s][3], out);
  }
  fclose(f);

  if (duct_walls_mode() == DUCT_DEPO) {
    unsigned long long n[4];
    depo_cs_counts(n);
    unsigned long long calls = n[0] + n[1] + n[2] + n[3];
    bft_printf("depo: %llu contacts (%llu rebound, %llu captured, %llu skipped, %llu invalid), "
               "%.0f ns per call of depo_apply_f64\n",
               calls, n[0], n[1], n[2], n[3], 1e9 * depo_cs_apply_time() / (double)(calls ? calls : 1));
  }
}

END_C_DECLS
